#pragma once
// Caster diagnostics (DESIGN.md §4.3): what classic, non-soup shadow methods assume of a
// caster, measured on the exactly welded soup. Geometric decisions (collinearity,
// self-intersection) use CGAL's exact predicates; no tolerance anywhere.
#include <cstdint>

#include "core/soup.h"

namespace shadowcert {

struct CasterDiagnostics {
  std::uint64_t vertices = 0;              // input vertices
  std::uint64_t welded_vertices = 0;       // distinct positions after exact welding
  std::uint64_t triangles = 0;             // input triangles
  std::uint64_t degenerate_triangles = 0;  // a repeated welded index, or exactly collinear
  std::uint64_t duplicate_triangles = 0;   // extra copies of a welded vertex set, either orientation
  std::uint64_t edges = 0;                 // undirected edges of triangles with 3 distinct welded ids
  std::uint64_t border_edges = 0;          // edges with exactly one incident triangle
  std::uint64_t nonmanifold_edges = 0;     // edges with three or more incident triangles
  std::uint64_t nonmanifold_vertices = 0;  // vertices whose incident triangles form more than one fan
  std::uint64_t components = 0;            // edge-connected components of triangles
  bool closed = false;                     // no border edge (and at least one edge)
  bool manifold = false;                   // no non-manifold edge or vertex
  bool consistently_oriented = false;      // every two-triangle edge is used once each way
  bool self_intersecting = false;          // two triangles meet other than as sharing permits
  std::uint64_t self_intersecting_pairs = 0;
  double seconds = 0.0;                    // wall time of diagnose_caster
};

[[nodiscard]] CasterDiagnostics diagnose_caster(const Soup& soup);

}  // namespace shadowcert
