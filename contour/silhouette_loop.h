#pragma once
// A light's silhouette on a smooth caster (contour/smooth_caster.h) as loops of points on the
// mesh (Mattausch et al. 2012, §3.1; docs/smooth-silhouettes.md):
//   discrete : the mesh edges between a lit and an unlit triangle (the classic silhouette of a
//              manifold caster); the loop points are mesh vertices.
//   accurate : Hertzmann and Zorin's silhouette of the smooth surface the corner normals
//              describe. Every corner has the value f = n . (l - w v) (n the corner normal, (l, w)
//              the light); f >= 0 counts as lit (the fixed rule that keeps every loop well
//              formed where f = 0). Inside each triangle the zero set of the linearly
//              interpolated f is one segment or none, between points on two of its edges: on the
//              edge (i, j), i < j, at u = f_i / (f_i - f_j), position (1 - u) v_i + u v_j, normal
//              normalize((1 - u) n_i + u n_j), always computed from i to j, so the two triangles of
//              a smooth edge get the same bits. At a crease the two sides' values differ: the
//              part of the edge lit on one side only is part of the silhouette too, so a loop
//              runs along the crease between the two sides' points (a zero-length piece where
//              they coincide: the crease point is doubled, once per side's normal).
// Either way a loop is the boundary of the lit part of the caster, traversed with the lit part
// on its left (seen from the side the triangles' orientation points to), minus the caster's
// borders: loops are closed on closed casters and end at border edges on open ones.
#include <cstdint>
#include <span>
#include <vector>

#include "contour/smooth_caster.h"
#include "core/light.h"

namespace shadowcert {

struct SilhouettePoint {
  Vec3 position{};
  Vec3 normal{};  // unit: interpolated (accurate) or the corner's (at a mesh vertex)
  // Where it lies: on the mesh edge (edge_from, edge_to), edge_from < edge_to (welded vertex
  // indices), at u from edge_from; u = 0 at a vertex (edge_to == edge_from then).
  std::uint32_t edge_from = 0, edge_to = 0;
  double u = 0.0;
  std::uint32_t triangle = 0;  // the triangle whose corner normals gave it
};

struct SilhouetteLoop {
  std::vector<SilhouettePoint> points;  // in order; a closed loop does not repeat its first point
  // segment_triangles[i]: the triangle whose lit part the segment points[i] -> points[i + 1]
  // bounds (the last one of a closed loop returns to points[0]); kBorder for the zero-length
  // piece between a crease point's two copies. A point at a mesh vertex where the loop changes
  // triangles belongs to both segments: each takes that triangle's corner normal there
  // (smooth_contour.h), as the paper doubles a crease point with either normal.
  std::vector<std::uint32_t> segment_triangles;
  bool closed = false;
};

// The corner values f of every corner (3 per triangle, in the caster's corner order).
// Precondition: `light` defined (core/light.h).
[[nodiscard]] std::vector<std::array<double, 3>> corner_light_values(const SmoothCaster& caster, const Light& light);

// `lit`: one entry per caster triangle, nonzero where the triangle faces the light (the caller
// decides it, e.g. exactly with exact/light_orientation). Throws std::invalid_argument
// ("discrete_silhouette: ...") when the sizes differ.
[[nodiscard]] std::vector<SilhouetteLoop> discrete_silhouette(const SmoothCaster& caster,
                                                              std::span<const std::uint8_t> lit);

[[nodiscard]] std::vector<SilhouetteLoop> accurate_silhouette(const SmoothCaster& caster, const Light& light);

}  // namespace shadowcert
