#pragma once
// The `cs` method (docs/gpu.md): the shadow-volume chain of docs/definitions.md#counts built on the GPU by
// a compute shader (gpu/shaders/compute_volume.comp.glsl) with Milet 2014's reference edge
// (§2.2): multiplicities per edge, |m| side quads per edge oriented by sign(m), caps per
// triangle, all derived from ONE float evaluation per triangle on its vertices sorted by
// canonical index, so the chain is closed by construction and its signs equal
// refedge_multiplicities(..., Precision::float32) of exact/ bit for bit.
//
//   ComputeVolumeSoup soup(canonical.soup, table);   // once per scene: SSBO uploads
//   ComputeShadowVolume volume(soup);                // per light: output buffers
//   volume.build(light);                             // per frame or light change: 3 dispatches
//   renderer.render(..., {LightVolume{light, nullptr, volume.draw()}});
//
// gpu/ takes the canonical soup and its edge table as plain data (scene/); it never calls
// exact/. Vertices are rounded once from double to float exactly as HomogeneousMesh's
// finite vertices; far vertices x_inf = (x - l, 0) are formed in float on the GPU from those
// (cli/'s cpu conversion forms x - l in double): the two volumes' sides may differ by one
// rounding, which moves only pixels on volume boundaries.
#include <array>
#include <cstdint>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "gpu/gl_object.h"
#include "gpu/sign_mode.h"
#include "gpu/stencil_shadow_renderer.h"
#include "scene/edge_table.h"

namespace shadowcert::gpu {

// The canonical soup and its edge table as shader storage buffers (read only).
class ComputeVolumeSoup {
 public:
  // Precondition: `table` is build_edge_table(canonical) and `canonical` a canonical soup
  // (scene/canonical_soup.h: index order = vertex order). Throws std::invalid_argument on
  // sizes that do not fit each other or 32-bit counts.
  ComputeVolumeSoup(const Soup& canonical, const EdgeTable& table);

  [[nodiscard]] std::uint32_t edge_count() const { return edge_count_; }
  [[nodiscard]] std::uint32_t triangle_count() const { return triangle_count_; }
  // Sum over edges of opposite count x 6 plus 6 per triangle, which no chain without wide far
  // edges can exceed (a fan edge with k opposites can have |m| = k), plus room for those
  // (compute_volume.cpp: a quarter more and 64 Ki vertices).
  [[nodiscard]] std::uint64_t worst_case_vertices() const { return worst_case_vertices_; }
  // The vertices every build reads (vec4 floats, w = 1, one per canonical vertex); written
  // from a host's vertex buffer by gpu/host_vertex_gather.h before a build.
  [[nodiscard]] GLuint vertex_buffer() const { return vertices_.name(); }

 private:
  friend class ComputeShadowVolume;
  friend class PerTriangleShadowVolume;  // pertri reads the same vertices and triangles
  friend class GeometryShaderShadowVolume;  // gs too (its edge records are its own)
  friend class TessellationShadowVolume;  // ts too (edge and triangle records of its own)
  Buffer vertices_, edges_, first_opposite_, opposite_vertex_, triangles_;
  std::uint32_t edge_count_ = 0;
  std::uint32_t triangle_count_ = 0;
  std::uint64_t worst_case_vertices_ = 0;
};

using Vec4f = std::array<float, 4>;
using VolumeTriangle = std::array<Vec4f, 3>;

// One light's volume: output buffers, indirect draw command, vertex array.
class ComputeShadowVolume {
 public:
  // Compiles the shader and sizes the output for soup.worst_case_vertices(), clamped to
  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE (build() then reports an overflow). `soup` must outlive
  // this object. Throws GlError with the driver's log.
  explicit ComputeShadowVolume(const ComputeVolumeSoup& soup, SignMode sign = SignMode::exact);

  // Runs the edge, triangle and finish dispatches for `light` and puts the barriers the draw
  // and the readbacks need. Throws std::invalid_argument on a light that is not finite with
  // w in {0, 1} or a directional light (0, 0, 0, 0).
  void build(const Light& light);

  // What the stencil renderer draws (glDrawArraysIndirect of GL_TRIANGLES).
  [[nodiscard]] IndirectVolumeDraw draw() const { return {vertex_array_.name(), command_.name()}; }
  [[nodiscard]] std::uint64_t capacity_vertices() const { return capacity_; }

  // Readbacks (they synchronise with the GPU; for tests, diagnostics and --capture).
  [[nodiscard]] std::vector<std::int32_t> read_multiplicities() const;  // per table edge
  [[nodiscard]] std::vector<std::int32_t> read_triangle_signs() const;  // s(t) per soup triangle
  [[nodiscard]] std::uint64_t read_requested_vertices() const;  // > capacity_vertices(): overflow
  [[nodiscard]] std::vector<VolumeTriangle> read_triangles() const;  // the drawn triangles

 private:
  const ComputeVolumeSoup* soup_;
  Program program_;
  Buffer signs_, command_, volume_;
  VertexArray vertex_array_;
  std::uint64_t capacity_ = 0;
};

}  // namespace shadowcert::gpu
