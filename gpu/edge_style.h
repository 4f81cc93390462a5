#pragma once
// Styles drawn from an edge map (Nienhaus & Doellner 2003, §5; docs/edge-maps.md): a scene pass
// that shades every visible surface in the style into a texture, then a screen pass that puts
// the edge map (gpu/edge_map.h) over it into the frame:
//   edges  plain edges: white paper, inner edges grey, profile edges black
//   gooch  Gooch et al.'s technical illustration (cool-to-warm tone), inner edges to white,
//          profile edges to black (the paper's Fig. 7)
//   toon   Lake et al.'s cartoon shading (a 1D shade texture, kToonShades, read with nearest
//          filtering at n . l), the cartoon map anti-aliased by a 3 x 3 tent in the composite
//          (the paper's Fig. 9, right), edges black
// Each is shaded by one light (the scene's first). With shadows, the light's amount per pixel
// comes from any shadow method (gpu/shadow_method_renderer.h: StencilShadowFrame::first_light,
// 1 lit, 0 shadowed, between in a penumbra) and scales the light's term of the style. The edge
// map itself never sees the shadows: its passes draw into framebuffers of their own, and the
// composite writes colour only (no depth or stencil test, no depth or stencil write), so the
// stencil counts a shadow method left in the target survive it (the paper's orthogonality;
// tests/gpu/edge_style_test.cpp checks both directions, bit for bit).
//
//   EdgeMapRenderer edges(parts);  EdgeStyleRenderer style;
//   edges.draw(w, h, camera, EdgeFilter::diagonal);
//   RgbaImage image = style.render(target, edges, camera, EdgeStyle::gooch, options);
#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

#include "core/camera.h"
#include "core/light.h"
#include "gpu/detail/render_texture.h"
#include "gpu/edge_map.h"
#include "gpu/frame_timing.h"
#include "gpu/gl_object.h"
#include "gpu/gpu_stage_timer.h"
#include "gpu/image.h"
#include "gpu/offscreen_target.h"

namespace shadowcert::gpu {

enum class EdgeStyle { edges, gooch, toon };
inline constexpr std::array<EdgeStyle, 3> kEdgeStyles{EdgeStyle::edges, EdgeStyle::gooch, EdgeStyle::toon};

// "edges", "gooch", "toon" (the CLI's --style values).
[[nodiscard]] std::string_view edge_style_name(EdgeStyle style);
[[nodiscard]] std::optional<EdgeStyle> parse_edge_style(std::string_view name);

// Lake et al.'s shade texture: texel k covers n . l in [k / 4, (k + 1) / 4); nearest filtering
// gives three hard bands (shadow side below 0.5, mid tone, highlight from 0.75).
inline constexpr std::array<float, 4> kToonShades{0.35f, 0.35f, 0.7f, 1.0f};

struct EdgeStyleOptions {
  // Intensity thresholds (gpu/edge_map.h's profile_threshold and inner_threshold): an
  // intensity at or below its threshold is not drawn (it is no edge pixel), one at twice the
  // threshold or more is drawn fully, linearly between.
  double profile_threshold = 0.0;
  double inner_threshold = 0.0;
  // The light the style is shaded by (the scene's first).
  Light light{{0.0, 10.0, 0.0, 1.0}};
  // With shadows: the light's amount per pixel, width * height floats, row 0 at the TOP
  // (StencilShadowFrame::first_light; kUncoveredLight where no receiver). Empty: lit everywhere.
  std::span<const float> light_amount;
};

class EdgeStyleRenderer {
 public:
  EdgeStyleRenderer();  // compiles, makes the shade texture; throws GlError with the log

  // Draws `style` into `target` (bound here): `edges`'s last draw (at target's size, else
  // std::invalid_argument, as is a light_amount of another size) over the scene `edges` holds,
  // shaded from `camera`. Writes colour only. With `timer` (a frame of it open) the two
  // passes are its RenderStage::composite.
  void draw(const OffscreenTarget& target, const EdgeMapRenderer& edges, const Camera& camera, EdgeStyle style,
            const EdgeStyleOptions& options, GpuStageTimer* timer = nullptr);
  // draw(), then the target's colour (alpha 255 everywhere: the style's paper is opaque).
  [[nodiscard]] RgbaImage render(const OffscreenTarget& target, const EdgeMapRenderer& edges, const Camera& camera,
                                 EdgeStyle style, const EdgeStyleOptions& options, GpuStageTimer* timer = nullptr);

 private:
  Program shade_;
  Program composite_;
  VertexArray empty_;
  Texture toon_shades_;
  std::optional<detail::RenderTexture> shade_target_;
  Texture light_amount_;
  std::uint32_t light_amount_width_ = 0, light_amount_height_ = 0;
};

// `warm_up` untimed frames, then `frames` frames each drawing the edge map (`edges.draw`:
// stages g_buffer and edge_filter) and the style (`style.draw`: composite) without readback,
// ended by glFinish, timed by a fresh GpuStageTimer(sync) and the wall clock. Throws
// std::invalid_argument for frames = 0, GlEnvironmentError without timer queries.
[[nodiscard]] FrameTiming time_edge_frames(EdgeMapRenderer& edges, EdgeStyleRenderer& style,
                                           const OffscreenTarget& target, const Camera& camera, EdgeFilter filter,
                                           EdgeStyle style_kind, const EdgeStyleOptions& options,
                                           std::size_t warm_up, std::size_t frames, StageSync sync);

// The stages time_edge_frames reports, in frame order: g_buffer, edge_filter, composite.
inline constexpr std::array<RenderStage, 3> kEdgeStages{RenderStage::g_buffer, RenderStage::edge_filter,
                                                        RenderStage::composite};

}  // namespace shadowcert::gpu
