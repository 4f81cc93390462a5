#pragma once
// The contour error of a smooth-silhouette method (docs/smooth-silhouettes.md, "Error
// against the analytic shadow"): how far the shadow boundary the method casts on a plane lies
// from the true one, the conic where the light's tangent cone meets the plane
// (reference/ellipsoid_shadow.h). What bench/smooth_silhouette_bench.cpp tabulates per shape,
// for any scene whose casters know their ellipsoids, as `shadowcert bench` reports it.
//
// The methods built on the CPU (discrete, accurate, smooth) are measured on their loops or
// contours; smooth-gpu's contour exists only as the triangles its GPU build drew, so it is
// measured on those, read back (a GL context is current):
//
//   const std::optional<ContourError> e = contour_error(scene, 0, ShadowMethod::smooth, 0.01, plane);
//   const std::vector<CasterVolume> built = smooth_gpu_caster_volumes(scene, 0, 0.01);  // GL
//   const std::optional<ContourError> g = volume_contour_error(scene, 0, built, plane);
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "contour/smooth_caster.h"
#include "core/homogeneous_mesh.h"
#include "core/scene.h"
#include "gpu/shadow_method_renderer.h"
#include "reference/ellipsoid_shadow.h"

namespace shadowcert {

// Boundary points of the truth: the conic sampled at this many points (the benchmark's).
inline constexpr std::size_t kContourTruthSamples = 4096;

struct ContourError {
  double max = 0.0;        // world units on the plane: the largest distance to the conic
  double mean = 0.0;       // mean over the boundary points (each loop's mean weighted by its points)
  std::size_t points = 0;  // the method's boundary points (loops' or smooth contours'; a volume's: distinct ones)
  std::size_t casters = 0; // the analytic casters measured
};

// For every mesh of `scene` (world space, as given) that casts, knows its ellipsoid
// (SceneMesh::ellipsoid) and qualifies as a smooth caster (contour/smooth_caster.h with
// `crease_angle_degrees`): the method's loops (discrete: each triangle's exact light side;
// accurate) or smooth contours (smooth, at the mesh's own "epsilon" or `epsilon`) for light
// `light`, projected from the light onto `plane` and measured against the ellipsoid's shadow
// boundary there (boundary_distance, 8 samples per segment); the maximum and the point-weighted
// mean over those meshes. nullopt when no mesh is such a caster. Throws
// std::invalid_argument("contour_error: ...") for a method that is not a smooth-silhouette one
// or is smooth-gpu (its contour is the GPU's: smooth_gpu_caster_volumes, volume_contour_error),
// a light out of range or an epsilon not finite and > 0, and what ellipsoid_shadow_boundary and
// shadow_on_plane throw (a light inside the ellipsoid, a boundary ray that misses the plane).
[[nodiscard]] std::optional<ContourError> contour_error(const Scene& scene, std::size_t light,
                                                        gpu::ShadowMethod method, double epsilon,
                                                        const Plane& plane,
                                                        double crease_angle_degrees = kDefaultCreaseAngleDegrees);

// One analytic caster's closed volume for one light, as a method built it: `mesh` indexes the
// scene's meshes (world space, as given); `volume` is that mesh's volume alone
// (core/homogeneous_mesh.h: w = 1 finite, w = 0 at infinity).
struct CasterVolume {
  std::size_t mesh = 0;
  HomogeneousMesh volume;
};

// The contour error read from built volumes: a volume's boundary on the plane is where its side
// faces rise from its front cap X, so each triangle with exactly two finite vertices gives its
// finite edge, a segment of X's boundary (the contour); a segment drawn both ways cancels, as
// in the CPU build's global cancellation, and one drawn twice the same way (the lit part's and
// the unlit part's sides) counts once. Those segments, projected from light `light` onto
// `plane`, against the mesh's ellipsoid's shadow boundary as contour_error measures its loops
// (8 samples per segment, the mean by arc length; per mesh, then weighted by each mesh's
// points). On one closed loop this is contour_error's figure on the same points. nullopt when
// no volume gives a segment. Throws std::invalid_argument("volume_contour_error: ...") for a
// light or a mesh out of range, a mesh without an ellipsoid, and what contour_error's truth
// throws.
[[nodiscard]] std::optional<ContourError> volume_contour_error(const Scene& scene, std::size_t light,
                                                               std::span<const CasterVolume> volumes,
                                                               const Plane& plane);

// smooth-gpu's volumes for light `light`: every mesh contour_error would measure (it casts,
// knows its ellipsoid, qualifies as a smooth caster with `crease_angle_degrees`), built alone by
// the GPU (gpu/smooth_silhouette_volume.h, the shader render and diff draw with) in world space
// as given, at the mesh's own "epsilon" or `epsilon`, with its caps on the surface (cap offset
// 0, as contour_error's), and read back. Needs a current GL context. Throws
// std::invalid_argument("smooth_gpu_caster_volumes: ...") for a light out of range or an
// epsilon not finite and > 0, gpu::VolumeCapacityError when a volume outgrows the GPU's buffer,
// and what gpu/smooth_silhouette_volume.h throws.
[[nodiscard]] std::vector<CasterVolume> smooth_gpu_caster_volumes(const Scene& scene, std::size_t light,
                                                                  double epsilon,
                                                                  double crease_angle_degrees = kDefaultCreaseAngleDegrees);

}  // namespace shadowcert
