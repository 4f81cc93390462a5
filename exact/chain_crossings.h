#pragma once
// Internal to exact/: signed crossings of finite segments with a shadow-volume chain
// (docs/definitions.md#count-certificate), for the occluder-count certificate.
//
// Crossing the chain's face F from A to B adds +1 when A lies on the side F's outward
// orientation points to (entering) and -1 otherwise (leaving), so that along AB the crossings
// sum to w(B) - w(A), the change of the chain's winding number, which is n(B) - n(A) for the
// exact chain. In orient signs, with start side sigma = orient(plane of F, A):
//   front cap t' = s(t) * t :  + s(t) * orient(a, b, c, A)
//   m copies of side quad (u, v, v_inf, u_inf) (normal -(u - l) x (v - l)) : - m * orient(L, u, v, A)
// Back caps lie at infinity: a finite segment never meets them.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "exact/count_sampling.h"
#include "exact/shadow_volume_chain.h"

namespace shadowcert::detail {

struct CrossingQuery {
  const Soup& canonical;
  const Light& light;
  const ShadowVolumeChain& chain;
};

// Signed crossings of segments inside a box with the chain, accelerated: a CGAL AABB tree over
// the faces' boxes, traversed per segment with exact segment/box tests. A cap's box is its
// vertices' box; a side face, unbounded, is cut to `clip` and into pieces along its rays of
// about `piece_length`, each bounded by interval arithmetic (rounded outwards): no candidate
// is ever lost. Built once; queries are const and run concurrently. The soup, light and chain
// of the query must outlive it.
class ChainCrossingIndex {
 public:
  ChainCrossingIndex(const CrossingQuery& query, const Box& clip, double piece_length);
  ~ChainCrossingIndex();
  ChainCrossingIndex(const ChainCrossingIndex&) = delete;
  ChainCrossingIndex& operator=(const ChainCrossingIndex&) = delete;

  // Crossings of from -> to, or nullopt when one of its face tests met a zero sign that
  // matters (a touch, exact/face_crossing.h). A segment leaving `clip` is tested against every
  // face instead (correct, slow).
  [[nodiscard]] std::optional<std::int64_t> crossings(const Vec3& from, const Vec3& to) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One segment against every face, no acceleration: for tests and single user queries.
[[nodiscard]] std::optional<std::int64_t> chain_crossings_of_segment(const CrossingQuery& query, const Vec3& from,
                                                                     const Vec3& to);

}  // namespace shadowcert::detail
