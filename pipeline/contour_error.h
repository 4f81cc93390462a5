#pragma once
// The contour error of a smooth-silhouette method (docs/smooth-silhouettes.md, "Error
// against the analytic shadow"): how far the shadow boundary the method casts on a plane lies
// from the true one, the conic where the light's tangent cone meets the plane
// (reference/ellipsoid_shadow.h). What bench/smooth_silhouette_bench.cpp tabulates per shape,
// for any scene whose casters know their ellipsoids, as `shadowcert bench` reports it.
//
//   const std::optional<ContourError> e = contour_error(scene, 0, ShadowMethod::smooth, 0.01, plane);
#include <cstddef>
#include <optional>

#include "contour/smooth_caster.h"
#include "core/scene.h"
#include "gpu/shadow_method_renderer.h"
#include "reference/ellipsoid_shadow.h"

namespace shadowcert {

// Boundary points of the truth: the conic sampled at this many points (the benchmark's).
inline constexpr std::size_t kContourTruthSamples = 4096;

struct ContourError {
  double max = 0.0;        // world units on the plane: the largest distance to the conic
  double mean = 0.0;       // mean over the boundary points (each loop's mean weighted by its points)
  std::size_t points = 0;  // the method's boundary points (loops' or smooth contours')
  std::size_t casters = 0; // the analytic casters measured
};

// For every mesh of `scene` (world space, as given) that casts, knows its ellipsoid
// (SceneMesh::ellipsoid) and qualifies as a smooth caster (contour/smooth_caster.h with
// `crease_angle_degrees`): the method's loops (discrete: each triangle's exact light side;
// accurate) or smooth contours (smooth and smooth-gpu, at the mesh's own "epsilon" or
// `epsilon`) for light `light`, projected from the light onto `plane` and measured against the
// ellipsoid's shadow boundary there (boundary_distance, 8 samples per segment); the maximum and
// the point-weighted mean over those meshes. nullopt when no mesh is such a caster. Throws
// std::invalid_argument("contour_error: ...") for a method that is not a smooth-silhouette one,
// a light out of range or an epsilon not finite and > 0, and what ellipsoid_shadow_boundary and
// shadow_on_plane throw (a light inside the ellipsoid, a boundary ray that misses the plane).
[[nodiscard]] std::optional<ContourError> contour_error(const Scene& scene, std::size_t light,
                                                        gpu::ShadowMethod method, double epsilon,
                                                        const Plane& plane,
                                                        double crease_angle_degrees = kDefaultCreaseAngleDegrees);

}  // namespace shadowcert
