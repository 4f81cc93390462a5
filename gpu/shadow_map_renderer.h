#pragma once
// The `shadowmap` baseline (docs/definitions.md#speed-against-error): no volume, no
// counting identity. Per light, the depth of the receivers that cast (ShadedSoupPart::casts:
// a part that only receives is left out) is rendered from the light into a
// GL_DEPTH_COMPONENT32F texture; the scene pass compares each visible point's light-space
// depth with it (GL_COMPARE_REF_TO_TEXTURE, hardware comparison, one nearest texel, no PCF)
// and adds the light's Lambert term where the comparison says lit.
//   point light: a perspective frustum from the light aimed at the centre of the scene's
//     bounding box, its field of view the smallest symmetric one holding the box's corners;
//     a point light inside the box (a lamp in a room, at its centre included) or so near it
//     that this half angle would exceed atan(8) gets a cube map instead: six 90-degree faces,
//     each a perspective frustum along one axis drawn into its layer of an array texture, and
//     one lit pass in which each fragment reads the face its direction falls in (light_views,
//     shaders/cube_face.glsl);
//   directional light: an orthographic box fitted to the scene's bounds seen along -l.
// Its errors are the method's own: texel-sized staircases along shadow boundaries (fewer as
// the map grows), and acne or peter-panning traded through the two bias options.
// Frame output is StencilShadowFrame, as the stencil methods give: there are no counts, so
// first_stencil holds 0 where the first light's comparison says lit and 1 where it says
// shadowed (0 where no receiver covers the pixel), and first_lit_mask = lit_mask(first_stencil).
//
// Filters (docs/smoothies.md; ShadowFilter, chosen at construction; shaders/shadow_filter.glsl):
//   hard      the above, unchanged (the `shadowmap` method);
//   pcf       percentage-closer filtering, K x K comparisons at whole-texel offsets (`pcf`);
//   pcss      percentage-closer soft shadows (Fernando 2005): blocker search, then PCF over the
//             penumbra the blockers' mean depth predicts for a disk light of radius R (`pcss`);
//   smoothie  the hard comparison, then the nearest smoothie in front of the point, its alpha
//             remapped (Chen & Tsai §3; gpu/smoothie_map.h) (`smoothie`).
// The soft filters give an amount of light in [0, 1]: the lit pass adds the Lambert term times
// it, and first_stencil marks a pixel shadowed where the amount is below kLitThreshold.
// Every readback frame also holds the first light's amount per pixel (StencilShadowFrame::
// first_light), drawn in one more pass of the receivers into a LightImageTarget.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "gpu/gl_object.h"
#include "gpu/gpu_stage_timer.h"
#include "gpu/light_image_target.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method.h"
#include "gpu/smoothie_map.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu {

inline constexpr std::uint32_t kDefaultShadowMapSize = 2048;
// GL_MAX_TEXTURE_SIZE of llvmpipe and of the NVIDIA drivers we target; a 16384^2 32-bit
// depth texture is already 1 GiB.
inline constexpr std::uint32_t kMaxShadowMapSize = 16384;
// Subtracted from the reference depth (light window depth, [0, 1]) before the comparison: it
// absorbs the map's float32 rounding and the difference between the depth interpolated at a
// map texel's centre and at the visible point inside that texel on a surface facing the
// light. Too small: acne (lit floors speckled with shadow); too large: shadows detach from
// their casters (peter-panning). Depth is non-linear under the point light's perspective,
// the near plane sits just before the scene's bounds, so 1e-4 is a few millimetres at the
// far end of default.json.
inline constexpr float kDefaultShadowMapBias = 1.0e-4f;
// glPolygonOffset factor of the depth pass: pushes each surface away from the light by its
// depth slope times this, which absorbs the texel-sized depth error of surfaces seen nearly
// edge-on from the light (where the constant bias alone would have to be large).
inline constexpr float kDefaultShadowMapSlope = 2.0f;

// ShadowFilter (hard, pcf, pcss, smoothie) is gpu/shadow_method.h's: each method names its filter there.

// pcf: K x K taps, K odd, from 1 (the hard map, pixel for pixel) to this (225 taps).
inline constexpr std::uint32_t kDefaultPcfKernel = 3;
inline constexpr std::uint32_t kMaxPcfKernel = 15;
// Soft filters: first_stencil marks a pixel lit (0) where the first light's amount is at least
// this, the middle of the penumbra, so the lit mask stays comparable with the hard boundary.
inline constexpr float kLitThreshold = 0.5f;

