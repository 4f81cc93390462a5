#pragma once
// The framebuffer every method renders into: RGBA8 colour + DEPTH24_STENCIL8, of a given
// size, with readbacks of colour, of the exact per-pixel stencil counts (docs/definitions.md#pixel-protocol
// compares them modulo 256) and of the lit mask derived from them.
#include <array>
#include <cstdint>

#include "gpu/gl_object.h"
#include "gpu/image.h"

namespace shadowcert::gpu {

class OffscreenTarget {
 public:
  // Throws GlError naming the size when the framebuffer is incomplete or too large.
  OffscreenTarget(std::uint32_t width, std::uint32_t height);

  // Binds it as the draw and read framebuffer with a full-size viewport.
  void bind() const;
  // Clears colour (RGBA in [0, 1]), depth to 1 and stencil to 0.
  void clear(const std::array<float, 4>& colour = {0.0f, 0.0f, 0.0f, 1.0f}) const;

  [[nodiscard]] RgbaImage read_colour() const;
  [[nodiscard]] GrayImage read_stencil() const;  // the stencil byte of each pixel, unchanged

  [[nodiscard]] std::uint32_t width() const { return width_; }
  [[nodiscard]] std::uint32_t height() const { return height_; }
  [[nodiscard]] GLuint framebuffer() const { return framebuffer_.name(); }

 private:
  std::uint32_t width_;
  std::uint32_t height_;
  Renderbuffer colour_;
  Renderbuffer depth_stencil_;
  Framebuffer framebuffer_;
};

// 255 where the stencil count is 0 (lit), 0 where it is not (in shadow): the mask the
// pixel protocol compares, as a PNG-ready image.
[[nodiscard]] GrayImage lit_mask(const GrayImage& stencil);

}  // namespace shadowcert::gpu
