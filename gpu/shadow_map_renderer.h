#pragma once
// The `shadowmap` baseline (docs/definitions.md#speed-against-error): no volume, no
// counting identity. Per light, the depth of the receivers that cast (ShadedSoupPart::casts:
// a part that only receives is left out) is rendered from the light into a
// GL_DEPTH_COMPONENT32F texture; the scene pass compares each visible point's light-space
// depth with it (GL_COMPARE_REF_TO_TEXTURE, hardware comparison, one nearest texel, no PCF)
// and adds the light's Lambert term where the comparison says lit.
//   point light: a perspective frustum from the light aimed at the centre of the scene's
//     bounding box, its field of view the smallest symmetric one holding the box's corners;
//   directional light: an orthographic box fitted to the scene's bounds seen along -l.
// Its errors are the method's own: texel-sized staircases along shadow boundaries (fewer as
// the map grows), and acne or peter-panning traded through the two bias options.
// Frame output is StencilShadowFrame, as the stencil methods give: there are no counts, so
// first_stencil holds 0 where the first light's comparison says lit and 1 where it says
// shadowed (0 where no receiver covers the pixel), and first_lit_mask = lit_mask(first_stencil).
#include <array>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "gpu/gl_object.h"
#include "gpu/gpu_stage_timer.h"
#include "gpu/offscreen_target.h"
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

// Axis-aligned bounds of the scene, what the light's frustum or box is fitted to.
struct SceneBounds {
  Vec3 lo{0.0, 0.0, 0.0};
  Vec3 hi{0.0, 0.0, 0.0};
};
// The bounds of a soup's referenced vertices; throws std::invalid_argument when it has none.
[[nodiscard]] SceneBounds soup_bounds(const Soup& soup);

// World to the light's clip space, fitted to `bounds` (see the top of this file). A point
// light too close to or inside the box gets a capped field of view (receivers outside it are
// lit; kMaxPointLightHalfAngleTangent in the .cpp). Throws std::invalid_argument for a
// directional l = 0 or a point light at the bounds' centre.
[[nodiscard]] glm::dmat4 light_to_clip(const Light& light, const SceneBounds& bounds);

struct ShadowMapOptions {
  float depth_bias = kDefaultShadowMapBias;
  float slope_scale = kDefaultShadowMapSlope;
  std::array<float, 4> background{0.0f, 0.0f, 0.0f, 0.0f};  // alpha 0 marks uncovered pixels
  std::array<float, 3> ambient{0.15f, 0.15f, 0.15f};
  std::array<float, 3> light_colour{0.85f, 0.85f, 0.85f};
  bool read_back = true;  // off for timing: render() returns only what was drawn
  // When set (and a frame of it open), the depth pre-pass, each light's shadow_map pass and
  // lit pass are timed as its stages (gpu/gpu_stage_timer.h); readbacks stay outside them.
  GpuStageTimer* timer = nullptr;
};

class ShadowMapRenderer {
 public:
  // Allocates the size x size depth texture. Throws std::invalid_argument for size 0 or over
  // kMaxShadowMapSize, GlError when the driver cannot hold it.
  explicit ShadowMapRenderer(std::uint32_t size = kDefaultShadowMapSize);

  // Renders into `target` (bound and cleared here), one depth pass and one lit pass per
  // light. Throws GlError on a GL error, std::invalid_argument from light_to_clip.
  StencilShadowFrame render(const OffscreenTarget& target, const ShadedSoupMesh& receivers, const SceneBounds& bounds,
                            const Camera& camera, std::span<const Light> lights,
                            const ShadowMapOptions& options = {}) const;

  [[nodiscard]] std::uint32_t size() const { return size_; }

 private:
  std::uint32_t size_;
  Texture depth_;
  Framebuffer framebuffer_;
  Program depth_program_;
  Program scene_program_;
};

}  // namespace shadowcert::gpu
