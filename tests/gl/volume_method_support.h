#pragma once
// Every volume method of `render --method` behind one test interface, so that a GL test can
// run the same check over cpu, cs, gs, ts and pertri (hard_case_render_test.cpp,
// gl_resource_test.cpp): build one light's volume, hand it to StencilShadowRenderer, read back
// what was drawn as exact/'s CapturedVolume. Test code only; it links shadowcert_exact for the
// cpu reference (the exact chain, exact/chain_mesh.h), as volume_test_support.h does.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/light.h"
#include "exact/captured_volume.h"
#include "exact/chain_mesh.h"
#include "exact/edge_multiplicity.h"
#include "exact/shadow_volume_chain.h"
#include "gpu/compute_volume.h"
#include "gpu/geometry_shader_volume.h"
#include "gpu/per_triangle_volume.h"
#include "gpu/shadow_volume_geometry.h"
#include "gpu/stencil_shadow_renderer.h"
#include "gpu/tessellation_volume.h"
#include "volume_test_support.h"

namespace shadowcert::gpu::test {

// cpu: exact/'s chain (exact multiplicities, assembled, converted by chain_mesh) uploaded as
// is, the reference; the others build their volume on the GPU from the same canonical soup.
enum class VolumeMethod { cpu, cs, gs, ts, pertri };
inline constexpr std::array<VolumeMethod, 5> kAllVolumeMethods{VolumeMethod::cpu, VolumeMethod::cs, VolumeMethod::gs,
                                                               VolumeMethod::ts, VolumeMethod::pertri};
inline constexpr std::array<VolumeMethod, 4> kGpuVolumeMethods{VolumeMethod::cs, VolumeMethod::gs, VolumeMethod::ts,
                                                               VolumeMethod::pertri};

// The `render --method` name.
[[nodiscard]] inline std::string_view volume_method_name(VolumeMethod method) {
  switch (method) {
    case VolumeMethod::cpu: return "cpu";
    case VolumeMethod::cs: return "cs";
    case VolumeMethod::gs: return "gs";
    case VolumeMethod::ts: return "ts";
    case VolumeMethod::pertri: return "pertri";
  }
  throw std::invalid_argument("volume_method_name: unknown method");
}

// Triangles as read back from the GPU (three vec4 each) as exact/'s CapturedVolume, unwelded:
// certify_captured_closure welds bitwise itself (as cli/volume_capture.cpp's conversion).
[[nodiscard]] inline CapturedVolume captured_volume(const std::vector<VolumeTriangle>& triangles) {
  CapturedVolume out;
  out.vertices.reserve(3 * triangles.size());
  out.triangles.reserve(triangles.size());
  for (const VolumeTriangle& t : triangles) {
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (const Vec4f& v : t) out.vertices.push_back(v);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

// One light's volume by one method. `prepared` (and `gpu_soup`, made from it; null is allowed
// for cpu only) must outlive the object; the GPU objects it creates die with it, so a test can
// count GL names around its lifetime. Construction compiles the method's shaders (GlError
// with the driver's log on failure); std::invalid_argument for a GPU method without gpu_soup.
class MethodVolume {
 public:
  MethodVolume(VolumeMethod method, const Prepared& prepared, const ComputeVolumeSoup* gpu_soup)
      : method_(method), prepared_(&prepared) {
    if (method == VolumeMethod::cpu) return;  // uploaded by build(): the chain depends on the light
    if (gpu_soup == nullptr) throw std::invalid_argument("MethodVolume: a GPU method needs the uploaded soup");
    switch (method) {
      case VolumeMethod::cpu: break;
      case VolumeMethod::cs: cs_ = std::make_unique<ComputeShadowVolume>(*gpu_soup); break;
      case VolumeMethod::gs: gs_ = std::make_unique<GeometryShaderShadowVolume>(*gpu_soup, prepared.table); break;
      case VolumeMethod::ts: ts_ = std::make_unique<TessellationShadowVolume>(*gpu_soup, prepared.table); break;
      case VolumeMethod::pertri: pertri_ = std::make_unique<PerTriangleShadowVolume>(*gpu_soup); break;
    }
  }

  // Builds (cpu: computes and uploads) the volume of `light`.
  void build(const Light& light) {
    light_ = light;
    if (method_ == VolumeMethod::cpu) {
      const Soup& canonical = prepared_->canonical.soup;
      const EdgeMultiplicities exact = exact_multiplicities(canonical, prepared_->table, light);
      geometry_ = chain_mesh(assemble_chain(canonical, prepared_->table, exact, light), canonical, light);
      mesh_.reset();  // the old buffers first: a cycle test sees one mesh alive at a time
      mesh_ = std::make_unique<ShadowVolumeMesh>(geometry_);
    } else if (cs_) {
      cs_->build(light);
    } else if (gs_) {
      gs_->build(light);
    } else if (ts_) {
      ts_->build(light);
    } else {
      pertri_->build(light);
    }
  }

  // What StencilShadowRenderer draws for the light last built. Throws std::logic_error before build().
  [[nodiscard]] LightVolume light_volume() const {
    if (!light_) throw std::logic_error("MethodVolume::light_volume: build() first");
    if (mesh_) return {*light_, mesh_.get(), {}};
    return {*light_, nullptr, cs_ ? cs_->draw() : gs_ ? gs_->draw() : ts_ ? ts_->draw() : pertri_->draw()};
  }

  // The vertices the build asked for (cpu: the chain's) and the room it had; past the
  // capacity a GPU method drew a truncated, open volume.
  [[nodiscard]] std::uint64_t read_requested_vertices() const {
    if (method_ == VolumeMethod::cpu) return 3 * geometry_.triangles.size();
    return cs_ ? cs_->read_requested_vertices() : gs_ ? gs_->read_requested_vertices()
           : ts_ ? ts_->read_requested_vertices() : pertri_->read_requested_vertices();
  }
  [[nodiscard]] std::uint64_t capacity_vertices() const {
    if (method_ == VolumeMethod::cpu) return 3 * geometry_.triangles.size();
    return cs_ ? cs_->capacity_vertices() : gs_ ? gs_->capacity_vertices()
           : ts_ ? ts_->capacity_vertices() : pertri_->capacity_vertices();
  }

  // The triangles drawn (cpu: the uploaded chain mesh, expanded), three vec4 each.
  [[nodiscard]] std::vector<VolumeTriangle> read_triangles() const {
    if (method_ != VolumeMethod::cpu)
      return cs_ ? cs_->read_triangles() : gs_ ? gs_->read_triangles() : ts_ ? ts_->read_triangles()
                                                                            : pertri_->read_triangles();
    std::vector<VolumeTriangle> out;
    out.reserve(geometry_.triangles.size());
    for (const auto& t : geometry_.triangles)
      out.push_back({geometry_.vertices.at(t[0]), geometry_.vertices.at(t[1]), geometry_.vertices.at(t[2])});
    return out;
  }

  [[nodiscard]] VolumeMethod method() const { return method_; }

 private:
  VolumeMethod method_;
  const Prepared* prepared_;
  std::optional<Light> light_;
  ShadowVolumeGeometry geometry_;  // cpu only
  std::unique_ptr<ShadowVolumeMesh> mesh_;
  std::unique_ptr<ComputeShadowVolume> cs_;
  std::unique_ptr<GeometryShaderShadowVolume> gs_;
  std::unique_ptr<TessellationShadowVolume> ts_;
  std::unique_ptr<PerTriangleShadowVolume> pertri_;
};

}  // namespace shadowcert::gpu::test
