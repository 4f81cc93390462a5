#pragma once
// Edge maps (Nienhaus & Doellner 2003, §4; docs/edge-maps.md): the G-buffer of the visible
// surfaces (gpu/g_buffer.h), then one image-space filter over it, each a fragment pass over a
// screen-sized triangle that writes the edge map, an RGBA32F texture of the frame's size:
//   r  the PROFILE edge intensity, from depth (silhouettes and borders: depth steps),
//   g  the INNER edge intensity, from normals (creases),
//   b  1 where a surface covers the pixel, 0 where none does; a 1.
// Both intensities lie in [0, 1], 0 = no edge, larger = more edge. The two are kept apart:
// styles (gpu/edge_style.h) draw them differently, the scores (pipeline/) score them apart.
//
// Filters, over the 3 x 3 neighbourhood A B C / D X E / F G H of pixel X (the paper's Fig. 2).
// z is the G-buffer's normalised depth, n its unit normal; every depth difference is clamped to
// [0, 1] (the background, kBackgroundDepth, lies a full step behind every surface); a normal
// pair with an uncovered sample counts as no normal discontinuity (that is a profile edge):
//   diagonal  the paper's first variant, taps A, C, F, H (one pass):
//               I_Z = (1 - |z_A - z_H| / 2)^2 (1 - |z_C - z_F| / 2)^2,  profile = 1 - I_Z
//               I_N = (n_A . n_H + n_C . n_F) / 2,                     inner   = (1 - I_N) / 2
//   c1        the C1-discontinuity operator of Saito & Takahashi and Decaudin as the paper
//             writes it (§4.1.2), on depth, and the same operator on normals:
//               profile = (|A-X| + 2|B-X| + |C-X| + 2|D-X| + 2|E-X| + |F-X| + 2|G-X| + |H-X|) / 12
//               inner   = the same weights over (1 - n_i . n_X) / 2, / 12 (0 where X is uncovered)
//             (the paper divides by 8; 12 is the weights' sum, so both lie in [0, 1] and the
//             three passes add up without a clamp),
//             in ONE pass of nine taps by default; the paper's three passes added by blending
//             (rows A B C, D E, F G H) with EdgeMapOptions::c1_three_passes (docs/edge-maps.md
//             says why one: the split came from four texture units; a GL 4.5 fragment shader
//             fetches nine texels, and one pass saves two full-screen read-modify-writes).
//   sobel     the usual baseline: the 3 x 3 Sobel gradient G of depth (differences to X,
//             clamped to [-1, 1]) and of the normal field (each component):
//               profile = min(1, |G_z| / 4),  inner = min(1, |G_n| / 8)   (0 where X is uncovered)
// The divisors make each filter's answer to an ideal step plain (the thresholds below): at
// the pixel next to an axis-aligned depth step of height s, profile = 1 - (1 - s/2)^4
// (diagonal), s/3 (c1), s (sobel); next to an axis-aligned crease whose normals differ by the
// angle a, inner = (1 - cos a) / 2 (diagonal), (1 - cos a) / 6 (c1), sin(a / 2) (sobel).
// Every filter marks the pixels on both sides of a step or a crease (lines two pixels wide, as
// in the paper's figures); texels beyond the image repeat the border (no edge at the frame).
//
// The entry point (the scores in pipeline/ call it; `shadowcert edges` too):
//   EdgeMapRenderer edges(shaded_parts(scene));          // every mesh, as render draws them
//   EdgeMapImage map = edges.render(target, scene.camera, EdgeFilter::diagonal);
//   map.profile[map.index(x, row)], map.inner[...], map.covered[...]   // row 0 at the TOP
// The scene in the eye's frame (core/eye_frame.h) and its camera's fitted near plane
// (core/near_plane.h), as render gives GL a scene. `target` gives the size only: nothing is
// drawn into it (its colour and stencil survive, the paper's orthogonality).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/camera.h"
#include "gpu/detail/render_texture.h"
#include "gpu/g_buffer.h"
#include "gpu/gl_object.h"
#include "gpu/gpu_stage_timer.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_map_renderer.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu {

enum class EdgeFilter { diagonal, c1, sobel };
inline constexpr std::array<EdgeFilter, 3> kEdgeFilters{EdgeFilter::diagonal, EdgeFilter::c1, EdgeFilter::sobel};

// "diagonal", "c1", "sobel" (the CLI's --filter values, the JSON's).
[[nodiscard]] std::string_view edge_filter_name(EdgeFilter filter);
// The filter of that name; nullopt for any other string.
[[nodiscard]] std::optional<EdgeFilter> parse_edge_filter(std::string_view name);

// The dihedral angle above which an edge is a crease (the angle between the two faces'
// normals, 0 for a flat pair): what `shadowcert edges --crease-angle` defaults to, for the inner
// threshold of the filters and for the exact ground truth alike. A box's edges (90) and a
// hexagonal prism's (60) are creases; a 32-slice sphere's facets (11.25) are not.
inline constexpr double kDefaultEdgeCreaseAngleDegrees = 30.0;
// The depth step (a fraction of the fitted depth range) the default profile threshold detects.
inline constexpr double kDefaultEdgeDepthStep = 0.02;

