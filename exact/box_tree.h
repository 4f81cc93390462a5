#pragma once
// Internal to exact/: a bounding-volume tree over closed axis-aligned boxes (a binary BVH of
// its own, binned-SAH built in parallel: exact/box_tree.cpp), queried with a segment or a ray:
// it reports every box the query meets, decided exactly on the doubles (CGAL's filtered
// Do_intersect_3 of Epick on each box a certified slab test cannot rule out), so a caller that bounds
// its objects by these boxes never loses a candidate. With LeafTest::skip it also reports
// boxes whose parent node the query meets but which it misses itself: a superset, for callers
// whose own exact test is cheaper than one more box test.
//
// The occluder count (casting triangles, exact/occluder_counter.cpp) and the chain crossings
// (caps and side pieces, exact/chain_crossings.cpp) both search with it; the exact image
// (reference/exact_image.cpp) finds first hits with its nearest-first ray query and counts from
// hit points known only as exact rationals with its dilated queries.
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <vector>

#include "core/box.h"
#include "core/soup.h"

namespace shadowcert::detail {

enum class LeafTest : bool { skip, exact };

class BoxTree {
 public:
  // Box i gets id i. Built now (in parallel, TBB); queries are const and run concurrently.
  BoxTree(const std::vector<Box>& boxes, LeafTest leaf_test);
  ~BoxTree();
  BoxTree(const BoxTree&) = delete;
  BoxTree& operator=(const BoxTree&) = delete;

  // Calls visit(id) for every box the closed segment from -> to meets (from != to), in no
  // particular order, until visit returns false.
  template <typename Visit>
  void segment_query(const Vec3& from, const Vec3& to, Visit&& visit) const {
    segment_query(from, to, erase(visit), &call<std::remove_reference_t<Visit>>);
  }
  // The same for the closed ray from `from` in direction `direction` (nonzero).
  template <typename Visit>
  void ray_query(const Vec3& from, const Vec3& direction, Visit&& visit) const {
    ray_query(from, direction, erase(visit), &call<std::remove_reference_t<Visit>>);
  }

  // The same queries for a segment (or ray) whose start is known only to lie in the box
  // from +- slack (slack >= 0 per axis, e.g. an interval enclosure of an exact rational point):
  // every box that the segment from any such start to `to` (or the ray along `direction`)
  // meets is reported. Those segments lie in the segment from -> to dilated by [-slack, slack]
  // per axis, so each box is dilated by slack and tested against the given segment (see
  // below: a superset, never a missed box). Equally, every box that any point within slack of
  // the segment lies in (the footprint pyramids of reference/detail/pixel_footprint.h).
  template <typename Visit>
  void dilated_segment_query(const Vec3& from, const Vec3& to, const Vec3& slack, Visit&& visit) const {
    dilated_segment_query(from, to, slack, erase(visit), &call<std::remove_reference_t<Visit>>);
  }
  // The dilated segment query's test of each box, over the boxes `ids` only (each below the
  // number of boxes), in their order: calls visit(id) for each listed box the query may meet,
  // until visit returns false. For a caller holding a list known to contain every box the
  // query meets (a cone's candidates), which would test each entry at a higher cost: the boxes
  // it passes on are the listed ones the walk would visit, a superset of those the dilated
  // segment meets. Throws std::invalid_argument for an id out of range.
  template <typename Visit>
  void dilated_segment_query(const Vec3& from, const Vec3& to, const Vec3& slack, std::span<const std::uint32_t> ids,
                             Visit&& visit) const {
    dilated_segment_query(from, to, slack, ids, erase(visit), &call<std::remove_reference_t<Visit>>);
  }
  template <typename Visit>
  void dilated_ray_query(const Vec3& from, const Vec3& direction, const Vec3& slack, Visit&& visit) const {
    dilated_ray_query(from, direction, slack, erase(visit), &call<std::remove_reference_t<Visit>>);
  }

  // First-hit search along the ray from + t direction, t >= 0 (direction nonzero): calls
  // visit(id) for the boxes the ray meets, the subtree whose box the ray enters first visited
  // first, and skips every subtree whose box the ray can only enter at a parameter t > *bound.
  // The visitor lowers *bound (through its own pointer) as it finds hits, and returns false to
  // stop. *bound may be +infinity.
  //
  // The dilated and nearest-first queries test boxes in plain double arithmetic with a
  // certified bound on every rounding error (the slab method, box_tree.cpp), so every box the
  // exact query meets (at some t <= *bound) is visited: a superset (boxes it just misses may
  // come too), never a missed box. Round-to-nearest is assumed, as everywhere in exact/ outside
  // an interval filter's scope.
  template <typename Visit>
  void nearest_first_ray_query(const Vec3& from, const Vec3& direction, const double* bound, Visit&& visit) const {
    nearest_first_ray_query(from, direction, bound, erase(visit), &call<std::remove_reference_t<Visit>>);
  }

 private:
  // The visitor travels as a pointer and a function that calls it (no CGAL in this header).
  using Callback = bool (*)(void* visit, std::uint32_t id);
  template <typename V>
  static void* erase(V& visit) {
    return const_cast<void*>(static_cast<const void*>(std::addressof(visit)));
  }
  template <typename V>
  static bool call(void* visit, std::uint32_t id) {
    return (*static_cast<V*>(visit))(id);
  }
  void segment_query(const Vec3& from, const Vec3& to, void* visit, Callback callback) const;
  void ray_query(const Vec3& from, const Vec3& direction, void* visit, Callback callback) const;
  void dilated_segment_query(const Vec3& from, const Vec3& to, const Vec3& slack, void* visit,
                             Callback callback) const;
  void dilated_segment_query(const Vec3& from, const Vec3& to, const Vec3& slack, std::span<const std::uint32_t> ids,
                             void* visit, Callback callback) const;
  void dilated_ray_query(const Vec3& from, const Vec3& direction, const Vec3& slack, void* visit,
                         Callback callback) const;
  void nearest_first_ray_query(const Vec3& from, const Vec3& direction, const double* bound, void* visit,
                               Callback callback) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shadowcert::detail
