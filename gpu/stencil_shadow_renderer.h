#pragma once
// Stencil shadow volumes (docs/definitions.md#counts, docs/definitions.md#pixel-protocol): the counting identity n(P) = winding number of
// the chain at P, evaluated per pixel in the stencil buffer.
//
// Per frame: a depth pre-pass of the receivers in ambient colour; then per light: clear the
// stencil, draw that light's volume with colour and depth writes off and two-sided
// GL_INCR_WRAP / GL_DECR_WRAP (counts modulo 256, as docs/definitions.md#pixel-protocol compares them), then add the light's
// Lambert term where the stencil is 0 (depth GL_EQUAL, additive blending).
//   z-fail (default, Carmack's reverse): back faces +1 and front faces -1 where the depth
//     test FAILS, i.e. the faces behind the visible point P; right wherever the eye is,
//     because caps close the volume at the occluder and at infinity.
//   z-pass: front faces +1 and back faces -1 where it PASSES (faces between eye and P);
//     wrong when the eye itself is inside a volume (the count is then off by the eye's own).
//     Caps are drawn under z-pass too and never count there: a front cap lies on a scene
//     triangle, which the depth pre-pass drew, so it is at the visible point's depth or behind
//     it (GL_LESS fails), unless it lies between the eye and the near plane, which a proven
//     z-pass excludes (exact/zpass_proof.h); back caps are at infinity (depth 1, never less).
// The method is chosen per light (LightVolume::stencil, else StencilShadowOptions::method), so
// one frame can count proven lights with z-pass and the others with z-fail
// (pipeline/stencil_choice.h, `--stencil auto`).
// Caps at infinity: the projection's far plane is at infinity and GL_DEPTH_CLAMP is on for
// the volume pass, so nothing is clipped there; no polygon offset is used: every pass runs
// the same invariant vertex shader, so a cap and the triangle it lies on get equal depths.
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "gpu/gl_object.h"
#include "gpu/gpu_stage_timer.h"
#include "gpu/image.h"
#include "gpu/light_image_target.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_volume_geometry.h"

namespace shadowcert::gpu {

// One soup of the receiver/caster mesh with its colour.
struct ShadedSoupPart {
  const Soup* soup = nullptr;
  std::array<float, 3> albedo{0.8f, 0.8f, 0.8f};
  // false: the part only receives (a mesh with "casts": false): drawn and seen, but left out
  // of the shadow map's depth pass. The volume methods are given their casters apart
  // (ShadowMethodScene), so only the shadow map reads this.
  bool casts = true;
};

// Receivers on the GPU: triangles expanded to three vertices each (vec4 position with
// w = 1, rounded once to float exactly as HomogeneousMesh's finite vertices are; the
// soup's vertex normals when it has them, else the face normal; the part's albedo).
class ShadedSoupMesh {
 public:
  explicit ShadedSoupMesh(std::span<const ShadedSoupPart> parts);
  explicit ShadedSoupMesh(const Soup& soup);

  [[nodiscard]] GLuint vertex_array() const { return vertex_array_.name(); }
  // The interleaved vertex buffer the vertex array reads (a host may draw it itself, e.g. as
  // gpu/host_shadow_volumes.h's HostReceivers): per vertex kVertexStride bytes, the vec4
  // position at kPositionOffset, the vec3 normal at kNormalOffset, the vec3 albedo at
  // kAlbedoOffset, all GL_FLOAT.
  [[nodiscard]] GLuint vertex_buffer() const { return vertices_.name(); }
  static constexpr GLsizei kVertexStride = 40;
  static constexpr GLintptr kPositionOffset = 0;
  static constexpr GLintptr kNormalOffset = 16;
  static constexpr GLintptr kAlbedoOffset = 28;
  // Every triangle twice, (a, b, c) then (a, c, b) (stencil_shadow_renderer.cpp says why): what
  // the stencil method's depth and lit passes draw.
  [[nodiscard]] GLsizei vertex_count() const { return vertex_count_; }
  // The first copy alone, (a, b, c) per triangle: for passes that need each triangle once.
  [[nodiscard]] GLsizei single_order_vertex_count() const { return vertex_count_ / 2; }
  // The first copy of the casting parts' triangles (ShadedSoupPart::casts) as vertex ranges,
  // first and count, for glMultiDrawArrays: what the shadow map's depth pass draws. Adjacent
  // casting parts share one range; none when nothing casts.
  [[nodiscard]] std::span<const GLint> caster_firsts() const { return caster_firsts_; }
  [[nodiscard]] std::span<const GLsizei> caster_counts() const { return caster_counts_; }