// The filter's profile intensity next to an axis-aligned depth step of `depth_step` (in
// [0, 1], a fraction of the depth range): the threshold that detects steps at least that high.
// Throws std::invalid_argument outside [0, 1].
[[nodiscard]] double profile_threshold(EdgeFilter filter, double depth_step);
// The filter's inner intensity next to an axis-aligned crease of `crease_angle_degrees` (in
// [0, 180]): the inner threshold that detects creases sharper than that angle (`--crease-angle`).
// Throws std::invalid_argument outside [0, 180].
[[nodiscard]] double inner_threshold(EdgeFilter filter, double crease_angle_degrees);

// An edge map read back: width * height values each, row-major, row 0 at the TOP (gpu/image.h).
struct EdgeMapImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> profile;         // in [0, 1], 1 = strongest; depth discontinuities
  std::vector<float> inner;           // in [0, 1], 1 = strongest; normal discontinuities
  std::vector<std::uint8_t> covered;  // 1 where a surface covers the pixel, 0 elsewhere

  [[nodiscard]] std::size_t index(std::uint32_t x, std::uint32_t row) const { return std::size_t{row} * width + x; }
};

// Edge pixels: intensity strictly above the threshold (a threshold of 1 marks none).
struct EdgePixelCounts {
  std::uint64_t profile = 0;
  std::uint64_t inner = 0;
  std::uint64_t covered = 0;  // pixels a surface covers
};
[[nodiscard]] EdgePixelCounts count_edge_pixels(const EdgeMapImage& map, double profile_threshold,
                                                double inner_threshold);

// The edge-map texture (RGBA32F, the layout at the top) in a framebuffer of its own.
class EdgeMap {
 public:
  // Throws GlError naming the size when the framebuffer is incomplete or too large.
  EdgeMap(std::uint32_t width, std::uint32_t height);

  // Binds the framebuffer (draw) with a full-size viewport.
  void bind() const;
  [[nodiscard]] EdgeMapImage read() const;
  // The texture as it is, width * height RGBA floats, row 0 at the TOP: what the orthogonality
  // test compares bit for bit.
  [[nodiscard]] std::vector<float> read_texels() const;

  [[nodiscard]] std::uint32_t width() const { return target_.width(); }
  [[nodiscard]] std::uint32_t height() const { return target_.height(); }
  [[nodiscard]] GLuint texture() const { return target_.texture(); }

 private:
  detail::RenderTexture target_;
};

struct EdgeMapOptions {
  // c1 only: the paper's three passes (rows of taps) added by blending instead of one pass.
  bool c1_three_passes = false;
};

// The filter passes (edge_map.vert.glsl, edge_{diagonal,c1,sobel}.frag.glsl): any G-buffer to
// an edge map of its size. Tests feed it hand-built G-buffers.
class EdgeMapFilter {
 public:
  EdgeMapFilter();  // compiles the three programs; throws GlError with the log

  // Writes `out` from `g_buffer` (same size, else std::invalid_argument). With `timer` (a frame
  // of it open) the pass (or c1's three) is its RenderStage::edge_filter.
  void apply(const GBuffer& g_buffer, const EdgeMap& out, EdgeFilter filter, const EdgeMapOptions& options = {},
             GpuStageTimer* timer = nullptr) const;

 private:
  VertexArray empty_;  // the screen triangle comes from gl_VertexID
  Program diagonal_;
  Program c1_;
  Program sobel_;
};

class EdgeMapRenderer {
 public:
  // Uploads the parts (a ShadedSoupMesh: the soup's vertex normals where it has them, else
  // face normals) and compiles the passes; needs a current context. Throws
  // std::invalid_argument when the parts hold no triangle.
  explicit EdgeMapRenderer(std::span<const ShadedSoupPart> parts, const EdgeMapOptions& options = {});

  // The G-buffer pass and the filter at target's size, then readback. Nothing is drawn into
  // `target`. With `timer` (a frame of it open) the two passes are its stages g_buffer and
  // edge_filter; the readback is outside them.
  [[nodiscard]] EdgeMapImage render(const OffscreenTarget& target, const Camera& camera, EdgeFilter filter,
                                    GpuStageTimer* timer = nullptr);
  // The same passes without readback, at width x height (the G-buffer and edge map are made or
  // remade at that size when needed).
  void draw(std::uint32_t width, std::uint32_t height, const Camera& camera, EdgeFilter filter,
            GpuStageTimer* timer = nullptr);

  // The last draw's textures (std::logic_error before the first draw) and what they were drawn
  // from: for the styles (gpu/edge_style.h).
  [[nodiscard]] const GBuffer& g_buffer() const;
  [[nodiscard]] const EdgeMap& edge_map() const;
  [[nodiscard]] const ShadedSoupMesh& mesh() const { return mesh_; }
  [[nodiscard]] const SceneBounds& bounds() const { return bounds_; }
  // fitted_depth_range(camera, bounds()): what the G-buffer's depth is normalised to.
  [[nodiscard]] DepthRange depth_range(const Camera& camera) const;

 private:
  EdgeMapOptions options_;
  ShadedSoupMesh mesh_;
  SceneBounds bounds_;
  GBufferRenderer g_buffer_pass_;
  EdgeMapFilter filter_;
  std::optional<GBuffer> g_buffer_;
  std::optional<EdgeMap> edge_map_;
};

}  // namespace shadowcert::gpu
