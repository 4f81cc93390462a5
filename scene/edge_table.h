#pragma once
// Plain (no CGAL): exact/ computes multiplicities over it and gpu/ uploads it as patches.
// The edge table of a canonical soup (scene/canonical_soup.h): every undirected edge {u, v}
// (u < v in the canonical vertex order, i.e. by index) with all its opposite vertices, any
// number of them (docs/definitions.md#counts). Triangles with a repeated index have no edges. Stored as
// compressed rows so that a method walks one contiguous array.
#include <array>
#include <cstdint>
#include <vector>

#include "core/soup.h"

namespace shadowcert {

struct EdgeTable {
  std::vector<std::array<std::uint32_t, 2>> edges;  // (u, v), u < v, sorted ascending
  // Edge e's opposite entries are [first_opposite[e], first_opposite[e + 1]); size edges + 1.
  // Within an edge the entries are in ascending triangle index, one per triangle (a triangle
  // with three distinct indices has three distinct edges); a duplicated triangle appears twice.
  std::vector<std::uint32_t> first_opposite;
  std::vector<std::uint32_t> opposite_vertex;    // the third vertex of the triangle
  std::vector<std::uint32_t> opposite_triangle;  // that triangle's index in the soup

  [[nodiscard]] std::size_t size() const { return edges.size(); }
};

// O(n log n) in the number of triangles. Precondition: `canonical` comes from canonical_soup
// (indices in range); throws std::invalid_argument("build_edge_table: ...") otherwise.
[[nodiscard]] EdgeTable build_edge_table(const Soup& canonical);

}  // namespace shadowcert
