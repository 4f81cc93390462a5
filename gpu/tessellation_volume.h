#pragma once
// The `ts` method (docs/gpu.md): the shadow-volume chain of docs/definitions.md#counts built by the
// tessellator, Milet 2014 §2.2 (gpu/shaders/tessellation_volume.{vert,tesc,tese,geom}.glsl),
// a close sibling of `gs` (gpu/geometry_shader_volume.h). One GL_PATCHES patch per RECORD of
// 4 + kTessellationOppositesPerRecord words, the patch vertices being the words (Milet's
// Figure 4): an edge record (u, v, count, 0, up to K opposite vertex indices; an edge with more
// opposites is split into several records whose partial quads add up) or a triangle record
// (a, b, c, 1). The control shader evaluates the partial multiplicity m with cs's and gs's
// refedge evaluation, copied operation for operation, and asks for |m| isolines (none when
// m = 0); the geometry shader makes each line one copy of the side quad oriented by sign(m),
// and a triangle record's line its caps (gs's cap code). Captured by transform feedback and
// drawn through the same GPU-filled draw command as gs. With exact signs the control shader
// runs the float filter only and defers a record it cannot decide to the finish pass
// (tessellation_volume_finish.comp.glsl), which evaluates it exactly and appends its quads.
//
//   ComputeVolumeSoup soup(canonical.soup, table);            // once per scene (cs uploads)
//   TessellationShadowVolume volume(soup, table);             // records, capture buffer
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

// Opposite vertices one edge record holds (K): |partial m| <= K isolines, so K must stay below
// GL_MAX_TESS_GEN_LEVEL / 2 (>= 64 / 2), checked at construction. Must equal
// kOppositesPerRecord in tessellation_volume.tesc.glsl. A patch is 4 + K vertices, within
// GL_MAX_PATCH_VERTICES (>= 32).
inline constexpr std::uint32_t kTessellationOppositesPerRecord = 16;

class TessellationShadowVolume {
 public:
  // Compiles the shaders, checks the tessellation limits (GlEnvironmentError), builds the edge
  // and triangle records from `table` (the table `soup` was made from) and sizes the capture as
  // gs does. `soup` must outlive this object. Throws std::invalid_argument on counts past 32
  // bits, GlError with the driver's log.
  TessellationShadowVolume(const ComputeVolumeSoup& soup, const EdgeTable& table, SignMode sign = SignMode::exact);

  // One transform-feedback patch draw, the finish dispatch, the barriers. Throws
  // std::invalid_argument on a light that is not finite with w in {0, 1} or (0, 0, 0, 0).
  void build(const Light& light);

  [[nodiscard]] IndirectVolumeDraw draw() const { return {vertex_array_.name(), command_.name()}; }
  [[nodiscard]] std::uint64_t capacity_vertices() const { return capacity_; }
  [[nodiscard]] std::uint32_t record_count() const { return record_count_; }  // edge records

  // Readbacks (they synchronise with the GPU; for tests, diagnostics and --capture).
  [[nodiscard]] std::uint64_t read_requested_vertices() const;
  // Edge records the control shader's filter left to the finish pass's exact stage in the last
  // build (0 with float signs).
  [[nodiscard]] std::uint32_t read_deferred_records() const;
  [[nodiscard]] std::vector<VolumeTriangle> read_triangles() const;

 private:
  const ComputeVolumeSoup* soup_;
  Program program_, finish_;
  Buffer records_, deferred_, command_, volume_;
  VertexArray patches_;       // attribute 0: the record words
  VertexArray vertex_array_;  // the captured volume as attribute 0
  Query generated_;
  Framebuffer no_attachments_;
  std::uint32_t record_count_ = 0;
  std::uint32_t item_count_ = 0;  // edge records + triangles
  std::uint64_t capacity_ = 0;
};

}  // namespace shadowcert::gpu
