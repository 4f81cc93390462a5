#pragma once
// Caster diagnostics (docs/definitions.md#caster-diagnostics): what classic, non-soup shadow methods assume of a
// caster, measured on the exactly welded soup. Geometric decisions (collinearity,
// self-intersection) use CGAL's exact predicates; no tolerance anywhere.
//
// Definitions (docs/caster-diagnostics.md has them at length, with examples):
//  - Everything is counted on the exactly welded soup (canonical_soup; docs/definitions.md#inputs: two vertices are one iff their
//    doubles are bitwise equal, -0 == +0), so "index" below means welded index.
//  - A triangle is *index-proper* when its three indices are distinct. Only index-proper
//    triangles have edges, fans, duplicates and components; a triangle with a repeated index
//    is counted as degenerate and nowhere else (it casts nothing, docs/definitions.md#orientation).
//  - An *edge* is an unordered index pair {u, v} used by at least one index-proper triangle
//    (exactly collinear triangles included: their edges exist). A triangle *traverses* it
//    u -> v or v -> u according to its vertex order.
#include <cstdint>

#include "core/soup.h"

namespace shadowcert {

struct CasterDiagnostics {
  std::uint64_t vertices = 0;              // input vertices (unreferenced ones included)
  std::uint64_t welded_vertices = 0;       // distinct positions after exact welding
  std::uint64_t triangles = 0;             // input triangles
  // A repeated welded index, or three distinct points that are exactly collinear
  // (CGAL Epick `collinear`, a filtered hence exact predicate).
  std::uint64_t degenerate_triangles = 0;
  // Extra copies of a welded vertex set {a, b, c} (index-proper triangles), either
  // orientation: a set that appears k times counts k - 1.
  std::uint64_t duplicate_triangles = 0;
  std::uint64_t edges = 0;                 // undirected edges of index-proper triangles
  std::uint64_t border_edges = 0;          // edges with exactly one incident triangle
  std::uint64_t nonmanifold_edges = 0;     // edges with three or more incident triangles
  // Vertices whose incident index-proper triangles fall into two or more classes when
  // triangles sharing an edge at the vertex are joined (a bow-tie: not one fan). Triangles
  // joined through a non-manifold edge are one class, so that defect is not counted twice.
  std::uint64_t nonmanifold_vertices = 0;
  // Classes of index-proper triangles under "shares an edge with", transitively.
  std::uint64_t components = 0;
  bool closed = false;                     // at least one edge and no border edge
  bool manifold = false;                   // no non-manifold edge and no non-manifold vertex
  // Every edge with two or more incident triangles is traversed as often u -> v as v -> u:
  // once each way on a two-triangle edge; balanced on a non-manifold edge (so an odd number
  // of triangles on an edge is never consistent). Border edges are not looked at. Reversing
  // every triangle keeps it. True on a soup without edges.
  bool consistently_oriented = false;
  // Two index-proper, non-collinear triangles share a point that their common welded
  // vertices do not account for: no common vertex and they meet; one common vertex and
  // they meet elsewhere too; a common edge and they overlap beyond it (coplanar, opposite
  // vertices on the same side); three common vertices (duplicates) always. Degenerate
  // triangles are skipped. Exact (CGAL filtered predicates on the input doubles).
  bool self_intersecting = false;
  std::uint64_t self_intersecting_pairs = 0;  // unordered pairs of triangles as above
  // Added: edges whose signed use count (+1 per triangle traversing u -> v, -1 per v -> u,
  // for u < v) is not zero, border edges included: the data README's "unbal" column.
  std::uint64_t unbalanced_edges = 0;
  double seconds = 0.0;                    // wall time of diagnose_caster (welding included)
};

// Throws std::invalid_argument (from weld_soup) on an index out of range or on normals whose
// count is neither zero nor the vertex count.
[[nodiscard]] CasterDiagnostics diagnose_caster(const Soup& soup);

}  // namespace shadowcert
