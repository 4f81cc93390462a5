#pragma once
// The `smooth-gpu` method (docs/smooth-silhouettes.md): the closed smooth shadow volume of
// contour/smooth_volume.h (Mattausch et al. 2012 §4), built on the GPU by one compute invocation
// per caster triangle (gpu/shaders/smooth_silhouette_volume.comp.glsl). The paper leaves a GPU
// version to future work (its §5); what makes one possible without tracing loops is that each
// triangle's accurate segment, its subdivision and its strip depend only on its own corners and
// on the triangles across its edges, and that every point two triangles share is computed by
// both from the same floats in the same order, so their caps meet bit for bit and the volume is
// closed by construction. It equals the CPU build up to float rounding (the CPU computes in
// double), which tests/gpu/smooth_silhouette_volume_test.cpp checks triangle by triangle.
//
//   SmoothCasterBuffers casters(arrays);     // once per scene: the connectivity, uploaded
//   SmoothSilhouetteVolume volume(casters);  // per light: output buffers
//   volume.build(light);                     // per frame or light change: 2 dispatches
//   renderer.render(..., {LightVolume{light, nullptr, volume.draw()}});
//
// gpu/ never sees contour/ (nor OpenMesh): the caster comes as plain arrays, which
// pipeline/silhouette_volumes.h fills from contour/smooth_caster.h's SmoothCaster.
#include <array>
#include <cstdint>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "gpu/gl_object.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu {

// Halvings of one contour segment at most: contour/smooth_contour.h's kMaxSubdivisionDepth
// (pipeline/ asserts they are equal); the shader's subdivision stack is sized by it.
inline constexpr std::uint32_t kSmoothGpuMaxSubdivisionDepth = 8;

// No triangle across an edge (contour/smooth_caster.h's kBorder).
inline constexpr std::uint32_t kNoTriangleAcross = 0xFFFFFFFFu;

// One or more smooth casters (oriented 2-manifolds with a unit normal per corner wedge;
// contour/smooth_caster.h) as plain arrays, concatenated: indices are global.
struct SmoothCasterArrays {
  std::vector<Vec3> vertices;  // welded positions, as GL is given them (the eye's frame)
  std::vector<std::array<std::uint32_t, 3>> triangles;  // vertex indices, oriented outwards
  // wedges[t][k]: corner k's wedge (a vertex with one normal); wedge_normals[w]: its unit normal.
  std::vector<std::array<std::uint32_t, 3>> wedges;
  std::vector<Vec3> wedge_normals;
  // across[t][k]: the triangle across edge k = (corner k, corner k + 1), or kNoTriangleAcross.
  std::vector<std::array<std::uint32_t, 3>> across;
  std::vector<std::uint8_t> crease_bits;  // per triangle: bit k set where edge k is a crease
  // Per triangle, its mesh's: the contour error epsilon (world units, > 0) and the cap offset
  // (>= 0: how far behind the surface cut cap points lie; SmoothVolumeOptions::cap_offset).
  std::vector<float> epsilon;
  std::vector<float> cap_offset;
};

// The arrays as shader storage buffers (read only).
class SmoothCasterBuffers {
 public:
  // Throws std::invalid_argument("SmoothCasterBuffers: ...") when the arrays' sizes differ,
  // an index is out of range, a coordinate or normal is not finite, an epsilon is not finite and
  // > 0 or a cap offset not finite and >= 0.
  explicit SmoothCasterBuffers(const SmoothCasterArrays& arrays);

  [[nodiscard]] std::uint32_t triangle_count() const { return triangle_count_; }

 private:
  friend class SmoothSilhouetteVolume;
  Buffer vertices_, wedge_normals_, triangles_;
  std::uint32_t triangle_count_ = 0;
};

using Vec4f = std::array<float, 4>;
using VolumeTriangle = std::array<Vec4f, 3>;

// One light's smooth volume: output buffer, indirect draw command, vertex array.
class SmoothSilhouetteVolume {
 public:
  // Compiles the shader and sizes the output for the caps, their back caps and a silhouette's
  // worth of strips; build() grows it when a light needs more, up to
  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE (past that the overflow is reported, never drawn).
  // `casters` must outlive this object. Throws GlError with the driver's log.
  explicit SmoothSilhouetteVolume(const SmoothCasterBuffers& casters);

  // The triangle and finish dispatches for `light`, then one 4-byte readback of the vertices
  // asked for (a synchronisation point): when they did not fit, the buffer grows and the volume
  // is built again. Throws std::invalid_argument on a light that is not finite with w in {0, 1}
  // or a directional light (0, 0, 0, 0).
  void build(const Light& light);

  [[nodiscard]] IndirectVolumeDraw draw() const { return {vertex_array_.name(), command_.name()}; }
  [[nodiscard]] std::uint64_t capacity_vertices() const { return capacity_; }

  // Readbacks (they synchronise with the GPU; for tests, diagnostics and --capture).
  [[nodiscard]] std::uint64_t read_requested_vertices() const;  // > capacity_vertices(): overflow
  [[nodiscard]] std::vector<VolumeTriangle> read_triangles() const;  // the drawn triangles

 private:
  void allocate(std::uint64_t vertices);
  void dispatch_build(const Light& light);

  const SmoothCasterBuffers* casters_;
  Program program_;
  Buffer command_, volume_;
  VertexArray vertex_array_;
  std::uint64_t capacity_ = 0;
  std::uint64_t limit_ = 0;  // the most vertices one storage block addresses
};

}  // namespace shadowcert::gpu
