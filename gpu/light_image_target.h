#pragma once
// Where the shadow map family writes a light's amount of light per pixel (docs/smoothies.md, "The
// light image"): an R32F colour renderbuffer and a DEPTH24_STENCIL8 one (the depth format of
// OffscreenTarget, so the nearest receiver per pixel is the one the frame shows), of the frame's
// size. gpu/shadow_map_renderer.cpp draws the receivers into it once per frame for the first light.
#include <cstdint>
#include <vector>

#include "gpu/gl_object.h"

namespace shadowcert::gpu {

// What read_light() holds where no receiver covers the pixel (the clear value).
inline constexpr float kUncoveredLight = -1.0f;

class LightImageTarget {
 public:
  // Throws GlError naming the size when the framebuffer is incomplete or too large.
  LightImageTarget(std::uint32_t width, std::uint32_t height);

  // Binds it as the draw framebuffer with a full-size viewport.
  void bind() const;
  // Clears the colour to kUncoveredLight, depth to 1 and stencil to 0.
  void clear() const;
  // width x height floats, row 0 at the TOP (gpu/image.h's convention).
  [[nodiscard]] std::vector<float> read_light() const;

  [[nodiscard]] std::uint32_t width() const { return width_; }
  [[nodiscard]] std::uint32_t height() const { return height_; }

 private:
  std::uint32_t width_;
  std::uint32_t height_;
  Renderbuffer light_;
  Renderbuffer depth_stencil_;
  Framebuffer framebuffer_;
};

}  // namespace shadowcert::gpu
