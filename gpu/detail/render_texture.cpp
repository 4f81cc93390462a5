#include "gpu/detail/render_texture.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "gpu/detail/gl_readback.h"
#include "gpu/gl_error.h"

namespace shadowcert::gpu::detail {
namespace {

std::string size_text(std::uint32_t w, std::uint32_t h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

RenderTexture::RenderTexture(std::uint32_t width, std::uint32_t height, GLenum format, bool depth,
                             const std::string& name)
    : width_(width), height_(height), name_(name), texture_(Texture::create(GL_TEXTURE_2D)),
      framebuffer_(Framebuffer::create()) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (width == 0 || height == 0 || width > static_cast<std::uint32_t>(max_size) ||
      height > static_cast<std::uint32_t>(max_size)) {
    throw GlError(name + ": size " + size_text(width, height) + " outside 1.." + std::to_string(max_size));
  }
  const auto w = static_cast<GLsizei>(width);
  const auto h = static_cast<GLsizei>(height);
  const GLuint texture = texture_.name();
  glTextureStorage2D(texture, 1, format, w, h);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT0, texture, 0);
  if (depth) {
    depth_ = Renderbuffer::create();
    glNamedRenderbufferStorage(depth_.name(), GL_DEPTH_COMPONENT32F, w, h);
    glNamedFramebufferRenderbuffer(framebuffer_.name(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.name());
  }
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer_.name(), GL_FRAMEBUFFER);
  check_gl_errors((name + " " + size_text(width, height)).c_str());
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char code[16];
    std::snprintf(code, sizeof code, "%04X", status);
    throw GlError(name + " " + size_text(width, height) + ": framebuffer incomplete (status 0x" + code + ")");
  }
}

void RenderTexture::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.name());
  glViewport(0, 0, static_cast<GLsizei>(width_), static_cast<GLsizei>(height_));
}

void RenderTexture::clear(const float (&colour)[4]) const {
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glClearNamedFramebufferfv(framebuffer_.name(), GL_COLOR, 0, colour);
  if (depth_) {
    glDepthMask(GL_TRUE);
    const float one = 1.0f;
    glClearNamedFramebufferfv(framebuffer_.name(), GL_DEPTH, 0, &one);
  }
}

std::vector<float> RenderTexture::read_rgba() const {
  return read_texture<float>(texture_.name(), GL_RGBA, GL_FLOAT, {width_, height_, 4}, RowOrder::top_first,
                             (name_ + " read").c_str());
}

void RenderTexture::upload_rgba(const std::vector<float>& rgba_top_first) const {
  if (rgba_top_first.size() != std::size_t{width_} * height_ * 4)
    throw std::invalid_argument(name_ + " upload: expected " + std::to_string(std::size_t{width_} * height_ * 4) +
                                " floats, got " + std::to_string(rgba_top_first.size()));
  upload_rgba(rgba_top_first.data());
}

void RenderTexture::upload_rgba(const float* rgba_top_first) const {
  std::vector<float> rows(rgba_top_first, rgba_top_first + std::size_t{width_} * height_ * 4);
  flip_rows(rows.data(), ReadbackShape{width_, height_, 4});
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage2D(texture_.name(), 0, 0, 0, static_cast<GLsizei>(width_), static_cast<GLsizei>(height_), GL_RGBA,
                      GL_FLOAT, rows.data());
  check_gl_errors((name_ + " upload").c_str());
}

}  // namespace shadowcert::gpu::detail
