#pragma once
// Every synchronous GPU-to-CPU copy of gpu/, in one place (internal to gpu/): a framebuffer's
// pixels, a texture's texels and a buffer's items, each checked for GL errors under the
// caller's name, images returned top row first. Each of these waits for the GPU: callers use
// them for results (a frame's images, a volume as drawn), never inside timed frames.
//
//   std::vector<std::uint8_t> rgba = read_framebuffer<std::uint8_t>(fbo, GL_COLOR_ATTACHMENT0,
//       GL_RGBA, GL_UNSIGNED_BYTE, {w, h, 4}, "OffscreenTarget::read_colour");
//   std::vector<float> rg = read_texture<float>(texture, GL_RG, GL_FLOAT, {w, h, 2}, RowOrder::gl, "...");
//   std::vector<Command> c = read_buffer<Command>(buffer, 0, 1, "...");
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gpu/gl_error.h"
#include "gpu/gl_object.h"

namespace shadowcert::gpu::detail {

// An image's shape: width x height pixels of `channels` items each.
struct ReadbackShape {
  std::uint32_t width = 0, height = 0;
  std::uint32_t channels = 1;
  [[nodiscard]] std::size_t items() const { return std::size_t{width} * height * channels; }
};

// GL's rows run bottom-up; images top-down. The same swap converts either way.
template <class T>
void flip_rows(T* items, const ReadbackShape& shape) {
  const std::size_t stride = std::size_t{shape.width} * shape.channels;
  for (std::uint32_t top = 0, bottom = shape.height == 0 ? 0 : shape.height - 1; top < bottom; ++top, --bottom)
    std::swap_ranges(items + top * stride, items + (top + 1) * stride, items + bottom * stride);
}

// Whether a readback keeps GL's bottom-up rows (textures read as data: a shadow or smoothie map)
// or returns an image, top row first.
enum class RowOrder { gl, top_first };

// The pixels of `framebuffer` (its `read_buffer` attachment, GL_NONE for stencil or depth),
// top row first. Packing alignment 1: rows of 1-byte pixels need not be 4-aligned.
template <class T>
std::vector<T> read_framebuffer(GLuint framebuffer, GLenum read_buffer, GLenum format, GLenum type,
                                const ReadbackShape& shape, const char* what) {
  std::vector<T> items(shape.items());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  if (read_buffer != GL_NONE) glReadBuffer(read_buffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, static_cast<GLsizei>(shape.width), static_cast<GLsizei>(shape.height), format, type,
               items.data());
  check_gl_errors(what);
  flip_rows(items.data(), shape);
  return items;
}

// Level 0 of `texture` in the given row order.
template <class T>
std::vector<T> read_texture(GLuint texture, GLenum format, GLenum type, const ReadbackShape& shape, RowOrder order,
                            const char* what) {
  std::vector<T> items(shape.items());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(texture, 0, format, type, static_cast<GLsizei>(items.size() * sizeof(T)), items.data());
  check_gl_errors(what);
  if (order == RowOrder::top_first) flip_rows(items.data(), shape);
  return items;
}

// `count` items of type T from `buffer`, starting at item `offset_items`.
template <class T>
std::vector<T> read_buffer(GLuint buffer, std::size_t offset_items, std::size_t count, const char* what) {
  std::vector<T> out(count);
  if (count != 0)
    glGetNamedBufferSubData(buffer, static_cast<GLintptr>(offset_items * sizeof(T)),
                            static_cast<GLsizeiptr>(count * sizeof(T)), out.data());
  check_gl_errors(what);
  return out;
}

}  // namespace shadowcert::gpu::detail
