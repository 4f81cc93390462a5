#pragma once
// The edges of a manifold caster as silhouette tracking sees them (Chen and Tsai, §2.1;
// docs/smoothies.md, "Silhouette tracking"): every edge with its two faces (one on a border),
// the edges around every vertex, and the two lists the paper consults every frame, the concave
// edges and the border edges.
//
// An edge's **neighbours** are the other edges that share a vertex with it (the paper's
// Figure 1: the search steps from a silhouette edge to the edges at its two ends). On a
// manifold no other edge shares both ends, so edge (a, b) has deg(a) + deg(b) - 2 neighbours.
//
// A **silhouette edge** for a light is an edge whose two faces lie on different sides of the
// light (face_light_side below: lit, unlit or edge-on), or a border edge whose one face is not
// edge-on. That is exactly the edge set with multiplicity m != 0 of docs/multiplicities.md when
// the face sides are exact (m = s(t2) - s(t1) on a manifold edge, -s(t) on a border edge).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "contour/smooth_caster.h"
#include "core/light.h"
#include "core/sign.h"

namespace shadowcert {

struct SilhouetteEdgeGraph {
  std::vector<Vec3> vertices;  // the caster's welded positions
  // Per face: its vertices sorted by lexicographic order of position, and the parity (+1 or -1)
  // of that order against the face's own, in one 16-byte record (a face's side reads one cache
  // line besides its vertices). face_light_side evaluates the sorted triple, so a face's side
  // does not depend on where its labelling starts (Milet 2014's refedge order).
  struct SortedFace {
    Triangle vertices;
    std::int32_t parity;
  };
  std::vector<SortedFace> sorted_faces;
  // Edge e: its welded vertices (edge_vertices[e][0] < edge_vertices[e][1]) and its faces; the
  // second face is kBorder (contour/smooth_caster.h) on a border edge. Edges are numbered in the
  // order their first triangle (lowest index) meets them, corner by corner.
  std::vector<std::array<std::uint32_t, 2>> edge_vertices;
  std::vector<std::array<std::uint32_t, 2>> edge_faces;
  // The edges around vertex v, ascending: vertex_edges[first_vertex_edge[v] .. first_vertex_edge[v + 1]).
  std::vector<std::uint32_t> first_vertex_edge;
  std::vector<std::uint32_t> vertex_edges;
  // The lists the paper checks every frame, ascending. Concave: an interior edge where the
  // opposite vertex o of its second face lies on the side its first face (a, b, c)'s normal
  // points to (a dihedral angle over 180 degrees seen from that side: from outside on an
  // outward mesh), by det[b - a, c - a, o - a] in double, above a flatness bound that absorbs
  // its rounding on coplanar faces (kFlatEdgeSine in the .cpp); a flat edge is neither.
  // Border: the edges with one face.
  std::vector<std::uint32_t> concave_edges;
  std::vector<std::uint32_t> border_edges;

  [[nodiscard]] std::size_t edge_count() const { return edge_vertices.size(); }
  [[nodiscard]] std::size_t face_count() const { return sorted_faces.size(); }
  // The edges around vertex v (v < vertices.size()).
  [[nodiscard]] std::span<const std::uint32_t> edges_at(std::uint32_t v) const {
    return {vertex_edges.data() + first_vertex_edge[v], vertex_edges.data() + first_vertex_edge[v + 1]};
  }
};

// Built once per caster, independent of the light; O(triangles + vertices).
[[nodiscard]] SilhouetteEdgeGraph silhouette_edge_graph(const SmoothCaster& caster);

// The float light-side test: the sign of core/light_side_formula.h evaluated in double on the
// face's sorted vertices, times its parity; positive: lit (the light on the side the face's
// normal points to), zero: edge-on. It is refedge double's cap sign (exact/edge_multiplicity.h),
// and differs from the exact sign only where the light is within rounding of the face's plane.
// Preconditions (not checked: called per face per frame): face < face_count(), light defined.
[[nodiscard]] Sign face_light_side(const SilhouetteEdgeGraph& graph, std::uint32_t face, const Light& light);

// Whether edge e is a silhouette edge given its faces' sides (`second` ignored on a border edge).
[[nodiscard]] inline bool silhouette_sides(Sign first, Sign second, bool border) {
  return border ? first != Sign::zero : first != second;
}

}  // namespace shadowcert
