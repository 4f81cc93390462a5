#include "contour/silhouette_edge_graph.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/light_side_formula.h"
#include "core/vector3.h"

namespace shadowcert {
namespace {

// An edge is concave only when the opposite vertex rises above the first face's plane by a sine
// of more than this (det[b - a, c - a, o - a] > kFlatEdgeSine |(b - a) x (c - a)| |o - a|). It
// absorbs the rounding of the double determinant where the two faces are coplanar (a uv
// sphere's or a torus's quads, split in two: exactly flat, but the determinant comes out a
// few 1e-16 of that product either way, which put half of those diagonals on the concave list);
// a real dent shallower than 1e-10 radians is not listed.
constexpr double kFlatEdgeSine = 1e-10;

// The face's vertices in lexicographic order of position, and the parity of that permutation.
SilhouetteEdgeGraph::SortedFace sorted_face(const std::vector<Vec3>& vertices, const Triangle& t) {
  SilhouetteEdgeGraph::SortedFace f{t, 1};
  Triangle& s = f.vertices;
  const auto before = [&](std::uint32_t x, std::uint32_t y) { return vertices[x] < vertices[y]; };
  if (before(s[1], s[0])) std::swap(s[0], s[1]), f.parity = -f.parity;
  if (before(s[2], s[1])) std::swap(s[1], s[2]), f.parity = -f.parity;
  if (before(s[1], s[0])) std::swap(s[0], s[1]), f.parity = -f.parity;
  return f;
}

std::uint32_t opposite_vertex(const Triangle& t, std::uint32_t a, std::uint32_t b) {
  for (const std::uint32_t v : t)
    if (v != a && v != b) return v;
  throw std::logic_error("silhouette_edge_graph: a face has no vertex opposite its edge");
}

}  // namespace

SilhouetteEdgeGraph silhouette_edge_graph(const SmoothCaster& caster) {
  const std::size_t n = caster.triangles.size();
  if (caster.across.size() != n)
    throw std::invalid_argument("silhouette_edge_graph: the caster's across table does not match its triangles");
  SilhouetteEdgeGraph g;
  g.vertices = caster.vertices;
  const std::vector<Triangle>& triangles = caster.triangles;
  const std::vector<std::array<std::uint32_t, 3>>& across = caster.across;
  g.sorted_faces.reserve(n);
  for (std::size_t t = 0; t < n; ++t) g.sorted_faces.push_back(sorted_face(g.vertices, triangles[t]));

  // Each interior edge once, from its lower triangle; each border edge from its one triangle.
  g.edge_vertices.reserve(3 * n / 2 + 1);
  g.edge_faces.reserve(3 * n / 2 + 1);
  for (std::uint32_t t = 0; t < n; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t other = across[t][k];
      if (other != kBorder && other < t) continue;
      const std::uint32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      const auto e = static_cast<std::uint32_t>(g.edge_vertices.size());
      g.edge_vertices.push_back({std::min(a, b), std::max(a, b)});
      g.edge_faces.push_back({t, other});
      if (other == kBorder) {
        g.border_edges.push_back(e);
        continue;
      }
      const Triangle& first = triangles[t];
      const Vec3& p = g.vertices[first[0]];
      const Vec3& o = g.vertices[opposite_vertex(triangles[other], a, b)];
      const Vec3 normal = cross(difference(g.vertices[first[1]], p), difference(g.vertices[first[2]], p));
      const Vec3 rise = difference(o, p);
      const double side = dot(normal, rise);
      if (side > kFlatEdgeSine * std::sqrt(dot(normal, normal) * dot(rise, rise))) g.concave_edges.push_back(e);
    }

  // Edges around each vertex, by a counting sort (ascending edge index within a vertex).
  g.first_vertex_edge.assign(g.vertices.size() + 1, 0);
  for (const auto& [a, b] : g.edge_vertices) ++g.first_vertex_edge[a + 1], ++g.first_vertex_edge[b + 1];
  for (std::size_t v = 0; v < g.vertices.size(); ++v) g.first_vertex_edge[v + 1] += g.first_vertex_edge[v];
  g.vertex_edges.resize(g.first_vertex_edge.back());
  std::vector<std::uint32_t> next(g.first_vertex_edge.begin(), g.first_vertex_edge.end() - 1);
  for (std::uint32_t e = 0; e < g.edge_vertices.size(); ++e)
    for (const std::uint32_t v : g.edge_vertices[e]) g.vertex_edges[next[v]++] = e;
  return g;
}

Sign face_light_side(const SilhouetteEdgeGraph& graph, std::uint32_t face, const Light& light) {
  const SilhouetteEdgeGraph::SortedFace& f = graph.sorted_faces[face];
  const Triangle& s = f.vertices;
  const Sign side = light_side_sign<double>(graph.vertices[s[0]], graph.vertices[s[1]], graph.vertices[s[2]], light.position);
  return f.parity > 0 ? side : -side;
}

}  // namespace shadowcert
