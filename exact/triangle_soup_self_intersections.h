#pragma once
// Exact self-intersections of a welded triangle soup (docs/definitions.md#caster-diagnostics).
//
// Two triangles of the soup form a self-intersecting pair iff they share a point that the
// vertices they have in common do not account for:
//   - no common vertex: the closed triangles meet at all;
//   - one common vertex v: they meet anywhere besides v;
//   - two common vertices (a common edge e): they overlap beyond e, i.e. the two opposite
//     vertices are coplanar with e and on the same side of it (a coplanar fold-back);
//   - three common vertices (a duplicate, either orientation): always.
// "Common" means equal welded index, which after exact welding (docs/definitions.md#inputs) is the same as
// equal position; so the input must come from weld_soup. This is CGAL 5.5's
// Polygon_mesh_processing::self_intersections rule (do_faces_intersect) with the mesh's
// halfedge adjacency replaced by index sharing, so soups need no face graph.
//
// Degenerate triangles (repeated index or exactly collinear, see degenerate_triangles.h) are
// skipped: they span no plane and cast nothing (docs/definitions.md#orientation), and the shared-vertex and
// shared-edge rules above assume each triangle spans a plane. All decisions are exact
// (CGAL Epick filtered predicates on the input doubles; no tolerance, no constructions).
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/soup.h"
#include "exact/degenerate_triangles.h"

namespace shadowcert {

using TrianglePair = std::pair<std::uint32_t, std::uint32_t>;  // first < second

// All self-intersecting pairs, sorted, each once. `shapes` is classify_triangle_shapes(welded)
// (passed in so that callers that already have it do not pay twice); throws
// std::invalid_argument if its size differs from the triangle count.
[[nodiscard]] std::vector<TrianglePair> find_self_intersecting_pairs(const Soup& welded,
                                                                     std::span<const TriangleShape> shapes);

// Convenience: classifies the shapes itself.
[[nodiscard]] std::vector<TrianglePair> find_self_intersecting_pairs(const Soup& welded);

}  // namespace shadowcert