 private:
  Buffer vertices_;
  VertexArray vertex_array_;
  GLsizei vertex_count_ = 0;
  std::vector<GLint> caster_firsts_;
  std::vector<GLsizei> caster_counts_;
};

enum class StencilMethod { zfail, zpass };

// "zfail" or "zpass" (the CLI's --stencil values, the JSON's).
[[nodiscard]] constexpr std::string_view stencil_method_name(StencilMethod method) {
  return method == StencilMethod::zpass ? "zpass" : "zfail";
}

// A volume the GPU built itself (gpu/compute_volume.h): a vertex array of vec4 triangles
// (attribute 0) drawn by glDrawArraysIndirect(GL_TRIANGLES) from `command`, a
// DrawArraysIndirectCommand whose count only the GPU knows.
//
// With `reversed` (pertri, gpu/per_triangle_volume.h), a second DrawArraysIndirectCommand
// follows the first in `command`: triangles stored in the vertex order of a triangle they
// cancel, each standing for its own reversal. They are drawn with the stencil operations of
// the two facings swapped, so such a pair is one primitive drawn twice: the same fragments at
// the same depths (only stencil state differs between the draws, which GL's invariance rules
// let no rasterisation depend on), counted once up and once down whatever the depth test
// says. Two copies in opposite vertex orders round their depths apart near the visible
// surface and need not cancel (docs/gpu.md, "Per-triangle volumes").
struct IndirectVolumeDraw {
  GLuint vertex_array = 0;
  GLuint command = 0;
  bool reversed = false;
};

// A light and the volume its shadows are counted with: `volume`, `indirect`, or both (their
// union: smooth-gpu's GPU-built volume and the given volume of the meshes it does not build);
// counted with `stencil` when set, else with StencilShadowOptions::method.
struct LightVolume {
  Light light;
  const ShadowVolumeMesh* volume = nullptr;
  IndirectVolumeDraw indirect{};
  std::optional<StencilMethod> stencil{};
};

struct StencilShadowOptions {
  StencilMethod method = StencilMethod::zfail;  // every light without its own LightVolume::stencil
  std::array<float, 4> background{0.0f, 0.0f, 0.0f, 0.0f};  // alpha 0 marks uncovered pixels
  std::array<float, 3> ambient{0.15f, 0.15f, 0.15f};
  // Each light's colour; several lights share 1 so that the sum stays in range.
  std::array<float, 3> light_colour{0.85f, 0.85f, 0.85f};
  bool read_back = true;  // off for timing: render() returns only what was drawn
  // The first light's volume fill, counted with occlusion queries after its volume pass
  // (StencilShadowFrame::first_volume_fragments): two more draws of that volume, outside the
  // timed stages. Off by default.
  bool count_fragments = false;
  // When set (and a frame of it open), the depth, stencil and lit passes are timed as its
  // stages (gpu/gpu_stage_timer.h); readbacks stay outside them.
  GpuStageTimer* timer = nullptr;
};

struct StencilShadowFrame {
  RgbaImage colour;           // alpha 255 where a receiver covers the pixel, 0 elsewhere
  GrayImage first_stencil;    // the first light's counts modulo 256 (after its volume pass)
  GrayImage first_lit_mask;   // lit_mask(first_stencil): 255 where the count is 0
  // The first light's amount of light per pixel (docs/smoothies.md, "The light image"): width x
  // height floats, row 0 at the TOP, in [0, 1] where a receiver covers the pixel (stencil
  // methods: 1 where the count is 0, else 0; the shadow map family: its filter's amount) and
  // kUncoveredLight (-1) where none does. Empty without readback.
  std::vector<float> first_light;
  // With StencilShadowOptions::count_fragments: the fragments the first light's volume
  // rasterises (its fill rate: every one runs the stencil test), and those that change the
  // stencil (their depth test fails under z-fail, passes under z-pass). 0 otherwise.
  std::uint64_t first_volume_fragments = 0;
  std::uint64_t first_stencil_updates = 0;
};

class ShadowSceneProgram;  // gpu/stencil_passes.h

class StencilShadowRenderer {
 public:
  StencilShadowRenderer();  // compiles shadow_scene.{vert,frag}.glsl; throws GlError with the log
  ~StencilShadowRenderer();
  StencilShadowRenderer(StencilShadowRenderer&&) noexcept;
  StencilShadowRenderer& operator=(StencilShadowRenderer&&) noexcept;

  // Renders into `target` (bound and cleared here), lights one after another. Throws
  // std::invalid_argument for a light without a volume, GlError on a GL error.
  StencilShadowFrame render(const OffscreenTarget& target, const ShadedSoupMesh& receivers, const Camera& camera,
                            std::span<const LightVolume> lights, const StencilShadowOptions& options = {}) const;

 private:
  // The passes themselves are gpu/stencil_passes.h's, which the host layer
  // (gpu/host_shadow_volumes.h) draws with too.
  std::unique_ptr<ShadowSceneProgram> program_;
};

}  // namespace shadowcert::gpu
