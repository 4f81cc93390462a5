#include "pipeline/scene_comparison.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <span>
#include <stdexcept>

#include "exact/volume_closure.h"
#include "gpu/depth_precision.h"
#include "gpu/shadow_map_renderer.h"
#include "pipeline/mesh_palette.h"
#include "pipeline/method_inputs.h"
#include "pipeline/ray_traced_comparison.h"
#include "reference/input_rounding.h"
#include "core/eye_frame.h"
#include "scene/merged_soup.h"

namespace shadowcert {
namespace {

// The exact image's options: the GL depth band of `camera`'s near plane, and with `progress` a
// bar on stderr.
ExactImageOptions exact_options(const Camera& camera, bool progress) {
  ExactImageOptions options;
  options.depth_band = [near = camera.near_plane](double view_depth) { return gpu::depth_band(view_depth, near); };
  if (!progress) return options;
  options.progress = [](std::string_view stage, std::uint64_t done, std::uint64_t total) {
    constexpr int kBarWidth = 32;
    const double fraction = total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total);
    const auto filled = static_cast<std::size_t>(fraction * kBarWidth);
    fmt::print(stderr, "\rexact image, {:<6} [{}{}] {:3.0f}%", stage, std::string(filled, '#'),
               std::string(kBarWidth - filled, '.'), 100.0 * fraction);
    if (done >= total) fmt::print(stderr, "\n");
    std::fflush(stderr);
  };
  return options;
}

// The frame's coverage: 255 where a receiver was drawn (alpha), else 0.
std::vector<std::uint8_t> coverage(const gpu::RgbaImage& colour) {
  std::vector<std::uint8_t> c(std::size_t{colour.width} * colour.height);
  for (std::size_t p = 0; p < c.size(); ++p) c[p] = colour.pixels[4 * p + 3] != 0 ? 255 : 0;
  return c;
}

// reference_image of `scene`, whose merged soup the caller has (compare_scene merges once).
// Every triangle of the scene receives, and those of the meshes that cast (SceneMesh::casts)
// cast, as in the GL methods. The GPU gets the scene in float: where that rounding changes the
// exact answer, the pixel is ambiguous (reference/input_rounding.h), so the scene is imaged twice.
ExactImage reference_image_of(const Soup& merged, const Scene& scene, bool progress, double* rounded_seconds) {
  ExactImageOptions options = exact_options(scene.camera, progress);
  if (!std::all_of(scene.meshes.begin(), scene.meshes.end(), [](const SceneMesh& m) { return m.casts; }))
    options.casts = casting_triangles(scene);
  return exact_image_of_float_input(merged, scene.lights, scene.camera, options, rounded_seconds);
}

// Whether every mesh was cast by discrete or the robust chain (or not at all): then the volume
// shadows what the exact chain shadows, and the run is held to the robust rule.
bool chain_shadows_only(const SilhouetteVolumes& volumes) {
  return std::all_of(volumes.casters.begin(), volumes.casters.end(), [](const SilhouetteCaster& c) {
    return !c.cast_by || *c.cast_by == gpu::ShadowMethod::discrete;
  });
}

}  // namespace

std::uint64_t MethodRun::sum(std::uint64_t PixelComparison::*figure) const {
  std::uint64_t n = 0;
  for (const LightRun& l : lights) n += l.comparison.*figure;
  return n;
}

std::optional<bool> MethodRun::closed() const {
  if (!gpu::draws_volume(method)) return std::nullopt;
  return std::all_of(lights.begin(), lights.end(), [](const LightRun& l) { return l.closure && l.closure->closed; });
}

double MethodRun::gl_ms() const {
  return std::accumulate(lights.begin(), lights.end(), 0.0, [](double s, const LightRun& l) { return s + l.gl_ms; });
}

std::optional<AnalyticCounts> MethodRun::analytic() const {
  std::optional<AnalyticCounts> sum;
  for (const LightRun& l : lights)
    if (l.analytic) (sum ? *sum : sum.emplace()) += *l.analytic;
  return sum;
}

bool MethodRun::failed() const {
  return closed() == false || (held_robust && sum(&PixelComparison::hard_errors) > 0);
}

bool SceneComparison::passed() const {
  return std::none_of(runs.begin(), runs.end(), [](const MethodRun& r) { return r.failed(); });
}

ExactImage reference_image(const Scene& scene, bool progress, double* rounded_seconds) {
  return reference_image_of(merged_soup(scene), scene, progress, rounded_seconds);
}

LightRun compare_light(gpu::ShadowMethodRenderer& renderer, const ExactImage& exact, std::size_t light,
                       const gpu::OffscreenTarget& target, const Camera& camera, std::size_t timed_frames) {
  const gpu::ShadowMethod method = renderer.method();
  LightRun l;
  l.frame = renderer.render(target, camera);
  try {
    renderer.check_capacity();
  } catch (const gpu::VolumeCapacityError& e) {
    l.capacity_error = e.what();  // what was drawn is still compared and certified (open)
  }
  const std::vector<std::uint8_t> covered = coverage(l.frame.colour);
  RenderedPixels rendered{camera.width, camera.height, covered, l.frame.first_lit_mask.pixels, {}};
  // The chain methods' stencil counts are n(P) itself, and so are discrete's (on a qualifying
  // caster it is the exact chain; pipeline/silhouette_volumes.h). accurate and smooth shadow
  // another surface: only their lit masks are compared, as the shadow map's.
  if (gpu::draws_volume(method) && !gpu::shadows_smooth_surface(method))
    rendered.counts = l.frame.first_stencil.pixels;
  l.comparison = compare_pixels(exact, light, rendered);
  if (gpu::draws_volume(method)) {
    l.closure = certify_volume_closure(renderer.first_volume()).certificate;
    l.volume_triangles = renderer.volume_triangles();
  }
  if (timed_frames > 0) {
    const std::vector<double> ms = renderer.render_frames(target, camera, timed_frames);
    l.gl_ms = std::accumulate(ms.begin(), ms.end(), 0.0) / static_cast<double>(ms.size());
  }
  return l;
}

