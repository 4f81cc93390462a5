#pragma once
// The GL near plane a scene is drawn with (Camera::near_plane; gpu/camera_transform.h's
// infinite projection, whose window depth is 1 - near / D at view depth D).
//
// A fixed near plane fails at both ends of scale. A scene a million units away lands at
// window depth 1 - 1e-8, which a 24-bit depth buffer rounds to 1, the cleared depth: the
// receivers fail GL_LESS and nothing is drawn (fuzz --gl seed 101, case 227: a snapped soup at
// 2^17, tests/regressions/gl/far_scene_off_vertex). A scene smaller than the near distance is
// clipped away. The fitted plane keeps the depth buffer's relative resolution at the farthest
// vertex at least what kDefaultNearPlane gives a unit scene (view depth 20), and never clips a
// triangle: it stays at or below half the distance from the eye to the nearest triangle.
#include <algorithm>
#include <cmath>
#include <span>

#include "core/camera.h"
#include "core/scene.h"
#include "core/soup.h"
#include "core/vector3.h"

namespace shadowcert {

// The farthest vertex's view depth over the near plane, at most: 2^11 keeps 2^13 window-depth
// steps between that vertex and depth 1, as kDefaultNearPlane does for a unit scene at depth 20.
inline constexpr double kFarOverNear = 2048.0;
// The near plane's largest share of the distance to the nearest triangle: below 1 so that the
// rounding of that distance and of the projection never clips what lies just beyond it.
inline constexpr double kNearClipShare = 0.5;

// The distance from `p` to the segment [a, b] (a point when a == b), in double.
[[nodiscard]] inline double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = difference(b, a), ap = difference(p, a);
  const double length2 = dot(ab, ab);
  const double s = length2 > 0.0 ? std::clamp(dot(ab, ap) / length2, 0.0, 1.0) : 0.0;
  const Vec3 gap{ap[0] - s * ab[0], ap[1] - s * ab[1], ap[2] - s * ab[2]};
  return std::sqrt(dot(gap, gap));
}

// The distance from `p` to the triangle (a, b, c), in double: to the closest point of the
// triangle as Ericson's Real-Time Collision Detection 5.1.5 finds it by Voronoi region (a
// degenerate triangle gives the distance to one of its edges or vertices).
[[nodiscard]] inline double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto length = [](const Vec3& v) { return std::sqrt(dot(v, v)); };
  const auto along = [](const Vec3& o, const Vec3& u, double s) { return Vec3{o[0] + s * u[0], o[1] + s * u[1], o[2] + s * u[2]}; };
  const Vec3 ab = difference(b, a), ac = difference(c, a), ap = difference(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return length(ap);
  const Vec3 bp = difference(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return length(bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return length(difference(p, along(a, ab, d1 / (d1 - d3))));
  const Vec3 cp = difference(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return length(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return length(difference(p, along(a, ac, d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
    return length(difference(p, along(b, difference(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  const double sum = va + vb + vc;
  if (!(sum > 0.0))  // a degenerate triangle that no region test caught: its nearest edge
    return std::min({distance_to_segment(p, a, b), distance_to_segment(p, b, c), distance_to_segment(p, c, a)});
  const Vec3 q = along(along(a, ab, vb / sum), ac, vc / sum);
  return length(difference(p, q));
}

// The near plane for drawing `soups` (world-space, finite vertices) from `eye`:
//   max(kDefaultNearPlane, farthest vertex distance / kFarOverNear), then at most
//   kNearClipShare times the distance from the eye to the nearest triangle.
// When the eye lies on a triangle (that distance is 0) only the first rule applies. Last, the
// plane is floored at the farthest distance * 2^-22, so that it stays positive and the farthest
// vertex keeps 4 depth steps below 1: a triangle nearer than that is clipped rather than the far
// end lost. An empty scene gets kDefaultNearPlane.
[[nodiscard]] inline double fitted_near_plane(std::span<const Soup* const> soups, const Vec3& eye) {
  double farthest = 0.0;
  double nearest = INFINITY;
  for (const Soup* soup : soups) {
    for (const Vec3& v : soup->vertices) {
      const Vec3 d = difference(v, eye);
      farthest = std::max(farthest, std::sqrt(dot(d, d)));
    }
    for (const Triangle& t : soup->triangles)
      nearest = std::min(nearest, distance_to_triangle(eye, soup->vertices[t[0]], soup->vertices[t[1]], soup->vertices[t[2]]));
  }
  if (!(farthest > 0.0)) return kDefaultNearPlane;
  double near = std::max(kDefaultNearPlane, farthest / kFarOverNear);
  if (nearest > 0.0) near = std::min(near, kNearClipShare * nearest);
  return std::max(near, std::ldexp(farthest, -22));
}

// The scene's camera with its near plane fitted to every mesh (above).
[[nodiscard]] inline Camera camera_fitted_to(const Scene& scene) {
  std::vector<const Soup*> soups;
  for (const SceneMesh& mesh : scene.meshes) soups.push_back(&mesh.soup);
  Camera camera = scene.camera;
  camera.near_plane = fitted_near_plane(soups, camera.eye);
  return camera;
}

}  // namespace shadowcert