// Axis-aligned bounds of the scene, what the light's frustum or box is fitted to.
struct SceneBounds {
  Vec3 lo{0.0, 0.0, 0.0};
  Vec3 hi{0.0, 0.0, 0.0};
};
// The bounds of a soup's referenced vertices; throws std::invalid_argument when it has none.
[[nodiscard]] SceneBounds soup_bounds(const Soup& soup);

// pcss without a light radius (ShadowMethodOptions::light_radius = 0): this fraction of the
// diagonal of the scene's bounds, about 0.17 on default.json (diagonal about 17). A point
// light's disk is in world units, so its default follows the scene's scale.
inline constexpr double kDefaultLightRadiusFraction = 0.01;
[[nodiscard]] double default_light_radius(const SceneBounds& bounds);

// A directional light's size is an angle, the angular radius of its disk (a sun), whatever the
// scene's scale (a 1000-unit scene gets the same sun as a 1-unit one). Its default is the
// angle the default point-light disk subtends from one scene diagonal away, atan(0.01) =
// 0.573 degrees, so that both kinds of light cast penumbrae of one width by default (the
// real sun's is 0.27 degrees). Must lie in (0, kMaxLightAngleDegrees).
inline constexpr double kDefaultLightAngleDegrees = 0.57293869768349;  // atan(kDefaultLightRadiusFraction)
// Exclusive: at 90 degrees the disk's tangent, which the filters and the soft reference
// scale penumbrae by, is infinite.
inline constexpr double kMaxLightAngleDegrees = 90.0;
// tan(degrees): the half-width of the penumbra per unit of distance between caster and
// receiver that pcss and the soft reference use for a directional light. Throws
// std::invalid_argument("light_angle_tangent: ...") outside (0, kMaxLightAngleDegrees).
[[nodiscard]] double light_angle_tangent(double degrees);

// The light's view of the scene, fitted to `bounds` (see the top of this file): one of the
// views light_views returns.
struct LightFrustum {
  glm::dmat4 view{1.0};        // world to the light's view (looking down -z)
  glm::dmat4 projection{1.0};  // view to clip
  double near = 0.0, far = 0.0;  // linear depths along the light's axis
  // Point light: the tangent of the half field of view (both axes); directional light: the
  // box's half width and half height. Texture coordinates span 2 * that (* depth) world units.
  double tangent = 0.0;
  std::array<double, 2> half_extent{0.0, 0.0};
  bool orthographic = false;  // directional light
  // 0..5: this view is the face of a point light's cube map looking along +x, -x, +y, -y, +z,
  // -z (shaders/cube_face.glsl assigns each direction from the light to one of them); -1: the
  // light's one map.
  int cube_face = -1;
};

// Whether a point light is drawn with a cube map: it lies inside `bounds` or so near them
// that one frustum holding the box would need a half angle over atan(8) (beyond, the map's
// texels stretch until it means nothing, and a corner behind the light cannot be held at all).
// False for a directional light.
[[nodiscard]] bool needs_cube_map(const Light& light, const SceneBounds& bounds);

// The views `light`'s depth map is drawn in: one (a directional light's box, a point light's
// frustum), or for needs_cube_map the faces of its cube map that can hold part of the bounds
// (a face along which no corner of the box lies ahead of the light is left out), in face
// order. A cube face's half angle is atan(1.02), a little over 45 degrees, so that
// neighbouring faces overlap by about 1 % of a face (20 texels at 2048: PCF's widest kernel
// reads across a seam); its far plane holds the box, and its near plane is `nearest_receiver`
// (the light's distance to the nearest receiver, nearest_receiver_distance) over sqrt(3) (the
// nearest a point at that distance can be along a face's axis), so that no receiver is in
// front of it, but at least 1/1000 of the far plane (depth precision); nearest_receiver <= 0 or
// not finite (unknown): 1/64 of the far plane (constants in the .cpp). Throws
// std::invalid_argument("light_views: ...") for a directional l = 0 or a light that is not
// finite.
[[nodiscard]] std::vector<LightFrustum> light_views(const Light& light, const SceneBounds& bounds,
                                                    double nearest_receiver = 0.0);

// The distance from a point light to the nearest triangle of `parts` (as drawn: the vertices
// rounded to float), in double; infinity without a triangle. What light_views takes as
// `nearest_receiver`. Throws std::invalid_argument("nearest_receiver_distance: ...") for a
// directional light.
[[nodiscard]] double nearest_receiver_distance(std::span<const ShadedSoupPart> parts, const Light& light);

