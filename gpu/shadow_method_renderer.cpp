#include "gpu/shadow_method_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "gpu/smooth_silhouette_volume.h"

namespace shadowcert::gpu {

namespace {

// The bounds of every part's referenced vertices (parts without triangles add nothing).
SceneBounds receiver_bounds(std::span<const ShadedSoupPart> parts) {
  std::optional<SceneBounds> all;
  for (const ShadedSoupPart& part : parts) {
    if (part.soup == nullptr || part.soup->triangles.empty()) continue;
    const SceneBounds b = soup_bounds(*part.soup);
    if (!all) {
      all = b;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      all->lo[k] = std::min(all->lo[k], b.lo[k]);
      all->hi[k] = std::max(all->hi[k], b.hi[k]);
    }
  }
  if (!all) throw std::invalid_argument("ShadowMethodRenderer: no receiver triangle");
  return *all;
}

using Clock = std::chrono::steady_clock;

}  // namespace

std::vector<RenderStage> method_stages(ShadowMethod method) {
  if (method == ShadowMethod::smoothie)
    return {RenderStage::depth, RenderStage::shadow_map, RenderStage::smoothie_map, RenderStage::lit};
  if (uses_shadow_map(method)) return {RenderStage::depth, RenderStage::shadow_map, RenderStage::lit};
  return {RenderStage::volume, RenderStage::depth, RenderStage::stencil, RenderStage::lit};
}

ShadowMethodRenderer::ShadowMethodRenderer(ShadowMethod method, const ShadowMethodScene& scene,
                                           const ShadowMethodOptions& options)
    : method_(method),
      options_(options),
      lights_(scene.lights.begin(), scene.lights.end()),
      receivers_(scene.receivers),
      bounds_(receiver_bounds(scene.receivers)) {
  if (lights_.empty()) throw std::invalid_argument("ShadowMethodRenderer: no light");
  light_colour_ = StencilShadowOptions{}.light_colour;
  for (float& c : light_colour_) c /= static_cast<float>(lights_.size());

  if (uses_shadow_map(method)) {
    if (method == ShadowMethod::pcf &&
        (options.pcf_kernel < 1 || options.pcf_kernel > kMaxPcfKernel || options.pcf_kernel % 2 == 0))
      throw std::invalid_argument("ShadowMethodRenderer: the pcf kernel must be odd and in [1, " +
                                  std::to_string(kMaxPcfKernel) + "], got " + std::to_string(options.pcf_kernel));
    if (method == ShadowMethod::pcss) {
      if (!std::isfinite(options.light_radius) || options.light_radius < 0.0)
        throw std::invalid_argument("ShadowMethodRenderer: the pcss light radius must be finite and >= 0 (0: the "
                                    "default), got " + std::to_string(options.light_radius));
      if (options.light_radius == 0.0) options_.light_radius = default_light_radius(bounds_);
      if (!std::isfinite(options.light_angle_degrees) || options.light_angle_degrees < 0.0 ||
          !(options.light_angle_degrees < kMaxLightAngleDegrees))
        throw std::invalid_argument("ShadowMethodRenderer: the pcss light angle must be in [0, 90) degrees (0: the "
                                    "default), got " + std::to_string(options.light_angle_degrees));
      if (options.light_angle_degrees == 0.0) options_.light_angle_degrees = kDefaultLightAngleDegrees;
    }
    // A point light inside or next to the bounds gets a cube map, whose near plane is the
    // nearest receiver's distance (light_views): measured once here, from the parts as drawn.
    for (const Light& light : lights_)
      nearest_receivers_.push_back(needs_cube_map(light, bounds_) ? nearest_receiver_distance(scene.receivers, light)
                                                                  : 0.0);
    if (method == ShadowMethod::smoothie) {
      if (scene.smoothies.size() != lights_.size())
        throw std::invalid_argument("ShadowMethodRenderer: smoothie needs one smoothie mesh per light (" +
                                    std::to_string(scene.smoothies.size()) + " for " +
                                    std::to_string(lights_.size()) + " lights)");
      for (const SmoothieMesh& mesh : scene.smoothies) {
        smoothies_.push_back(std::make_unique<SmoothieQuads>(mesh));
        smoothie_views_.push_back(smoothies_.back().get());
      }
    }
    shadow_map_renderer_.emplace(options.shadow_map_size, shadow_filter(method));
    return;
  }
  volumes_.emplace(method, scene, options.sign, options.light_stencil, "ShadowMethodRenderer");
  stencil_renderer_.emplace();
}

ShadowMethodRenderer::~ShadowMethodRenderer() = default;

StencilShadowFrame ShadowMethodRenderer::draw(const OffscreenTarget& target, const Camera& camera, bool read_back,
                                              GpuStageTimer* timer) {
  if (shadow_map_renderer_) {
    ShadowMapOptions o;
    o.depth_bias = options_.shadow_map_bias;
    o.slope_scale = options_.shadow_map_slope;
    o.light_colour = light_colour_;
    o.read_back = read_back;
    o.timer = timer;
    o.pcf_kernel = options_.pcf_kernel;
    o.light_radius = options_.light_radius;
    o.light_angle_degrees = options_.light_angle_degrees > 0.0 ? options_.light_angle_degrees : kDefaultLightAngleDegrees;
    o.nearest_receivers = nearest_receivers_;
    o.smoothies = smoothie_views_;
    return shadow_map_renderer_->render(target, receivers_, bounds_, camera, lights_, o);
  }
  volumes_->build(timer);
  StencilShadowOptions o;
  o.method = options_.stencil;
  o.light_colour = light_colour_;
  o.read_back = read_back;
  o.count_fragments = read_back && options_.count_fragments;  // render() only: never in timed frames
  o.timer = timer;
  return stencil_renderer_->render(target, receivers_, camera, volumes_->light_volumes(), o);
}

StencilShadowFrame ShadowMethodRenderer::render(const OffscreenTarget& target, const Camera& camera,
                                                GpuStageTimer* timer) {
  return draw(target, camera, true, timer);
}

std::vector<double> ShadowMethodRenderer::render_frames(const OffscreenTarget& target, const Camera& camera,
                                                        std::size_t frames, GpuStageTimer* timer) {
  std::vector<double> wall_ms;
  wall_ms.reserve(frames);
  for (std::size_t i = 0; i < frames; ++i) {
    const auto start = Clock::now();
    if (timer != nullptr) timer->begin_frame();
    (void)draw(target, camera, false, timer);
    if (timer != nullptr) timer->end_frame();
    glFinish();
    wall_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  return wall_ms;
}

FrameTiming ShadowMethodRenderer::time_frames(const OffscreenTarget& target, const Camera& camera,
                                              std::size_t warm_up, std::size_t frames, StageSync sync) {
  if (frames == 0) throw std::invalid_argument("ShadowMethodRenderer::time_frames: frames must be at least 1");
  (void)render_frames(target, camera, warm_up);
  GpuStageTimer timer(sync);
  const std::vector<double> wall_ms = render_frames(target, camera, frames, &timer);
  const std::vector<FrameStageTimes> gpu = timer.collect();
  return summarize_frames(method_stages(method_), sync, gpu, wall_ms);
}

void ShadowMethodRenderer::check_capacity() const {
  if (volumes_) volumes_->check_capacity();
}

std::uint64_t ShadowMethodRenderer::volume_triangles() const { return volumes_ ? volumes_->volume_triangles() : 0; }

HomogeneousMesh ShadowMethodRenderer::first_volume() const {
  if (!volumes_)
    throw std::logic_error("ShadowMethodRenderer::first_volume: " + std::string(shadow_method_name(method_)) +
                           " draws no volume");
  return volumes_->first_volume();
}

}  // namespace shadowcert::gpu
