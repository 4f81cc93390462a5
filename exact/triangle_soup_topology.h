#pragma once
// Combinatorial structure of a welded triangle soup (docs/definitions.md#inputs, docs/definitions.md#caster-diagnostics): the edge, fan,
// duplicate and component counts of caster_diagnostics.h, on indices only (no geometry).
//
// Only triangles with three distinct (welded) indices take part; a triangle with a repeated
// index has fewer than three edges and casts nothing (docs/definitions.md#orientation). Exactly collinear
// triangles with distinct indices do take part: their edges are real edges of the soup.
#include <cstdint>

#include "core/soup.h"

namespace shadowcert {

struct SoupTopology {
  std::uint64_t edges = 0;              // distinct undirected edges {u, v}
  std::uint64_t border_edges = 0;       // edges with exactly one incident triangle
  std::uint64_t nonmanifold_edges = 0;  // edges with three or more incident triangles
  // Edges whose signed use count (+1 per triangle traversing u->v, -1 per v->u, u < v) is
  // not zero: the data README's "unbal" (border edges included, each counts +-1).
  std::uint64_t unbalanced_edges = 0;
  // Unbalanced edges with two or more incident triangles: orientation faults proper.
  std::uint64_t unbalanced_interior_edges = 0;
  // Vertices whose incident triangles split into two or more groups, where triangles at v
  // are grouped when they share an edge {v, w} (a bow-tie: not a single fan around v).
  std::uint64_t nonmanifold_vertices = 0;
  // Extra copies of one vertex set {a, b, c}, either orientation (k copies count k - 1).
  std::uint64_t duplicate_triangles = 0;
  // Classes of triangles under "shares an edge with", transitively.
  std::uint64_t components = 0;
};

// Pass weld_soup(...).soup for the counts of docs/definitions.md#inputs's vertex identity, as
// diagnose_caster does. On an unwelded soup the same call counts the soup's own index
// topology, which is how data/README.md measured its columns (the tests use it so).
// O(triangles + vertices) plus a sort of each vertex's few edge uses; parallel over vertices.
// Throws std::invalid_argument("analyze_topology: ...") on an index >= vertices.size() or
// more than 2^32 - 1 triangles.
[[nodiscard]] SoupTopology analyze_topology(const Soup& soup);

}  // namespace shadowcert
