#pragma once
// Internal to exact/: a bounding-volume tree over closed axis-aligned boxes (a CGAL AABB tree
// inside), queried with a segment or a ray: it reports every box the query meets, decided
// exactly on the doubles (CGAL's filtered Do_intersect_3 of Epick), so a caller that bounds
// its objects by these boxes never loses a candidate. With LeafTest::skip it also reports
// boxes whose parent node the query meets but which it misses itself: a superset, for callers
// whose own exact test is cheaper than one more box test.
//
// The occluder count (casting triangles, exact/occluder_counter.cpp) and the chain crossings
// (caps and side pieces, exact/chain_crossings.cpp) both search with it.
#include <array>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include "core/soup.h"

namespace shadowcert::detail {

struct ClosedBox {
  Vec3 lo{};
  Vec3 hi{};
};

enum class LeafTest : bool { skip, exact };

class BoxTree {
 public:
  // Box i gets id i. Built now (a Morton pre-order keeps the build cache-friendly); queries
  // are const and run concurrently.
  BoxTree(const std::vector<ClosedBox>& boxes, LeafTest leaf_test);
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

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shadowcert::detail
