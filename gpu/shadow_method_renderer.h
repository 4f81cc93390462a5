#pragma once
// One shadow method (gpu/shadow_method.h: the methods and their traits) rendering one scene: the layer `shadowcert render`, the
// benchmark (bench/render_bench.cpp) and the image comparison share, so that "scene S by
// method M" means the same frames everywhere.
//
//   cpu        the exact chain of exact/ per light, uploaded once (the caller converts it
//              with exact/chain_mesh.h: gpu/ never links exact/) and drawn as is
//   cs         compute-shader volumes (gpu/compute_volume.h)
//   gs         geometry shader over edge records (gpu/geometry_shader_volume.h)
//   ts         tessellation over edge-record patches (gpu/tessellation_volume.h)
//   pertri     every triangle's own closed volume (gpu/per_triangle_volume.h)
//   shadowmap  no volume: one depth map per light (gpu/shadow_map_renderer.h)
//   pcf, pcss  the shadow map filtered: K x K percentage-closer filtering, and Fernando's
//              percentage-closer soft shadows for a disk light of radius R (ShadowFilter)
//   smoothie   the shadow map, then the smoothie map of the caller's smoothies per light
//              (Chen & Tsai; core/smoothie_mesh.h from pipeline/scene_smoothies.h, drawn by
//              gpu/smoothie_map.h); docs/smoothies.md
//   discrete, accurate, smooth
//              smooth-silhouette volumes (docs/smooth-silhouettes.md), built by the caller
//              (pipeline/ with contour/) and drawn as cpu's are
//   smooth-gpu the smooth volume built on the GPU (gpu/smooth_silhouette_volume.h) from the
//              caller's smooth casters, rebuilt every frame; the meshes it does not cast come
//              as a given volume per light, drawn with it
//
// The GPU-built volumes (cs, gs, ts, pertri) are rebuilt in every frame, as for a moving
// light, so a frame's time includes their build (stage `volume`); cpu's are built once by
// the caller. Stencil methods draw with gpu/stencil_shadow_renderer.h, z-fail or z-pass.
// With several lights each light's colour is divided by their number so that the sum stays
// in range; the counts and masks of StencilShadowFrame are the first light's.
//
//   ShadowMethodRenderer renderer(ShadowMethod::cs, scene, options);  // uploads, compiles
//   StencilShadowFrame frame = renderer.render(target, camera);      // builds, draws, reads
//   renderer.check_capacity();                                        // overflowed? throws
//   FrameTiming t = renderer.time_frames(target, camera, 2, 20, StageSync::none);
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/camera.h"
#include "core/homogeneous_mesh.h"
#include "core/light.h"
#include "core/smoothie_mesh.h"
#include "core/soup.h"
#include "gpu/frame_timing.h"
#include "gpu/gpu_stage_timer.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_map_renderer.h"
#include "gpu/shadow_method.h"
#include "gpu/shadow_volume_set.h"
#include "gpu/sign_mode.h"
#include "gpu/stencil_shadow_renderer.h"
#include "scene/edge_table.h"

namespace shadowcert::gpu {

struct SmoothCasterArrays;  // gpu/smooth_silhouette_volume.h

// What the methods need of a scene. Everything is read (uploaded) during construction only,
// except cpu_volumes, which first_volume() returns: those must outlive the renderer.
struct ShadowMethodScene {
  // The shaded receivers (every mesh of the scene, with its colour); at least one triangle.
  std::span<const ShadedSoupPart> receivers;
  // The lights, at least one (core/light.h; w in {0, 1}).
  std::span<const Light> lights;
  // cs, gs, ts, pertri: the canonical soup of every caster (scene/canonical_soup.h) and its
  // build_edge_table. Ignored by the other methods.
  const Soup* canonical = nullptr;
  const EdgeTable* table = nullptr;
  // cpu: one volume per light, in the lights' order (exact/chain_mesh.h); discrete, accurate,
  // smooth, smooth-gpu: theirs (pipeline/silhouette_volumes.h). Ignored by the other methods.
  std::span<const HomogeneousMesh> cpu_volumes;
  // smooth-gpu: the casters whose smooth volume the GPU builds (pipeline/smooth_caster_arrays.h);
  // null or empty: none. Ignored by the other methods.
  const SmoothCasterArrays* smooth_casters = nullptr;
  // smoothie: one smoothie mesh per light, in the lights' order (pipeline/scene_smoothies.h),
  // uploaded on construction. Ignored by the other methods.
  std::span<const SmoothieMesh> smoothies;
};

struct ShadowMethodOptions {
  StencilMethod stencil = StencilMethod::zfail;  // volume methods
  // Volume methods: one stencil method per light, in the lights' order, overriding `stencil`
  // (--stencil auto: z-pass where pipeline/stencil_choice.h proves it); empty: `stencil` for all.
  std::vector<StencilMethod> light_stencil;
  SignMode sign = SignMode::exact;  // cs, gs, ts, pertri: how s(t) is taken (gpu/sign_mode.h)
  // shadowmap only (gpu/shadow_map_renderer.h): map side in texels, constant and slope bias.
  std::uint32_t shadow_map_size = kDefaultShadowMapSize;
  float shadow_map_bias = kDefaultShadowMapBias;
  float shadow_map_slope = kDefaultShadowMapSlope;
  // pcf: K (odd, [1, kMaxPcfKernel]); pcss: a point light's radius R in world units (finite,
  // > 0; ShadowMapOptions), 0: default_light_radius of the receivers' bounds; a directional
  // light's angular radius in degrees, in (0, kMaxLightAngleDegrees), 0: kDefaultLightAngleDegrees.
  std::uint32_t pcf_kernel = kDefaultPcfKernel;
  double light_radius = 0.0;
  double light_angle_degrees = 0.0;
  // Volume methods: count the first light's volume fragments in render() (StencilShadowFrame).
  bool count_fragments = false;
};

class ShadowMethodRenderer {
 public:
  // Uploads the receivers and the method's inputs and compiles its shaders; needs a current
  // context. Throws std::invalid_argument("ShadowMethodRenderer: ...") when the scene lacks
  // what the method needs (no light, no receiver triangle, no canonical soup or edge table for
  // a GPU-built method, not one cpu volume per light, not one smoothie mesh per light), or for
  // a pcf kernel or pcss light radius out of range, GlError / GlEnvironmentError from the
  // driver, and whatever the method's own constructor throws (e.g. a shadow map size out of
  // range).
  ShadowMethodRenderer(ShadowMethod method, const ShadowMethodScene& scene, const ShadowMethodOptions& options = {});
  ~ShadowMethodRenderer();
  ShadowMethodRenderer(const ShadowMethodRenderer&) = delete;
  ShadowMethodRenderer& operator=(const ShadowMethodRenderer&) = delete;

