#pragma once
// Scenes built around one caster, for the benchmarks, `shadowcert bench` and the tests, so that
// "mesh M framed over a floor" and "the analytic sphere 8x4" mean the same scene everywhere
// (docs/bench.md#the-suites):
//   - framed_mesh_scene: any mesh (the real meshes of ../shared/data/) over a floor, camera and
//     light placed by a fixed rule from its bounding box;
//   - analytic_shapes and analytic_shape_scene: the uv spheres 8x4 to 256x128 and the ellipsoid
//     of the smooth-silhouette error (docs/smooth-silhouettes.md), each over the floor y = -1.5
//     with the point light or the sun of those tables.
#include <cstdint>
#include <string>
#include <vector>

#include "core/ellipsoid.h"
#include "core/light.h"
#include "core/scene.h"
#include "core/soup.h"

namespace shadowcert {

struct FramedMeshOptions {
  std::uint32_t width = 256;
  std::uint32_t height = 192;
  // Whether the floor casts too (it lies under the mesh, so it shades nothing the camera sees,
  // but it joins every volume); false: it only receives.
  bool floor_casts = false;
};

// The framing rule: the mesh's vertex box (those its triangles use) has centre c and half
// diagonal r; the floor is a square 6r wide, 0.01r under the box, facing up; one point light at
// c + r (1.5, 3, 1); the eye at c + r (2.4, 1.6, 3.2) looking at c, 45 degrees, the near plane
// fitted to the scene (core/near_plane.h). Meshes: the mesh (named `name`), then the floor
// ("floor"). Throws std::invalid_argument("framed_mesh_scene: ...") for a mesh without a triangle
// or a size with a zero side.
[[nodiscard]] Scene framed_mesh_scene(const Soup& mesh, const std::string& name, const FramedMeshOptions& options = {});

// A caster of the analytic error: its soup and the ellipsoid it approximates.
struct AnalyticShape {
  std::string name;  // "sphere8x4", ..., "ellipsoid32x16"
  Soup soup;
  Ellipsoid ellipsoid;
};

// The floor of the analytic scenes: the plane y = kAnalyticFloorHeight, facing up.
inline constexpr double kAnalyticFloorHeight = -1.5;
// Their lights: a point light at (1.2, 4, 0.8) and a sun towards (0.3, 1, 0.2).
inline constexpr Light kAnalyticPointLight{{1.2, 4.0, 0.8, 1.0}};
inline constexpr Light kAnalyticSun{{0.3, 1.0, 0.2, 0.0}};

// Unit uv spheres at the origin, 8x4, 12x6, 16x8, 32x16, 64x32, 128x64 and 256x128 (slices x
// stacks, with the generator's normals), then "ellipsoid32x16": the 32x16 sphere under
// A = [[1.4, 0, -0.3], [0, 0.8, 0], [0.2, 0, 1]] (columns (1.4, 0, 0.2), (0, 0.8, 0), (-0.3, 0,
// 1)), its normals left to be computed from the transformed mesh.
[[nodiscard]] std::vector<AnalyticShape> analytic_shapes();

// `shape` at the origin over the floor (a square 16 wide at y = kAnalyticFloorHeight, receiving
// only: "floor" first, then the caster with its ellipsoid), under `light`, seen from
// (-2.5, 5.5, 6.5) towards (-0.4, -0.9, -0.3) (the shadow and the caster's terminator side in
// view), at width x height, near plane fitted.
[[nodiscard]] Scene analytic_shape_scene(const AnalyticShape& shape, const Light& light, std::uint32_t width,
                                         std::uint32_t height);

}  // namespace shadowcert
