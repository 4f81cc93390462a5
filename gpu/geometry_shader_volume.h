#pragma once
// The `gs` method (docs/gpu.md): the shadow-volume chain of docs/definitions.md#counts built by a geometry
// shader (gpu/shaders/geometry_shader_volume.{vert,geom}.glsl), the classic silhouette
// extrusion (Milet 2014 §2.2 evaluated per edge, as `cs` does in a compute shader). One point
// per EDGE RECORD: an edge (u, v) with at most kOppositesPerRecord opposite vertices; an edge
// with more opposites is split into several records, each emitting the quads of its partial
// multiplicity. Partial quads of one edge add up to m (copies of opposite signs cancel in
// every count), so the chain stays closed while the geometry shader's output stays bounded
// (max_vertices = 6 kOppositesPerRecord). Then one point per triangle emits its caps. Signs
// come from the cs evaluation copied operation for operation, so they equal
// refedge_multiplicities(..., Precision::float32) of exact/.
//
// The strips are captured by transform feedback into a vec4 buffer whose draw command is
// filled on the GPU (GL_PRIMITIVES_GENERATED x 3), so StencilShadowRenderer draws it exactly
// as it draws cs: the volume pass, z-fail or z-pass, is shared, and the capture is what
// --capture reads back.
//
//   ComputeVolumeSoup soup(canonical.soup, table);            // once per scene (cs uploads)
//   GeometryShaderShadowVolume volume(soup, table);           // records, capture buffer
//   volume.build(light);                                      // per frame: one draw + finish
//   renderer.render(..., {LightVolume{light, nullptr, volume.draw()}});
#include <cstdint>
#include <vector>

#include "core/light.h"
#include "gpu/compute_volume.h"
#include "gpu/gl_object.h"
#include "gpu/sign_mode.h"
#include "gpu/stencil_shadow_renderer.h"
#include "scene/edge_table.h"

namespace shadowcert::gpu {

// Opposite vertices one edge record holds: |partial m| <= 4, so a record emits at most 4
// quads (24 vertices: two 3-vertex strips each), well inside GL_MAX_GEOMETRY_OUTPUT_VERTICES
// (>= 256). Must equal kOppositesPerRecord in geometry_shader_volume.geom.glsl.
inline constexpr std::uint32_t kOppositesPerRecord = 4;

class GeometryShaderShadowVolume {
 public:
  // Compiles the shaders, builds the edge records from `table` (the table `soup` was made
  // from) and sizes the capture for the worst case (6 vertices per opposite entry and per
  // triangle), clamped to kMaxCaptureBytes. `soup` must outlive this object (its vertices and
  // triangles are read). Throws std::invalid_argument on counts past 32 bits, GlError with the
  // driver's log.
  GeometryShaderShadowVolume(const ComputeVolumeSoup& soup, const EdgeTable& table, SignMode sign = SignMode::exact);

  // One transform-feedback draw of records and triangles, the finish dispatch, the barriers
  // the draw and the readbacks need. Throws std::invalid_argument on a light that is not
  // finite with w in {0, 1} or a directional light (0, 0, 0, 0).
  void build(const Light& light);

  [[nodiscard]] IndirectVolumeDraw draw() const { return {vertex_array_.name(), command_.name()}; }
  [[nodiscard]] std::uint64_t capacity_vertices() const { return capacity_; }
  [[nodiscard]] std::uint32_t record_count() const { return record_count_; }

  // Readbacks (they synchronise with the GPU; for tests, diagnostics and --capture).
  [[nodiscard]] std::uint64_t read_requested_vertices() const;  // > capacity_vertices(): overflow
  [[nodiscard]] std::vector<VolumeTriangle> read_triangles() const;  // the drawn triangles

 private:
  const ComputeVolumeSoup* soup_;
  Program program_, finish_;
  Buffer records_, command_, volume_;
  VertexArray points_;        // no attributes: the shaders fetch by gl_VertexID
  VertexArray vertex_array_;  // the captured volume as attribute 0
  Query generated_;
  Framebuffer no_attachments_;  // a draw needs a complete framebuffer, even with rasterising off
  std::uint32_t record_count_ = 0;
  std::uint64_t capacity_ = 0;
};

}  // namespace shadowcert::gpu
