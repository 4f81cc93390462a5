#pragma once
// The `pertri` method (docs/gpu.md): per-triangle shadow volumes without a silhouette
// (Milet 2014 §2.1). Every triangle t with s(t) != 0 draws its whole volume V(t) of
// docs/definitions.md#counts (front cap, three side quads, back cap), built on the GPU by one compute
// invocation per triangle (gpu/shaders/per_triangle_volume.comp.glsl). s(t) is the
// reference-edge value of the `cs` triangle pass (sorted canonical indices, one `precise`
// float evaluation, parity), equal to refedge_multiplicities(..., Precision::float32)'s
// triangle_sign, and is used for caps and sides alike, so each V(t) is closed on its own.
// It is the baseline the silhouette methods are measured against: every interior
// edge's two quads are rasterised only to cancel.
//
//   ComputeVolumeSoup soup(canonical.soup, table);   // once per scene (the cs uploads)
//   PerTriangleShadowVolume volume(soup);            // per light: output buffers
//   volume.build(light);                             // per frame or light change: 2 dispatches
//   renderer.render(..., {LightVolume{light, nullptr, volume.draw()}});
#include <cstdint>
#include <vector>

#include "core/light.h"
#include "gpu/compute_volume.h"
#include "gpu/gl_object.h"
#include "gpu/sign_mode.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu {

class PerTriangleShadowVolume {
 public:
  // Compiles the shader and sizes the output for 24 vertices per triangle (8 triangles),
  // clamped to what four storage windows address (llvmpipe: 4 x 128 MiB = 32M vertices).
  // `soup` must outlive this object (only its vertices and triangles are read). Throws
  // GlError with the driver's log.
  explicit PerTriangleShadowVolume(const ComputeVolumeSoup& soup, SignMode sign = SignMode::exact);

  // Runs the triangle and finish dispatches and puts the barriers the draw and readbacks
  // need. Throws std::invalid_argument on a light that is not finite with w in {0, 1} or a
  // directional light (0, 0, 0, 0).
  void build(const Light& light);

  // Two parts (IndirectVolumeDraw::reversed): each side quad shared by two triangles is written
  // twice in one vertex order, once in each part, so the pair cancels at every pixel.
  [[nodiscard]] IndirectVolumeDraw draw() const { return {vertex_array_.name(), command_.name(), true}; }
  [[nodiscard]] std::uint64_t capacity_vertices() const { return capacity_; }

  // Readbacks (they synchronise with the GPU; for tests, diagnostics and --capture).
  [[nodiscard]] std::vector<std::int32_t> read_triangle_signs() const;  // s(t) per soup triangle
  // Both parts' vertices; > capacity_vertices(): overflow (then nothing is drawn).
  [[nodiscard]] std::uint64_t read_requested_vertices() const;
  // The drawn triangles as counted: the forward part, then the reversed part's triangles with
  // their last two vertices swapped.
  [[nodiscard]] std::vector<VolumeTriangle> read_triangles() const;

 private:
  const ComputeVolumeSoup* soup_;
  Program program_;
  Buffer signs_, command_, volume_;
  VertexArray vertex_array_;
  std::uint64_t window_vertices_ = 0;
  std::uint64_t volume_bytes_ = 0;
  std::uint64_t capacity_ = 0;
};

}  // namespace shadowcert::gpu