struct ShadowMapOptions {
  float depth_bias = kDefaultShadowMapBias;
  float slope_scale = kDefaultShadowMapSlope;
  std::array<float, 4> background{0.0f, 0.0f, 0.0f, 0.0f};  // alpha 0 marks uncovered pixels
  std::array<float, 3> ambient{0.15f, 0.15f, 0.15f};
  std::array<float, 3> light_colour{0.85f, 0.85f, 0.85f};
  bool read_back = true;  // off for timing: render() returns only what was drawn
  // When set (and a frame of it open), the depth pre-pass, each light's shadow_map pass,
  // smoothie_map pass and lit pass are timed as its stages (gpu/gpu_stage_timer.h); readbacks
  // and the light-image pass stay outside them.
  GpuStageTimer* timer = nullptr;
  // pcf: K, odd, in [1, kMaxPcfKernel].
  std::uint32_t pcf_kernel = kDefaultPcfKernel;
  // pcss: a point light's radius R, finite and > 0, in world units (a disk of radius R around
  // it, as the soft reference's, docs/smoothies.md), and a directional light's angular radius
  // in degrees, in (0, kMaxLightAngleDegrees).
  double light_radius = 0.0;
  double light_angle_degrees = kDefaultLightAngleDegrees;
  // Per light, in the lights' order, the distance from a point light to the nearest receiver
  // (nearest_receiver_distance; a directional light's entry is unread): the near plane of a
  // cube map (light_views). Empty: unknown (a fixed fraction of the far plane).
  std::span<const double> nearest_receivers;
  // smoothie: one mesh per light, in the lights' order (gpu/smoothie_map.h).
  std::span<const SmoothieQuads* const> smoothies;
};

class ShadowMapRenderer {
 public:
  // Allocates the size x size depth texture (and for `smoothie` the smoothie map of the same
  // size); a light that needs a cube map gets six more layers of each in its first render().
  // Throws std::invalid_argument for size 0 or over kMaxShadowMapSize, GlError when the driver
  // cannot hold it.
  explicit ShadowMapRenderer(std::uint32_t size = kDefaultShadowMapSize, ShadowFilter filter = ShadowFilter::hard);

  // Renders into `target` (bound and cleared here), per light one depth pass per view
  // (light_views: six for a cube map; smoothie: and as many smoothie map passes) and one lit
  // pass; with read_back, the light-image pass of the first light too. Throws GlError on a GL
  // error (a cube map the driver cannot hold among them),
  // std::invalid_argument from light_views, and std::invalid_argument("ShadowMapRenderer::render:
  // ...") for a pcf kernel that is even or out of range, a pcss light radius that is not finite
  // and > 0 or light angle out of range, nearest_receivers neither empty nor one per light, or
  // smoothie meshes that are not one per light.
  StencilShadowFrame render(const OffscreenTarget& target, const ShadedSoupMesh& receivers, const SceneBounds& bounds,
                            const Camera& camera, std::span<const Light> lights,
                            const ShadowMapOptions& options = {}) const;

  [[nodiscard]] std::uint32_t size() const { return size_; }
  [[nodiscard]] ShadowFilter filter() const { return filter_; }

 private:
  std::uint32_t size_;
  ShadowFilter filter_;
  Texture depth_;
  Framebuffer framebuffer_;
  Sampler depth_values_;  // the map without comparison: pcss's blocker search
  std::optional<SmoothieMap> smoothie_map_;
  Program depth_program_;
  Program scene_program_;
  // The first light's amount of light per pixel, reallocated when the target's size changes (a
  // cache of the const render(), hence mutable).
  mutable std::optional<LightImageTarget> light_image_;
  // A point light's cube map (light_views): six layers of the map's size, depth (and for
  // `smoothie` the smoothie map's RG32F, each face copied in after its smoothie pass), with a
  // framebuffer per depth layer; allocated by the first render() that needs one (a cache of the
  // const render(), hence mutable). 6 x 16 MiB of depth at 2048.
  struct CubeMap {
    Texture depth;
    std::array<Framebuffer, 6> layers;
    Texture smoothie;
  };
  mutable std::optional<CubeMap> cube_map_;
  const CubeMap& cube_map() const;
};

}  // namespace shadowcert::gpu
