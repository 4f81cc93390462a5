#include "exact/caster_diagnostics.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "exact/degenerate_triangles.h"
#include "exact/triangle_soup_self_intersections.h"
#include "exact/triangle_soup_topology.h"
#include "scene/canonical_soup.h"

namespace shadowcert {
namespace {

std::uint64_t count_degenerate(const std::vector<TriangleShape>& shapes) {
  return static_cast<std::uint64_t>(
      std::count_if(shapes.begin(), shapes.end(), [](TriangleShape s) { return s != TriangleShape::Proper; }));
}

void copy_topology(const SoupTopology& topology, CasterDiagnostics& d) {
  d.duplicate_triangles = topology.duplicate_triangles;
  d.edges = topology.edges;
  d.border_edges = topology.border_edges;
  d.nonmanifold_edges = topology.nonmanifold_edges;
  d.nonmanifold_vertices = topology.nonmanifold_vertices;
  d.unbalanced_edges = topology.unbalanced_edges;
  d.components = topology.components;
  d.closed = topology.edges > 0 && topology.border_edges == 0;
  d.manifold = topology.nonmanifold_edges == 0 && topology.nonmanifold_vertices == 0;
  // Balance of the directed uses on every edge with two or more triangles: on a two-triangle
  // edge that is "once each way"; on a non-manifold edge it is what keeps the winding number
  // piecewise constant across it (the README's PWN), and what makes the shadow-volume side
  // multiplicities of docs/definitions.md#counts cancel for a light far away.
  d.consistently_oriented = topology.unbalanced_interior_edges == 0;
}

}  // namespace

CasterDiagnostics diagnose_caster(const Soup& soup) {
  const auto start = std::chrono::steady_clock::now();
  CasterDiagnostics d;
  d.vertices = soup.vertices.size();
  d.triangles = soup.triangles.size();
  // docs/definitions.md#inputs: vertex identity is the index after exact welding, so every count below is
  // taken on the welded soup. The canonical form welds by one sort (faster than hashing) and
  // only renumbers vertices, which no figure here depends on.
  const CanonicalSoup welded = canonical_soup(soup);
  d.welded_vertices = welded.soup.vertices.size();
  const std::vector<TriangleShape> shapes = classify_triangle_shapes(welded.soup);
  d.degenerate_triangles = count_degenerate(shapes);
  copy_topology(analyze_topology(welded.soup), d);
  d.self_intersecting_pairs = find_self_intersecting_pairs(welded.soup, shapes).size();
  d.self_intersecting = d.self_intersecting_pairs > 0;
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return d;
}

}  // namespace shadowcert
