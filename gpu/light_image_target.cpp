#include "gpu/light_image_target.h"

#include <algorithm>
#include <cstddef>
#include <string>

#include "gpu/detail/gl_readback.h"
#include "gpu/gl_error.h"

namespace shadowcert::gpu {

LightImageTarget::LightImageTarget(std::uint32_t width, std::uint32_t height)
    : width_(width),
      height_(height),
      light_(Renderbuffer::create()),
      depth_stencil_(Renderbuffer::create()),
      framebuffer_(Framebuffer::create()) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width == 0 || height == 0 || width > static_cast<std::uint32_t>(max_size) ||
      height > static_cast<std::uint32_t>(max_size))
    throw GlError("LightImageTarget: size " + size + " outside 1.." + std::to_string(max_size));
  glNamedRenderbufferStorage(light_.name(), GL_R32F, static_cast<GLsizei>(width), static_cast<GLsizei>(height));
  glNamedRenderbufferStorage(depth_stencil_.name(), GL_DEPTH24_STENCIL8, static_cast<GLsizei>(width),
                             static_cast<GLsizei>(height));
  glNamedFramebufferRenderbuffer(framebuffer_.name(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, light_.name());
  glNamedFramebufferRenderbuffer(framebuffer_.name(), GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                 depth_stencil_.name());
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer_.name(), GL_FRAMEBUFFER);
  check_gl_errors(("LightImageTarget " + size).c_str());
  if (status != GL_FRAMEBUFFER_COMPLETE) throw GlError("LightImageTarget " + size + ": framebuffer incomplete");
}

void LightImageTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.name());
  glViewport(0, 0, static_cast<GLsizei>(width_), static_cast<GLsizei>(height_));
}

void LightImageTarget::clear() const {
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  const float colour[4] = {kUncoveredLight, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(framebuffer_.name(), GL_COLOR, 0, colour);
  glClearNamedFramebufferfi(framebuffer_.name(), GL_DEPTH_STENCIL, 0, 1.0f, 0);
}

std::vector<float> LightImageTarget::read_light() const {
  return detail::read_framebuffer<float>(framebuffer_.name(), GL_COLOR_ATTACHMENT0, GL_RED, GL_FLOAT,
                                         {width_, height_, 1}, "LightImageTarget::read_light");
}

}  // namespace shadowcert::gpu
