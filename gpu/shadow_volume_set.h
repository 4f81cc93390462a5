#pragma once
// Every light's shadow volume of one volume method (cpu, cs, gs, ts, pertri, discrete,
// accurate, smooth, smooth-gpu) on the GPU, ready to be counted: the given volumes uploaded,
// the GPU-built ones (gpu/compute_volume.h and its peers) with their buffers, and per light
// the LightVolume the stencil passes draw (gpu/stencil_passes.h). The offscreen renderer
// (gpu/shadow_method_renderer.h) and the host layer (gpu/host_shadow_volumes.h) both hold one,
// so "method M's volume of light k" is the same GL objects, built by the same calls, in both.
//
//   ShadowVolumeSet set(ShadowMethod::cs, scene, options, "ShadowMethodRenderer");
//   set.build(timer);                   // cs, gs, ts, pertri, smooth-gpu: queue the builds
//   count_volume(set.light_volumes()[k], StencilMethod::zfail);
//   set.check_capacity();               // waits for the GPU; throws VolumeCapacityError
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/homogeneous_mesh.h"
#include "core/light.h"
#include "gpu/gpu_stage_timer.h"
#include "gpu/shadow_method.h"
#include "gpu/sign_mode.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu {

class ComputeVolumeSoup;    // gpu/compute_volume.h
class SmoothCasterBuffers;  // gpu/smooth_silhouette_volume.h
struct ShadowMethodScene;   // gpu/shadow_method_renderer.h

// A GPU-built volume needed more vertices than its buffers hold: drawing it would draw an
// open volume, so callers report this instead of an image.
class VolumeCapacityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ShadowVolumeSet {
 public:
  // `scene`: its lights (at least one), and what `method` reads of it (ShadowMethodScene says
  // which); cpu_volumes must outlive this object (first_volume() returns them).
  // `sign`: how cs, gs, ts and pertri take s(t). `light_stencil`: empty, or one stencil method
  // per light (LightVolume::stencil). `who` prefixes the messages: throws
  // std::invalid_argument("<who>: ...") for a shadow-map method, no light, a GPU-built method
  // without the canonical soup and table, not one given volume per light, or a light_stencil
  // of another size; GlError / GlEnvironmentError from the driver.
  ShadowVolumeSet(ShadowMethod method, const ShadowMethodScene& scene, SignMode sign,
                  std::span<const StencilMethod> light_stencil, std::string_view who);
  ~ShadowVolumeSet();
  ShadowVolumeSet(const ShadowVolumeSet&) = delete;
  ShadowVolumeSet& operator=(const ShadowVolumeSet&) = delete;

  [[nodiscard]] ShadowMethod method() const { return method_; }
  [[nodiscard]] std::span<const Light> lights() const { return lights_; }
  // Per light, in the lights' order: what count_volume draws.
  [[nodiscard]] std::span<const LightVolume> light_volumes() const { return light_volumes_; }

  // cs, gs, ts, pertri: the canonical soup's vertices as the builds read them (vec4, w = 1,
  // in canonical order); 0 for the other methods. gpu/host_vertex_gather.h overwrites them
  // from a host's vertex buffer.
  [[nodiscard]] GLuint canonical_vertex_buffer() const;
  [[nodiscard]] std::uint32_t canonical_vertex_count() const { return canonical_vertices_; }

  // Moves light k (a moving light): the GPU-built volumes (cs, gs, ts, pertri) follow at the
  // next build(). Throws std::invalid_argument("ShadowVolumeSet::set_light: ...") for the
  // methods whose volume the caller builds per light (cpu and the silhouette methods: their
  // volume would no longer be the light's) and std::out_of_range for k out of range.
  void set_light(std::size_t k, const Light& light);

  // Queues every light's GPU build (cs, gs, ts, pertri, smooth-gpu) for its light, as stage
  // `volume` of `timer` when given; nothing for the given volumes. Never waits for the GPU.
  void build(GpuStageTimer* timer = nullptr);

  // After a build: throws VolumeCapacityError("the cs volume needs more vertices than its GL
  // storage buffers hold (N)") when a light's last build overflowed. Waits for the GPU.
  void check_capacity() const;
  // The first light's volume triangles as drawn (read back for the GPU-built part: waits).
  [[nodiscard]] std::uint64_t volume_triangles() const;
  // The first light's volume as drawn (the given mesh, then the GPU-built triangles, three
  // vertices each, read back: waits).
  [[nodiscard]] HomogeneousMesh first_volume() const;

  // A volume built on the GPU (cs, gs, ts, pertri, smooth-gpu behind one interface); in the .cpp.
  class BuiltVolume;

 private:
  ShadowMethod method_;
  std::vector<Light> lights_;
  std::span<const HomogeneousMesh> cpu_meshes_;  // the caller's, for first_volume()
  std::vector<std::unique_ptr<ShadowVolumeMesh>> cpu_volumes_;
  std::unique_ptr<ComputeVolumeSoup> gpu_soup_;
  std::unique_ptr<SmoothCasterBuffers> smooth_casters_;
  std::vector<std::unique_ptr<BuiltVolume>> built_volumes_;
  std::vector<LightVolume> light_volumes_;
  std::uint32_t canonical_vertices_ = 0;
};

}  // namespace shadowcert::gpu
