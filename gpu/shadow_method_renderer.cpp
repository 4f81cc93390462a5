#include "gpu/shadow_method_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "gpu/compute_volume.h"
#include "gpu/geometry_shader_volume.h"
#include "gpu/per_triangle_volume.h"
#include "gpu/smooth_silhouette_volume.h"
#include "gpu/tessellation_volume.h"

namespace shadowcert::gpu {

// The four GPU-built volume classes share build/draw/readback member functions but no base
// class (each stays a plain value type of its own header); this gives them one here.
class ShadowMethodRenderer::BuiltVolume {
 public:
  virtual ~BuiltVolume() = default;
  virtual void build(const Light& light) = 0;
  [[nodiscard]] virtual IndirectVolumeDraw draw() const = 0;
  [[nodiscard]] virtual std::uint64_t capacity_vertices() const = 0;
  [[nodiscard]] virtual std::uint64_t read_requested_vertices() const = 0;
  [[nodiscard]] virtual std::vector<VolumeTriangle> read_triangles() const = 0;
};

namespace {

template <class Volume>
class BuiltVolumeOf final : public ShadowMethodRenderer::BuiltVolume {
 public:
  template <class... Args>
  explicit BuiltVolumeOf(const Args&... args) : volume_(args...) {}
  void build(const Light& light) override { volume_.build(light); }
  [[nodiscard]] IndirectVolumeDraw draw() const override { return volume_.draw(); }
  [[nodiscard]] std::uint64_t capacity_vertices() const override { return volume_.capacity_vertices(); }
  [[nodiscard]] std::uint64_t read_requested_vertices() const override { return volume_.read_requested_vertices(); }
  [[nodiscard]] std::vector<VolumeTriangle> read_triangles() const override { return volume_.read_triangles(); }

