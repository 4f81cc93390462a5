#pragma once
// The volumes of the smooth-silhouette methods (`discrete`, `accurate`, `smooth`;
// docs/smooth-silhouettes.md) for a scene, one per light, as gpu/'s cpu-like methods draw them.
//
// Each mesh of the scene is taken as GL receives it (every coordinate and the light rounded to
// float, core/float_rounding.h) and asked whether it qualifies as a smooth caster
// (contour/smooth_caster.h). A mesh that qualifies casts the method's volume
// (contour/smooth_volume.h): for `discrete` each triangle's exact light side
// (exact/light_orientation.h) decides its cap, so on such a caster discrete draws the exact
// chain itself, with its counts. A mesh that does not qualify is never guessed at: it casts the robust chain of the
// float-rounded input (exact/cpu_volume.h), and the report says so. One light's volume is the
// union of the meshes' closed volumes, so it is closed.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "contour/smooth_caster.h"
#include "contour/smooth_volume.h"
#include "core/homogeneous_mesh.h"
#include "core/light.h"
#include "core/scene.h"
#include "gpu/shadow_method_renderer.h"

namespace shadowcert {

struct SilhouetteOptions {
  double epsilon = kDefaultContourEpsilon;                   // smooth: world units, > 0
  double crease_angle_degrees = kDefaultCreaseAngleDegrees;  // computed normals: [0, 180]
  // GL's near plane when the meshes are in the eye's frame (the eye at the origin), else 0.
  // accurate and smooth then set each mesh's cut cap points behind its surface by the depth
  // buffer's band at its farthest vertex (gpu/depth_precision.h; SmoothVolumeOptions::cap_offset
  // says why); 0: caps on the surface.
  double near_plane = 0.0;
};

// How one mesh cast.
struct SilhouetteCaster {
  std::string mesh;           // SceneMesh::name
  std::size_t triangles = 0;
  bool smooth = false;        // qualified: cast by the method; else by the robust chain
  std::string qualification;  // CasterQualification::summary()
  std::size_t loops = 0;      // the first light's silhouette loops (qualifying meshes)
};

struct SilhouetteVolumes {
  gpu::ShadowMethod method = gpu::ShadowMethod::smooth;
  std::vector<HomogeneousMesh> per_light;  // in the lights' order
  std::vector<SilhouetteCaster> casters;   // in the meshes' order
};

// `method`: discrete, accurate or smooth; `meshes` and `lights` as GL is given them (the eye's
// frame, core/eye_frame.h). Throws std::invalid_argument("silhouette_volumes: ...") for another
// method or bad options, and what smooth_caster and smooth_shadow_volume throw.
[[nodiscard]] SilhouetteVolumes silhouette_volumes(std::span<const SceneMesh> meshes, std::span<const Light> lights,
                                                   gpu::ShadowMethod method, const SilhouetteOptions& options = {});

}  // namespace shadowcert
