#pragma once
// One scene, every chosen GL shadow method against the exact image (docs/definitions.md#pixel-protocol, docs/diff.md):
// the part `shadowcert diff` and `shadowcert fuzz --gl` share, so that a campaign reproducer's
// `shadowcert diff` command computes exactly what the campaign computed.
//
//   gpu::EglContext context = gpu::open_gl_context("diff", device);  // current on this thread
//   SceneComparison c = compare_scene(scene, methods, {});         // exact image, then GL
//   bool ok = c.passed();                                          // no robust method failed
//
// Per method and light (each light rendered alone, so that every light is compared): the
// frame and its readback, the pixel comparison (reference/pixel_comparison.h) against the exact
// image of the scene and of its float rounding (reference/input_rounding.h), and for the volume
// methods the exact closure of the volume as drawn (exact/volume_closure.h).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene.h"
#include "exact/closure_certificate.h"
#include "reference/exact_image.h"
#include "reference/pixel_comparison.h"
#include "gpu/egl_context.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method_renderer.h"
#include "pipeline/analytic_comparison.h"
#include "pipeline/method_registry.h"
#include "pipeline/scene_smoothies.h"
#include "pipeline/silhouette_volumes.h"
#include "pipeline/soft_reference.h"
#include "pipeline/soft_shadow_comparison.h"
#include "pipeline/stencil_choice.h"

namespace shadowcert {

// Which methods must show zero hard errors and closed volumes, and which are reported only
// (baselines, smooth surfaces): pipeline/method_registry.h's robust(), MethodEntry::robust.

// One method against one light.
struct LightRun {
  PixelComparison comparison;
  gpu::StencilShadowFrame frame;
  std::optional<ClosureCertificate> closure;  // volume methods
  std::uint64_t volume_triangles = 0;
  double gl_ms = 0.0;          // mean wall ms of the timed frames; 0 when none were timed
  std::string capacity_error;  // a GPU-built volume overflowed its buffers (then drawn open)
  // A smooth-silhouette method against the analytic shadow (pipeline/analytic_comparison.h),
  // when the comparison has one (SceneComparison::analytic): reported, never a failure.
  std::optional<AnalyticCounts> analytic;
  // The method's light image against the light's exact soft reference (SceneComparison::soft),
  // when the comparison has one: reported, never a failure.
  std::optional<SoftShadowErrors> soft;
};

struct MethodRun {
  gpu::ShadowMethod method = gpu::ShadowMethod::cpu;
  std::vector<LightRun> lights;
  // Held to the robust rule (failed() on a hard error): robust(method), but a discrete run only
  // when every mesh was cast by discrete or the chain (a mesh's own "silhouette" may ask for
  // accurate or smooth, whose disagreement is their error; pipeline/silhouette_volumes.h).
  bool held_robust = true;

