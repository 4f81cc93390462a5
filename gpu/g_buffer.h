#pragma once
// The G-buffer of edge maps (Nienhaus & Doellner 2003, §4.1.1; docs/edge-maps.md): one RGBA32F
// texture the size of the frame holding, per pixel,
//   rgb  the eye-space unit normal of the visible surface, turned towards the eye (soups have
//        no orientation: the normal is flipped to the side of the triangle the eye sees);
//   a    its linear view depth normalised to the scene's depth range, (d - near) / (far - near),
//        d the distance along the view axis (DepthRange below; 0 at near, 1 at far).
// Pixels no surface covers hold kUncoveredNormal (0, 0, 0) and kBackgroundDepth: the filters
// (gpu/edge_map.h) tell coverage by the zero normal. The paper stores the normal in RGB and the
// depth in alpha of an 8-bit P-buffer, and fits the near and far planes to the bounds of the
// shapes because of that precision; float textures keep the fit (so that depth steps mean a
// fraction of the scene's depth) without the quantisation.
//
//   GBuffer g_buffer(width, height);
//   GBufferRenderer pass;                                         // compiles g_buffer.*.glsl
//   pass.render(g_buffer, mesh, camera, fitted_depth_range(camera, bounds));
//   std::vector<float> rgba = g_buffer.read();                    // rows top first
//
// Tests build G-buffers by hand and upload() them, so the filters run on known answers.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/camera.h"
#include "gpu/detail/render_texture.h"
#include "gpu/gl_object.h"
#include "gpu/gpu_stage_timer.h"
#include "gpu/shadow_map_renderer.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu {

// What an uncovered pixel holds: a zero normal (coverage) and a depth beyond the far plane.
// The filters clamp every depth difference to [0, 1] (a covered pixel's depth lies in [0, 1]),
// so a surface against the background is a full step: the background lies at infinity.
inline constexpr std::array<float, 3> kUncoveredNormal{0.0f, 0.0f, 0.0f};
inline constexpr float kBackgroundDepth = 2.0f;

// The view depths the G-buffer's depth is normalised between.
struct DepthRange {
  double near = 0.0;  // view depth stored as 0
  double far = 1.0;   // view depth stored as 1; > near
};

// The paper's fit (§4.1.1: "near and far clipping planes exactly match the bounding volumes"):
// the view depths of the 8 corners of `bounds`, near = max(nearest corner, camera.near_plane
// (core/near_plane.h's fitted plane: nothing nearer is drawn)), far = the farthest corner. When
// the box lies behind the near plane (nothing in view) far = near + 1, so the division stays
// finite; callers that need something in view check coverage. Throws std::invalid_argument as
// view_matrix for a degenerate camera.
[[nodiscard]] DepthRange fitted_depth_range(const Camera& camera, const SceneBounds& bounds);

// The RGBA32F texture (the G-buffer, sampled by the filters with texelFetch) and a DEPTH32F
// renderbuffer for its own hidden-surface removal, in a framebuffer of their own: drawing it
// touches no other framebuffer (the edge map is orthogonal to the stencil shadows drawn in
// OffscreenTarget).
class GBuffer {
 public:
  // Throws GlError naming the size when the framebuffer is incomplete or too large.
  GBuffer(std::uint32_t width, std::uint32_t height);

  // Binds the framebuffer (draw and read) with a full-size viewport and clears it to the
  // uncovered value (kUncoveredNormal, kBackgroundDepth) and depth 1.
  void bind_and_clear() const;
  // Replaces the texture's contents: width * height RGBA floats, row-major, row 0 at the TOP
  // (gpu/image.h's convention). Throws std::invalid_argument for another size.
  void upload(std::span<const float> rgba) const;
  // The texture's contents in the same layout.
  [[nodiscard]] std::vector<float> read() const;

  [[nodiscard]] std::uint32_t width() const { return target_.width(); }
  [[nodiscard]] std::uint32_t height() const { return target_.height(); }
  [[nodiscard]] GLuint texture() const { return target_.texture(); }

 private:
  detail::RenderTexture target_;
};

// The G-buffer pass (g_buffer.vert.glsl, g_buffer.frag.glsl): each triangle of `mesh` once
// (ShadedSoupMesh's first copy), depth test GL_LESS with camera's projection
// (gpu/camera_transform.h: its near plane, the far plane at infinity), no blending.
class GBufferRenderer {
 public:
  GBufferRenderer();  // compiles; throws GlError with the log

  // Clears `g_buffer` and draws `mesh` into it. With `timer` (a frame of it open) the pass is
  // its RenderStage::g_buffer. Throws std::invalid_argument for range.far <= range.near.
  void render(const GBuffer& g_buffer, const ShadedSoupMesh& mesh, const Camera& camera, const DepthRange& range,
              GpuStageTimer* timer = nullptr) const;

 private:
  Program program_;
};

}  // namespace shadowcert::gpu