  [[nodiscard]] ShadowMethod method() const { return method_; }

  // One frame into `target` (bound and cleared here): builds the GPU volumes, draws, reads
  // back colour, the first light's counts, mask and amount of light (first_light). With `timer`
  // (a frame of it open), the build and the passes are timed as its stages.
  StencilShadowFrame render(const OffscreenTarget& target, const Camera& camera, GpuStageTimer* timer = nullptr);

  // `frames` frames without readback, each ended by glFinish; returns each frame's wall time
  // in ms. With `timer`, each frame is one frame of it (begun and ended here).
  std::vector<double> render_frames(const OffscreenTarget& target, const Camera& camera, std::size_t frames,
                                    GpuStageTimer* timer = nullptr);

  // `warm_up` untimed frames (llvmpipe compiles shader variants on first use), then `frames`
  // frames timed by a fresh GpuStageTimer(sync) and the wall clock. Throws
  // std::invalid_argument for frames = 0, GlEnvironmentError without timer queries.
  [[nodiscard]] FrameTiming time_frames(const OffscreenTarget& target, const Camera& camera, std::size_t warm_up,
                                        std::size_t frames, StageSync sync);

  // After a frame, for the GPU-built methods: throws VolumeCapacityError("the cs volume needs
  // more vertices than its GL storage buffers hold (N)") when a light's last build overflowed.
  // Does nothing for cpu and shadowmap. Synchronises with the GPU.
  void check_capacity() const;
  // The first light's volume triangles as drawn (cpu: its mesh's; GPU-built: after a frame,
  // read back; smooth-gpu: both). 0 for shadowmap.
  [[nodiscard]] std::uint64_t volume_triangles() const;
  // The first light's volume as drawn (render --capture): cpu's mesh as uploaded; for the
  // GPU-built methods, after a frame, the read-back triangles, three vertices each (not
  // welded); smooth-gpu: its given mesh, then the read-back triangles. Throws std::logic_error
  // for shadowmap (no volume).
  [[nodiscard]] HomogeneousMesh first_volume() const;

 private:
  StencilShadowFrame draw(const OffscreenTarget& target, const Camera& camera, bool read_back, GpuStageTimer* timer);

  ShadowMethod method_;
  ShadowMethodOptions options_;
  std::vector<Light> lights_;
  std::array<float, 3> light_colour_{};  // each light's share of the default light colour
  ShadedSoupMesh receivers_;
  SceneBounds bounds_;  // shadowmap: what each light's frustum is fitted to
  // The volume methods' volumes (shared with the host layer, gpu/host_shadow_volumes.h).
  std::optional<ShadowVolumeSet> volumes_;
  std::optional<StencilShadowRenderer> stencil_renderer_;
  std::optional<ShadowMapRenderer> shadow_map_renderer_;
  std::vector<std::unique_ptr<SmoothieQuads>> smoothies_;  // smoothie: per light
  std::vector<const SmoothieQuads*> smoothie_views_;       // the same, as ShadowMapOptions takes them
  std::vector<double> nearest_receivers_;  // shadow map: per point light, for a cube map's near plane
};

}  // namespace shadowcert::gpu