  [[nodiscard]] std::uint64_t sum(std::uint64_t PixelComparison::*figure) const;
  // nullopt for shadowmap (no volume); otherwise whether every light's volume is closed.
  [[nodiscard]] std::optional<bool> closed() const;
  [[nodiscard]] double gl_ms() const;
  // The lights' analytic counts summed; nullopt when the run has none.
  [[nodiscard]] std::optional<AnalyticCounts> analytic() const;
  // A run held robust with a hard error, or any volume method with an open volume.
  [[nodiscard]] bool failed() const;
};

// A ray-traced method (pipeline/method_registry.h's RayTracedMethod: rt, rt-robust) against the
// exact image (pipeline/ray_traced_comparison.h): per light its lit mask compared as a
// mask-only method's (LightRun::frame holds its shaded picture, lit mask and light image;
// gl_ms the run's build and trace time shared among the lights; no closure: no volume).
// Never held to the robust rule: its hard errors are its figure.
struct RayTracedRun {
  RayTracedMethod method = RayTracedMethod::rt;
  std::vector<LightRun> lights;
  double build_seconds = 0.0;  // the hard image's BVH builds (every triangle; the casting ones apart)
  double trace_seconds = 0.0;  // its rays: centre rays and one shadow ray per hit and light
  // With soft references: the K-sample soft images' builds and rays, summed over the lights.
  double soft_build_seconds = 0.0;
  double soft_trace_seconds = 0.0;
  [[nodiscard]] std::uint64_t sum(std::uint64_t PixelComparison::*figure) const;
  [[nodiscard]] double ms() const { return 1000.0 * (build_seconds + trace_seconds); }
};

struct SceneComparisonOptions {
  gpu::ShadowMethodOptions method_options;  // z-fail or z-pass, shadow map size
  // `--stencil auto`: each light counted with z-pass where pipeline/stencil_choice.h proves it
  // at the scene's camera, else z-fail; method_options.stencil is then not read. Either way
  // method_options.light_stencil is not read (each light is rendered alone).
  bool stencil_auto = false;
  // Frames drawn without readback after the compared one, for LightRun::gl_ms (one frame
  // alone would mostly time llvmpipe's first-use compilation); 0: none.
  std::size_t timed_frames = 0;
  bool progress = false;  // the exact image's progress bar on stderr
  SilhouetteOptions silhouette;  // discrete, accurate, smooth (pipeline/silhouette_volumes.h)
  SceneSmoothieOptions smoothie;  // smoothie (pipeline/scene_smoothies.h)
  // When a smooth-silhouette method runs and a mesh casts as a known ellipsoid
  // (has_analytic_caster): the analytic shadow image too, and each such run against it.
  bool analytic = true;
  // With a value: every light's exact soft reference (pipeline/soft_reference.h: a disk light
  // of sampling.radius around a point light, of sampling.angle_degrees about a directional one,
  // K samples) and every method's light image against it (LightRun::soft). sampling.radius 0
  // takes the pcss light radius (method_options.light_radius, or gpu::default_light_radius of the
  // scene) and sampling.angle_degrees 0 pcss's angle (method_options.light_angle_degrees, or
  // gpu::kDefaultLightAngleDegrees), so that both model the same area light.
  std::optional<SoftReferenceOptions> soft;
  // The ray-traced methods to run as well (RayTracedRun), on the CPU in a TBB arena of
  // ray_traced_threads threads (0: every core).
  std::vector<RayTracedMethod> ray_traced;
  unsigned ray_traced_threads = 0;
};

struct SceneComparison {
  ExactImage exact;  // the reference, marked by the float-rounded scene's image
  double rounded_seconds = 0.0;  // the float-rounded scene's exact image
  std::vector<MethodRun> runs;   // one per GL method, in the given order
  std::vector<RayTracedRun> ray_traced;  // one per SceneComparisonOptions::ray_traced, in its order
  // Per light, the stencil method every volume method counted it with, and with stencil_auto
  // the proof that chose it (pipeline/stencil_choice.h); empty when no method draws a volume.
  std::vector<LightStencil> stencil;
  // Per smooth-silhouette method asked for, how each mesh cast (pipeline/silhouette_volumes.h).
  std::vector<SilhouetteVolumes> silhouettes;
  // The analytic shadow of the scene's ellipsoids (SceneComparisonOptions::analytic), which
  // the smooth-silhouette runs were compared with; nullopt when none.
  std::optional<AnalyticShadowImage> analytic;
  // Per light, its exact soft reference (SceneComparisonOptions::soft); empty when not asked.
  std::vector<SoftReference> soft;
  double soft_radius = 0.0;  // the area light's radius the references were made with (point lights)
  double soft_angle_degrees = 0.0;  // and its angular radius (directional lights)

  [[nodiscard]] bool passed() const;  // no GL run failed (a ray-traced run never fails)
};

// The exact image of `scene` (every mesh receives; those with SceneMesh::casts cast) at its
// camera, with the GL depth band (gpu/depth_precision.h), marked by the float-rounded scene's
// image (reference/input_rounding.h): what every GL frame of the scene is compared with. With
// `progress`, a bar on stderr; `rounded_seconds` receives the second image's time.
[[nodiscard]] ExactImage reference_image(const Scene& scene, bool progress = false,
                                         double* rounded_seconds = nullptr);

// One frame of `renderer` (built for light `light` of the scene alone, pipeline/method_inputs.h's
// light_scene) into `target`, compared with `exact` (reference_image of the scene, `camera`'s
// size): the readback against light `light`'s exact answer; for a volume method the exact
// closure of the volume as drawn; a capacity overflow recorded, not thrown (the open volume is
// still compared and certified). Then `timed_frames` frames without readback for gl_ms.
// Throws what the renderer and compare_pixels throw (a size mismatch among them).
[[nodiscard]] LightRun compare_light(gpu::ShadowMethodRenderer& renderer, const ExactImage& exact, std::size_t light,
                                     const gpu::OffscreenTarget& target, const Camera& camera,
                                     std::size_t timed_frames = 0);

// The reference and every method on `scene` (every mesh receives; the meshes that cast,
// SceneMesh::casts, cast, as in the GL methods), the GL `methods` and options.ray_traced.
// Preconditions: a GL context is current on this thread when `methods` is not empty; the scene
// has at least one light and one triangle, and some method is asked for
// (std::invalid_argument("compare_scene: ...") otherwise). Throws what the renderers, the ray
// tracer and the exact image throw.
[[nodiscard]] SceneComparison compare_scene(const Scene& scene, const std::vector<gpu::ShadowMethod>& methods,
                                            const SceneComparisonOptions& options);

}  // namespace shadowcert