 private:
  Volume volume_;
};

std::unique_ptr<ShadowMethodRenderer::BuiltVolume> make_built_volume(ShadowMethod method,
                                                                     const ComputeVolumeSoup& soup,
                                                                     const EdgeTable& table, SignMode sign) {
  switch (method) {
    case ShadowMethod::cs: return std::make_unique<BuiltVolumeOf<ComputeShadowVolume>>(soup, sign);
    case ShadowMethod::gs: return std::make_unique<BuiltVolumeOf<GeometryShaderShadowVolume>>(soup, table, sign);
    case ShadowMethod::ts: return std::make_unique<BuiltVolumeOf<TessellationShadowVolume>>(soup, table, sign);
    case ShadowMethod::pertri: return std::make_unique<BuiltVolumeOf<PerTriangleShadowVolume>>(soup, sign);
    case ShadowMethod::cpu:
    case ShadowMethod::shadowmap:
    case ShadowMethod::pcf:
    case ShadowMethod::pcss:
    case ShadowMethod::smoothie:
    case ShadowMethod::discrete:
    case ShadowMethod::accurate:
    case ShadowMethod::smooth:
    case ShadowMethod::smooth_gpu: break;
  }
  throw std::logic_error("make_built_volume: " + std::string(shadow_method_name(method)) +
                         " builds no volume on the GPU");
}

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
  if (draws_given_volume(method)) {
    if (scene.cpu_volumes.size() != lights_.size())
      throw std::invalid_argument("ShadowMethodRenderer: " + std::string(shadow_method_name(method)) +
                                  " needs one volume per light (" +
                                  std::to_string(scene.cpu_volumes.size()) + " for " +
                                  std::to_string(lights_.size()) + " lights)");
    cpu_meshes_ = scene.cpu_volumes;
    const bool smooth_gpu = method == ShadowMethod::smooth_gpu;
    if (smooth_gpu && scene.smooth_casters != nullptr && !scene.smooth_casters->triangles.empty())
      smooth_casters_ = std::make_unique<SmoothCasterBuffers>(*scene.smooth_casters);
    for (std::size_t i = 0; i < lights_.size(); ++i) {
      LightVolume volume{lights_[i]};
      // smooth-gpu draws its given volume only where there is one (the meshes it does not build).
      if (!smooth_gpu || !scene.cpu_volumes[i].triangles.empty()) {
        cpu_volumes_.push_back(std::make_unique<ShadowVolumeMesh>(scene.cpu_volumes[i]));
        volume.volume = cpu_volumes_.back().get();
      }
      if (smooth_casters_) {
        built_volumes_.push_back(std::make_unique<BuiltVolumeOf<SmoothSilhouetteVolume>>(*smooth_casters_));
        volume.indirect = built_volumes_.back()->draw();
      }
      if (volume.volume == nullptr && !smooth_casters_) {
        // Nothing casts: an empty volume counts nothing, as it should.
        cpu_volumes_.push_back(std::make_unique<ShadowVolumeMesh>(scene.cpu_volumes[i]));
        volume.volume = cpu_volumes_.back().get();
      }
      light_volumes_.push_back(volume);
    }
  } else {
    if (scene.canonical == nullptr || scene.table == nullptr)
      throw std::invalid_argument("ShadowMethodRenderer: " + std::string(shadow_method_name(method)) +
                                  " needs the canonical soup and its edge table");
    gpu_soup_ = std::make_unique<ComputeVolumeSoup>(*scene.canonical, *scene.table);
    for (const Light& light : lights_) {
      built_volumes_.push_back(make_built_volume(method, *gpu_soup_, *scene.table, options.sign));
      light_volumes_.push_back({light, nullptr, built_volumes_.back()->draw()});
    }
  }
  if (!options.light_stencil.empty()) {
    if (options.light_stencil.size() != lights_.size())
      throw std::invalid_argument("ShadowMethodRenderer: light_stencil needs one stencil method per light (" +
                                  std::to_string(options.light_stencil.size()) + " for " +
                                  std::to_string(lights_.size()) + " lights)");
    for (std::size_t i = 0; i < lights_.size(); ++i) light_volumes_[i].stencil = options.light_stencil[i];
  }
  stencil_renderer_.emplace();
}

ShadowMethodRenderer::~ShadowMethodRenderer() = default;

void ShadowMethodRenderer::build_volumes(GpuStageTimer* timer) {
  if (built_volumes_.empty()) return;
  const ScopedStage stage(timer, RenderStage::volume);
  for (std::size_t i = 0; i < built_volumes_.size(); ++i) built_volumes_[i]->build(lights_[i]);
}

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
  build_volumes(timer);
  StencilShadowOptions o;
  o.method = options_.stencil;
  o.light_colour = light_colour_;
  o.read_back = read_back;
  o.count_fragments = read_back && options_.count_fragments;  // render() only: never in timed frames
  o.timer = timer;
  return stencil_renderer_->render(target, receivers_, camera, light_volumes_, o);
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
  for (const auto& volume : built_volumes_) {
    if (volume->read_requested_vertices() > volume->capacity_vertices())
      throw VolumeCapacityError("the " + std::string(shadow_method_name(method_)) +
                                " volume needs more vertices than its GL storage buffers hold (" +
                                std::to_string(volume->capacity_vertices()) + ")");
  }
}

std::uint64_t ShadowMethodRenderer::volume_triangles() const {
  std::uint64_t triangles = cpu_meshes_.empty() ? 0 : cpu_meshes_.front().triangles.size();
  if (!built_volumes_.empty()) {
    const auto& v = *built_volumes_.front();
    triangles += std::min(v.read_requested_vertices(), v.capacity_vertices()) / 3;  // what the draw covers
  }
  return triangles;
}

HomogeneousMesh ShadowMethodRenderer::first_volume() const {
  if (cpu_meshes_.empty() && built_volumes_.empty())
    throw std::logic_error("ShadowMethodRenderer::first_volume: " + std::string(shadow_method_name(method_)) +
                           " draws no volume");
  HomogeneousMesh mesh;
  if (!cpu_meshes_.empty()) mesh = cpu_meshes_.front();
  if (built_volumes_.empty()) return mesh;
  const std::vector<VolumeTriangle> triangles = built_volumes_.front()->read_triangles();
  mesh.vertices.reserve(3 * triangles.size());
  mesh.triangles.reserve(triangles.size());
  for (const VolumeTriangle& t : triangles) {
    const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), t.begin(), t.end());
    mesh.triangles.push_back({first, first + 1, first + 2});
  }
  return mesh;
}

}  // namespace shadowcert::gpu
