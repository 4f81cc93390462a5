#pragma once
// Which triangles of a welded soup are degenerate (docs/definitions.md#inputs, docs/definitions.md#orientation, docs/definitions.md#caster-diagnostics).
//
// A degenerate triangle spans no plane, so it casts nothing (docs/definitions.md#orientation: s = 0). Two
// kinds, told apart because the combinatorial diagnostics still see the edges of the
// second kind:
//   - RepeatedIndex: two of its three (welded) indices are equal: a point or a segment
//     by construction, with fewer than three edges.
//   - Collinear: three distinct welded points that are exactly collinear (CGAL's filtered
//     `collinear`, exact on doubles; no tolerance).
#include <cstdint>
#include <vector>

#include "core/soup.h"

namespace shadowcert {

enum class TriangleShape : std::uint8_t { Proper = 0, RepeatedIndex = 1, Collinear = 2 };

// One entry per triangle. Precondition: `welded` is exactly welded (weld_soup), so that
// distinct indices are distinct points; on an unwelded soup a triangle whose repeated
// position hides behind two indices is reported Collinear instead of RepeatedIndex.
[[nodiscard]] std::vector<TriangleShape> classify_triangle_shapes(const Soup& welded);

// True iff the three indices of `t` are pairwise distinct.
[[nodiscard]] inline bool has_distinct_indices(const Triangle& t) {
  return t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
}

}  // namespace shadowcert
