#pragma once
// A 2D texture drawn into through a framebuffer of its own, with an optional depth
// renderbuffer: the storage of the edge-map passes (gpu/g_buffer.h's G-buffer, gpu/edge_map.h's
// edge map, gpu/edge_style.h's shaded scene). Internal to gpu/.
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/gl_object.h"

namespace shadowcert::gpu::detail {

class RenderTexture {
 public:
  // `format`: the texture's sized internal format (GL_RGBA32F, GL_RGBA8...); `depth`: a
  // GL_DEPTH_COMPONENT32F renderbuffer as well. Nearest filtering, clamped to the edge. Throws
  // GlError naming `name` and the size when the framebuffer is incomplete or the size is 0 or
  // beyond GL_MAX_TEXTURE_SIZE.
  RenderTexture(std::uint32_t width, std::uint32_t height, GLenum format, bool depth, const std::string& name);

  // Binds the framebuffer (draw and read) with a full-size viewport.
  void bind() const;
  // Clears colour to `colour` (and depth to 1), whatever the write masks were.
  void clear(const float (&colour)[4]) const;
  // The texture as RGBA floats, row-major, row 0 at the TOP (GL's rows are bottom-up).
  [[nodiscard]] std::vector<float> read_rgba() const;
  // Replaces the texture with RGBA floats in that layout (exactly width * height * 4 values).
  void upload_rgba(const std::vector<float>& rgba_top_first) const;
  void upload_rgba(const float* rgba_top_first) const;

  [[nodiscard]] std::uint32_t width() const { return width_; }
  [[nodiscard]] std::uint32_t height() const { return height_; }
  [[nodiscard]] GLuint texture() const { return texture_.name(); }
  [[nodiscard]] GLuint framebuffer() const { return framebuffer_.name(); }

 private:
  std::uint32_t width_;
  std::uint32_t height_;
  std::string name_;
  Texture texture_;
  Renderbuffer depth_;
  Framebuffer framebuffer_;
};

}  // namespace shadowcert::gpu::detail
