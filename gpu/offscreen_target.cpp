#include "gpu/offscreen_target.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "gpu/detail/gl_readback.h"
#include "gpu/gl_error.h"

namespace shadowcert::gpu {
namespace {

std::string size_text(std::uint32_t w, std::uint32_t h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

OffscreenTarget::OffscreenTarget(std::uint32_t width, std::uint32_t height)
    : width_(width),
      height_(height),
      colour_(Renderbuffer::create()),
      depth_stencil_(Renderbuffer::create()),
      framebuffer_(Framebuffer::create()) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width == 0 || height == 0 || width > static_cast<std::uint32_t>(max_size) ||
      height > static_cast<std::uint32_t>(max_size)) {
    throw GlError("OffscreenTarget: size " + size_text(width, height) + " outside 1.." + std::to_string(max_size));
  }
  const auto w = static_cast<GLsizei>(width);
  const auto h = static_cast<GLsizei>(height);
  glNamedRenderbufferStorage(colour_.name(), GL_RGBA8, w, h);
  glNamedRenderbufferStorage(depth_stencil_.name(), GL_DEPTH24_STENCIL8, w, h);
  glNamedFramebufferRenderbuffer(framebuffer_.name(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_.name());
  glNamedFramebufferRenderbuffer(framebuffer_.name(), GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                 depth_stencil_.name());
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer_.name(), GL_FRAMEBUFFER);
  check_gl_errors(("OffscreenTarget " + size_text(width, height)).c_str());
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("OffscreenTarget " + size_text(width, height) + ": framebuffer incomplete (status 0x" +
                  [&] { char b[8]; std::snprintf(b, sizeof b, "%04X", status); return std::string(b); }() + ")");
  }
}

void OffscreenTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.name());
  glViewport(0, 0, static_cast<GLsizei>(width_), static_cast<GLsizei>(height_));
}

void OffscreenTarget::clear(const std::array<float, 4>& colour) const {
  // Masks gate clears: a method that left writes off must not keep us from clearing.
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  glClearNamedFramebufferfv(framebuffer_.name(), GL_COLOR, 0, colour.data());
  glClearNamedFramebufferfi(framebuffer_.name(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
}

RgbaImage OffscreenTarget::read_colour() const {
  RgbaImage image(width_, height_);
  image.pixels = detail::read_framebuffer<std::uint8_t>(framebuffer_.name(), GL_COLOR_ATTACHMENT0, GL_RGBA,
                                                        GL_UNSIGNED_BYTE, {width_, height_, 4},
                                                        "OffscreenTarget::read_colour");
  return image;
}

GrayImage OffscreenTarget::read_stencil() const {
  GrayImage image(width_, height_);
  image.pixels = detail::read_framebuffer<std::uint8_t>(framebuffer_.name(), GL_NONE, GL_STENCIL_INDEX,
                                                        GL_UNSIGNED_BYTE, {width_, height_, 1},
                                                        "OffscreenTarget::read_stencil");
  return image;
}

GrayImage lit_mask(const GrayImage& stencil) {
  GrayImage mask(stencil.width, stencil.height);
  std::transform(stencil.pixels.begin(), stencil.pixels.end(), mask.pixels.begin(),
                 [](std::uint8_t count) { return static_cast<std::uint8_t>(count == 0 ? 255 : 0); });
  return mask;
}

}  // namespace shadowcert::gpu
