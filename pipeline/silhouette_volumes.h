#pragma once
// The volumes of the smooth-silhouette methods (`discrete`, `accurate`, `smooth`, `smooth-gpu`;
// docs/smooth-silhouettes.md) for a scene, one per light, as gpu/'s cpu-like methods draw them.
// Under smooth-gpu the meshes cast smooth are not built here: they go to the GPU as plain
// arrays (SilhouetteVolumes::gpu_casters, gpu/smooth_silhouette_volume.h), and the per-light
// volumes hold the other meshes only.
//
// Each mesh of the scene is taken as GL receives it (every coordinate and the light rounded to
// float, core/float_rounding.h) and asked whether it qualifies as a smooth caster
// (contour/smooth_caster.h). A mesh that qualifies casts the method's volume
// (contour/smooth_volume.h): for `discrete` each triangle's exact light side
// (exact/light_orientation.h) decides its cap, so on such a caster discrete draws the exact
// chain itself, with its counts. A mesh that does not qualify is never guessed at: it casts the robust chain of the
// float-rounded input (exact/cpu_volume.h), and the report says so. One light's volume is the
// union of the meshes' closed volumes, so it is closed.
//
// The scene has the last word per mesh (docs/scene-format.md): "casts": false keeps a mesh out
// of every volume; its own "silhouette" replaces the command's method for it ("chain": the
// robust chain, unasked), its own "epsilon" replaces SilhouetteOptions::epsilon.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "contour/smooth_caster.h"
#include "contour/smooth_volume.h"
#include "core/homogeneous_mesh.h"
#include "core/light.h"
#include "core/scene.h"
#include "gpu/shadow_method_renderer.h"
#include "gpu/smooth_silhouette_volume.h"

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
  bool casts = true;          // false: the scene's "casts": false, in no volume
  // The silhouette method that cast the mesh (the command's, or the mesh's own "silhouette";
  // smooth-gpu where the GPU builds it); nullopt: the robust chain (or nothing, when it does
  // not cast).
  std::optional<gpu::ShadowMethod> cast_by;
  double epsilon = 0.0;       // cast by smooth: the contour error it used; else 0
  // CasterQualification::summary(), or why the mesh was not asked: "the scene asks for the
  // chain", "the scene says it casts nothing".
  std::string qualification;
  std::size_t loops = 0;      // the first light's silhouette loops (cast on the CPU; smooth-gpu traces none: 0)
};

struct SilhouetteVolumes {
  gpu::ShadowMethod method = gpu::ShadowMethod::smooth;
  std::vector<HomogeneousMesh> per_light;  // in the lights' order
  std::vector<SilhouetteCaster> casters;   // in the meshes' order
  // smooth-gpu: the meshes cast smooth, for the GPU to build (every light); empty otherwise.
  gpu::SmoothCasterArrays gpu_casters;
};

// `method`: discrete, accurate, smooth or smooth-gpu; `meshes` and `lights` as GL is given them (the eye's
// frame, core/eye_frame.h). Throws std::invalid_argument("silhouette_volumes: ...") for another
// method, bad options or a mesh's bad epsilon (not finite and > 0), and what smooth_caster and
// smooth_shadow_volume throw.
// smooth-gpu's volumes as drawn: builds `volumes.gpu_casters` on the GPU for every light of
// `lights` (those `volumes` was made for) and appends the read-back triangles to its per_light,
// so that each is the whole volume render draws, for certify and the tests. Needs a current GL
// context; throws what gpu/smooth_silhouette_volume.h throws, and std::invalid_argument
// ("capture_gpu_volumes: ...") when the lights do not match the volumes.
void capture_gpu_volumes(SilhouetteVolumes& volumes, std::span<const Light> lights);

[[nodiscard]] SilhouetteVolumes silhouette_volumes(std::span<const SceneMesh> meshes, std::span<const Light> lights,
                                                   gpu::ShadowMethod method, const SilhouetteOptions& options = {});

}  // namespace shadowcert