SceneComparison compare_scene(const Scene& scene, const std::vector<gpu::ShadowMethod>& methods,
                              const SceneComparisonOptions& options) {
  if (scene.lights.empty()) throw std::invalid_argument("compare_scene: the scene has no light");
  if (methods.empty() && options.ray_traced.empty()) throw std::invalid_argument("compare_scene: no method");
  const Soup merged = merged_soup(scene);
  if (merged.triangles.empty()) throw std::invalid_argument("compare_scene: the scene has no triangle");

  SceneComparison result;
  result.exact = reference_image_of(merged, scene, options.progress, &result.rounded_seconds);
  const bool silhouette_methods = std::any_of(methods.begin(), methods.end(), gpu::is_silhouette_method);
  // The exact soft references, in world space as the exact image, one per light; the area light
  // is pcss's unless the options name a radius.
  if (options.soft) {
    SoftReferenceOptions soft = *options.soft;
    if (soft.sampling.radius == 0.0)
      soft.sampling.radius = options.method_options.light_radius > 0.0
                                 ? options.method_options.light_radius
                                 : gpu::default_light_radius(gpu::soup_bounds(merged));
    if (soft.sampling.angle_degrees == 0.0)
      soft.sampling.angle_degrees = options.method_options.light_angle_degrees > 0.0
                                        ? options.method_options.light_angle_degrees
                                        : gpu::kDefaultLightAngleDegrees;
    result.soft_radius = soft.sampling.radius;
    result.soft_angle_degrees = soft.sampling.angle_degrees;
    for (std::size_t k = 0; k < scene.lights.size(); ++k) result.soft.push_back(soft_reference(scene, k, soft));
  }
  // The analytic truth is the world scene's (its ellipsoids are in world space).
  if (options.analytic && silhouette_methods && has_analytic_caster(scene))
    result.analytic = analytic_reference(scene, options.silhouette.crease_angle_degrees);
  // The ray-traced methods trace the world scene, as the exact image does (no GL context).
  for (const RayTracedMethod method : options.ray_traced)
    result.ray_traced.push_back(compare_ray_traced(scene, method, result.exact, result.soft, options.ray_traced_threads));
  if (methods.empty()) return result;
  // The GL methods draw the scene in its eye's frame (core/eye_frame.h), which the reference's
  // float-rounded image models.
  const Scene drawn = eye_relative_scene(scene);
  MethodInputs inputs = prepare_method_inputs(merged_casters(drawn), drawn.lights, methods);
  if (std::find(methods.begin(), methods.end(), gpu::ShadowMethod::smoothie) != methods.end())
    add_smoothies(inputs, drawn.lights, gpu::soup_bounds(merged_soup(drawn)), options.smoothie);
  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(drawn);
  const gpu::OffscreenTarget target(scene.camera.width, scene.camera.height);
  if (std::any_of(methods.begin(), methods.end(), gpu::draws_volume)) {
    const StencilChoice choice = options.stencil_auto ? StencilChoice::automatic
                                 : options.method_options.stencil == gpu::StencilMethod::zpass ? StencilChoice::zpass
                                                                                                : StencilChoice::zfail;
    result.stencil = choose_stencil(choice, inputs, drawn.lights, drawn.camera);
  }
  for (gpu::ShadowMethod method : methods) {
    const SilhouetteVolumes* silhouette = nullptr;
    if (gpu::is_silhouette_method(method)) {
      SilhouetteOptions silhouette_options = options.silhouette;
      silhouette_options.near_plane = drawn.camera.near_plane;  // the meshes are in the eye's frame
      result.silhouettes.push_back(silhouette_volumes(drawn.meshes, drawn.lights, method, silhouette_options));
      silhouette = &result.silhouettes.back();
    }
    MethodRun run{method, {}, robust(method) && (silhouette == nullptr || chain_shadows_only(*silhouette))};
    for (std::size_t k = 0; k < drawn.lights.size(); ++k) {
      gpu::ShadowMethodOptions method_options = options.method_options;
      method_options.light_stencil.clear();
      if (!result.stencil.empty()) method_options.light_stencil.assign(1, result.stencil[k].method);
      // The z-pass proof is about the exact chain; a smooth-silhouette volume is another one.
      if (silhouette != nullptr) method_options.light_stencil.assign(1, gpu::StencilMethod::zfail);
      gpu::ShadowMethodRenderer renderer(
          method, light_scene(inputs, parts, drawn.lights, k, silhouette ? &silhouette->per_light[k] : nullptr,
                              silhouette ? &silhouette->gpu_casters : nullptr),
          method_options);
      run.lights.push_back(compare_light(renderer, result.exact, k, target, drawn.camera, options.timed_frames));
      if (!result.soft.empty())
        run.lights.back().soft = compare_soft_shadow(result.soft[k], run.lights.back().frame.first_light);
      if (silhouette != nullptr && result.analytic)
        run.lights.back().analytic = compare_analytic(*result.analytic, k, run.lights.back().frame);
    }
    result.runs.push_back(std::move(run));
  }
  return result;
}

}  // namespace shadowcert
