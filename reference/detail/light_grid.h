#pragma once
// Internal to reference/exact_image.cpp: the count tiles' candidate lists for one point light,
// read from a grid in the light's view instead of a walk of the box tree (docs/diff.md, "The
// light grid").
//
// Seen from a point light L, the whole open segment P -> L projects to one point, P's own
// projection: a triangle that the segment meets contains that point in its projection, and has
// a point strictly nearer to L than P. Where the scene's box lies strictly on one side of L
// along some axis a (L above a floor, say), every point p of the scene projects through L onto
// a plane perpendicular to a,
//   u = (p_b - L_b) / (p_a - L_a),   v = (p_c - L_c) / (p_a - L_a)   (b, c the other axes),
// with a denominator of one sign throughout. That plane is cut into cells, and each cell lists
// the triangles whose projection may meet it, nearest to L first. A box of hit points asks the
// cells its projection meets, and reads each list only as far as its triangles can be nearer to
// L than the box's farthest point.
//
// Nothing here decides a count: the lists only have to hold every triangle a segment can meet.
// Each projected coordinate is computed in round-to-nearest doubles as (n - ln) * (1 / (d - ld)),
// whose four roundings put it within 2^-50 of its value relative (plus 2^-1074 where it
// underflows); every interval is widened by 2^-48 relative plus 2^-1000, so it encloses the
// exact projections. A
// triangle's projection lies in the box of its vertices' projections (a central projection
// keeps segments straight on one side of L), a box's in the box of its corners' (u is
// linear-fractional with a denominator of one sign, so its extremes over a box are at corners).
// Cells are indexed by one monotone function of u (and v), so two intervals that meet always
// share a cell. The depth test compares input coordinates with keys rounded up (no decision
// rests on a rounding the other way).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/box.h"
#include "core/huge_page_advice.h"
#include "core/soup.h"

namespace shadowcert::detail {

class LightGrid {
 public:
  // Each list holds triangle ids in ascending order, each with its key(id): the triangle's
  // nearest coordinate along the axis (negated where the scene lies above the light: larger is
  // nearer), rounded up to a float, so that a key at or below a box's threshold still shows the
  // triangle farther than the box.
  // The cells a box's projection may meet (columns [c0, c1], rows [r0, r1]), and the key a
  // triangle must exceed to have a point strictly nearer to the light than some point of the
  // box (as every point of the open segment from the box to the light is).
  struct Reach {
    std::uint32_t c0, c1, r0, r1;
    double threshold;
    [[nodiscard]] bool one_cell() const { return c0 == c1 && r0 == r1; }
    [[nodiscard]] std::size_t cells() const { return std::size_t{c1 - c0 + 1} * (r1 - r0 + 1); }
  };

  // The grid of `soup`'s triangles that `listed` selects (per triangle, nonzero: listed), for
  // the point light `light`; `scene`: a box holding every vertex of `soup`. nullopt where no axis
  // has `scene` strictly on one side of the light, where a projection is not finite (coordinates
  // near the double range's ends), or where its lists would be long (kMostBigTriangles,
  // kMostEntriesPerTriangle): the caller then walks its box tree. Throws std::invalid_argument
  // when `listed` has not one entry per triangle.
  static std::optional<LightGrid> build(const Soup& soup, const Vec3& light, const Box& scene,
                                        std::span<const std::uint8_t> listed);

  // The reach of [lo, hi]; nullopt where the box is not strictly on the scene's side of the
  // light (the caller walks its tree). Every listed triangle that a segment from a point of the
  // box to the light can meet is in big() or in the list of a cell of the reach, with a key
  // above its threshold.
  [[nodiscard]] std::optional<Reach> reach(const Vec3& lo, const Vec3& hi) const;
  // The list of the cell in `column` and `row` (within the reach's bounds), and the triangles
  // too wide for the cells, which every reach holds.
  [[nodiscard]] std::span<const std::uint32_t> list(std::uint32_t column, std::uint32_t row) const {
    return list(std::size_t{row} * columns_ + column);
  }
  [[nodiscard]] std::span<const std::uint32_t> big() const { return big_; }
  // The key of a listed triangle.
  [[nodiscard]] float key(std::uint32_t id) const { return keys_[id]; }

  // Calls visit(id) for every entry of `reach`'s lists (big() first) with a key above its
  // threshold; a triangle listed in several of its cells comes once for each.
  template <typename Visit>
  void visit(const Reach& reach, Visit&& visit) const {
    const auto read = [&](std::span<const std::uint32_t> list) {
      for (const std::uint32_t id : list) {
        if (keys_[id] > reach.threshold) visit(id);
      }
    };
    read(big_);
    for_each_cell(reach, [&](std::size_t cell) { read(list(cell)); });
  }

  // Whether some cell of `reach` lists a triangle with a key above its threshold: false where
  // visit(reach) reports big()'s entries alone. The reach of a box inside the box of `reach`
  // then lists none either (its cells are among these, its threshold no lower).
  [[nodiscard]] bool cells_list_any(const Reach& reach) const {
    for (std::uint32_t y = reach.r0; y <= reach.r1; ++y)
      for (std::uint32_t x = reach.c0; x <= reach.c1; ++x)
        for (const std::uint32_t id : list(std::size_t{y} * columns_ + x))
          if (keys_[id] > reach.threshold) return true;
    return false;
  }

  // Triangles whose box of cells covers more than half of the cells (a floor under a mesh) are
  // listed once, apart (big()), not in each cell; at most kMostBigTriangles of them (each query
  // reads them all).
  static constexpr std::size_t kMostBigTriangles = 32;
  // At most this many cell entries per listed triangle (long triangles across many cells),
  // else no grid.
  static constexpr std::size_t kMostEntriesPerTriangle = 32;

  [[nodiscard]] std::size_t cells() const { return std::size_t{columns_} * rows_; }

 private:
  // Calls f(cell) for each cell of `r`, row-major (cell: the index into first_).
  template <typename F>
  void for_each_cell(const Reach& r, F&& f) const {
    for (std::uint32_t y = r.r0; y <= r.r1; ++y)
      for (std::uint32_t x = r.c0; x <= r.c1; ++x) f(std::size_t{y} * columns_ + x);
  }
  [[nodiscard]] std::span<const std::uint32_t> list(std::size_t cell) const {
    return {entries_.data() + first_[cell], entries_.data() + first_[cell + 1]};
  }
  [[nodiscard]] std::uint32_t column(double u) const;
  [[nodiscard]] std::uint32_t row(double v) const;

  int axis_ = 0, b_ = 1, c_ = 2;
  int side_ = -1;  // the sign of p_a - L_a over the scene
  Vec3 light_{};
  double u0_ = 0.0, v0_ = 0.0, u_scale_ = 1.0, v_scale_ = 1.0;
  std::uint32_t columns_ = 1, rows_ = 1;
  std::vector<std::uint32_t> first_;  // per cell (row-major), its list's start in entries_; one more at the end
  HugePageBuffer<std::uint32_t> entries_;  // every cell's list, uninitialised until written
  std::vector<std::uint32_t> big_;
  std::vector<float> keys_;  // per triangle of the soup (a listed one's key)
};

}  // namespace shadowcert::detail
