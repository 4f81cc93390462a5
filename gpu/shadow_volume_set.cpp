#include "gpu/shadow_volume_set.h"

#include <algorithm>
#include <string>

#include "gpu/compute_volume.h"
#include "gpu/geometry_shader_volume.h"
#include "gpu/per_triangle_volume.h"
#include "gpu/shadow_method_renderer.h"
#include "gpu/smooth_silhouette_volume.h"
#include "gpu/tessellation_volume.h"

namespace shadowcert::gpu {

// The GPU-built volume classes share build/draw/readback member functions but no base class
// (each stays a plain value type of its own header); this gives them one here.
class ShadowVolumeSet::BuiltVolume {
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
class BuiltVolumeOf final : public ShadowVolumeSet::BuiltVolume {
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

std::unique_ptr<ShadowVolumeSet::BuiltVolume> make_built_volume(ShadowMethod method, const ComputeVolumeSoup& soup,
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

}  // namespace

ShadowVolumeSet::ShadowVolumeSet(ShadowMethod method, const ShadowMethodScene& scene, SignMode sign,
                                 std::span<const StencilMethod> light_stencil, std::string_view who)
    : method_(method), lights_(scene.lights.begin(), scene.lights.end()) {
  const std::string prefix = std::string(who) + ": ";
  if (!draws_volume(method))
    throw std::invalid_argument(prefix + std::string(shadow_method_name(method)) + " draws no shadow volume");
  if (lights_.empty()) throw std::invalid_argument(prefix + "no light");
  if (draws_given_volume(method)) {
    if (scene.cpu_volumes.size() != lights_.size())
      throw std::invalid_argument(prefix + std::string(shadow_method_name(method)) + " needs one volume per light (" +
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
      throw std::invalid_argument(prefix + std::string(shadow_method_name(method)) +
                                  " needs the canonical soup and its edge table");
    gpu_soup_ = std::make_unique<ComputeVolumeSoup>(*scene.canonical, *scene.table);
    canonical_vertices_ = static_cast<std::uint32_t>(scene.canonical->vertices.size());  // checked by the soup
    for (const Light& light : lights_) {
      built_volumes_.push_back(make_built_volume(method, *gpu_soup_, *scene.table, sign));
      light_volumes_.push_back({light, nullptr, built_volumes_.back()->draw()});
    }
  }
  if (!light_stencil.empty()) {
    if (light_stencil.size() != lights_.size())
      throw std::invalid_argument(prefix + "light_stencil needs one stencil method per light (" +
                                  std::to_string(light_stencil.size()) + " for " + std::to_string(lights_.size()) +
                                  " lights)");
    for (std::size_t i = 0; i < lights_.size(); ++i) light_volumes_[i].stencil = light_stencil[i];
  }
}

ShadowVolumeSet::~ShadowVolumeSet() = default;

GLuint ShadowVolumeSet::canonical_vertex_buffer() const { return gpu_soup_ ? gpu_soup_->vertex_buffer() : 0; }

void ShadowVolumeSet::set_light(std::size_t k, const Light& light) {
  if (!builds_volume_on_gpu(method_))
    throw std::invalid_argument("ShadowVolumeSet::set_light: " + std::string(shadow_method_name(method_)) +
                                "'s volumes are given per light; build a new set for another light");
  if (k >= lights_.size())
    throw std::out_of_range("ShadowVolumeSet::set_light: light " + std::to_string(k) + " of " +
                            std::to_string(lights_.size()));
  require_defined(light, "ShadowVolumeSet::set_light");
  lights_[k] = light;
  light_volumes_[k].light = light;
}

void ShadowVolumeSet::build(GpuStageTimer* timer) {
  if (built_volumes_.empty()) return;
  const ScopedStage stage(timer, RenderStage::volume);
  for (std::size_t i = 0; i < built_volumes_.size(); ++i) built_volumes_[i]->build(lights_[i]);
}

void ShadowVolumeSet::check_capacity() const {
  for (const auto& volume : built_volumes_) {
    if (volume->read_requested_vertices() > volume->capacity_vertices())
      throw VolumeCapacityError("the " + std::string(shadow_method_name(method_)) +
                                " volume needs more vertices than its GL storage buffers hold (" +
                                std::to_string(volume->capacity_vertices()) + ")");
  }
}

std::uint64_t ShadowVolumeSet::volume_triangles() const {
  std::uint64_t triangles = cpu_meshes_.empty() ? 0 : cpu_meshes_.front().triangles.size();
  if (!built_volumes_.empty()) {
    const auto& v = *built_volumes_.front();
    triangles += std::min(v.read_requested_vertices(), v.capacity_vertices()) / 3;  // what the draw covers
  }
  return triangles;
}

HomogeneousMesh ShadowVolumeSet::first_volume() const {
  HomogeneousMesh mesh;
  if (!cpu_meshes_.empty()) mesh = cpu_meshes_.front();
  if (built_volumes_.empty()) return mesh;
  const std::vector<VolumeTriangle> triangles = built_volumes_.front()->read_triangles();
  mesh.vertices.reserve(mesh.vertices.size() + 3 * triangles.size());
  mesh.triangles.reserve(mesh.triangles.size() + triangles.size());
  for (const VolumeTriangle& t : triangles) {
    const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), t.begin(), t.end());
    mesh.triangles.push_back({first, first + 1, first + 2});
  }
  return mesh;
}

}  // namespace shadowcert::gpu
