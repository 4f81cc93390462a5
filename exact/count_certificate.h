#pragma once
// Certificate 2 of docs/definitions.md#certificates: occluder counts. For sample points B and a reference A with
// n(A) known, the signed crossings of segment AB with the chain must equal n(B) - n(A), where
// n(P) is computed directly: the number of triangles with s != 0 crossed by the open segment
// P -> light (the ray towards l for w = 0), by an AABB tree and exact segment/triangle tests.
// Every test is an orientation sign on the input doubles, so no far point is built; a zero
// sign that decides whether a segment meets a face is a degenerate configuration and the
// sample is re-drawn, never guessed (docs/definitions.md#count-certificate).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "exact/shadow_volume_chain.h"

namespace shadowcert {

struct CountSampling {
  std::uint64_t in_box = 1000;        // random points in the scene box enlarged by 10% per side
  std::uint64_t on_triangles = 1000;  // random points on the soup's triangles (barycentric)
  std::uint64_t seed = 1;
  std::vector<Vec3> user_points;      // checked as given; a degenerate one is reported, not moved
  std::uint32_t max_redraws = 64;     // per random sample before it is counted as skipped
};

struct CountFailure {
  Vec3 point{};
  std::int64_t expected = 0;  // n(B) - n(A) from the direct count
  std::int64_t crossed = 0;   // signed crossings of AB with the chain
};

struct CountCertificate {
  std::uint64_t checks = 0;    // samples whose count was compared
  std::uint64_t failures = 0;  // of them, disagreeing
  std::uint64_t redrawn = 0;   // random samples re-drawn because a sign was zero
  std::uint64_t skipped = 0;   // user points on a boundary, random ones past max_redraws
  std::vector<CountFailure> first_failures;  // at most 16, for reports
  double seconds = 0.0;
};

// The direct occluder count n(P) of docs/definitions.md#counts over the triangles with s != 0 of `soup`
// (signs exact); nullopt when P -> light touches a triangle's edge, vertex or plane, or P lies
// on a triangle: a boundary point whose count is undefined.
class OccluderCounter {
 public:
  OccluderCounter(const Soup& soup, const Light& light);
  ~OccluderCounter();
  OccluderCounter(OccluderCounter&&) noexcept;
  OccluderCounter& operator=(OccluderCounter&&) noexcept;

  [[nodiscard]] std::optional<std::uint32_t> count(const Vec3& point) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Signed crossings of the segment from -> to with the chain's faces (docs/definitions.md#count-certificate): +1 entering
// a face against its outward orientation, -1 leaving, so they sum to the change of the chain's
// winding number, n(to) - n(from) for a correct chain. nullopt when the segment touches a face's
// boundary or plane (a zero sign that matters). Tests every face: for single queries and tests.
[[nodiscard]] std::optional<std::int64_t> chain_crossings(const Soup& canonical, const Light& light,
                                                          const ShadowVolumeChain& chain, const Vec3& from,
                                                          const Vec3& to);

[[nodiscard]] CountCertificate certify_counts(const Soup& canonical, const Light& light,
                                              const ShadowVolumeChain& chain, const CountSampling& sampling);

}  // namespace shadowcert
