#include "gpu/viewer_frame.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

#include "gpu/camera_transform.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"
#include "gpu/stencil_passes.h"

namespace shadowcert::gpu {

ViewerFrame::ViewerFrame(std::span<const ShadedSoupPart> parts, std::uint32_t width, std::uint32_t height)
    : target_(width, height),
      receivers_(parts), program_(std::make_unique<ShadowSceneProgram>()), empty_(VertexArray::create()) {
  const Shader vertex = compile_shader(GL_VERTEX_SHADER, shaders::screen_triangle_vert, "screen_triangle.vert.glsl");
  const Shader fragment = compile_shader(GL_FRAGMENT_SHADER, shaders::overlay_frag, "overlay.frag.glsl");
  overlay_program_ = link_program({&vertex, &fragment}, "overlay");
  check_gl_errors("ViewerFrame");
}

ViewerFrame::~ViewerFrame() = default;

void ViewerFrame::draw(const Camera& camera, const HostShadowVolumes& shadows) const {
  if (camera.width != target_.width() || camera.height != target_.height())
    throw std::invalid_argument("ViewerFrame::draw: the camera's size is not the frame's");
  // What StencilShadowRenderer's first pass does.
  const StencilShadowOptions defaults;
  target_.bind();
  target_.clear(defaults.background);
  const glm::mat4 world_to_clip(projection_matrix(camera) * view_matrix(camera));
  program_->set_world_to_clip(world_to_clip);
  program_->set_ambient(defaults.ambient);
  glUseProgram(program_->name());
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindVertexArray(receivers_.vertex_array());
  glDrawArrays(GL_TRIANGLES, 0, receivers_.vertex_count());
  glBindVertexArray(0);
  glUseProgram(0);

  // Each light's share of the light colour, as ShadowMethodRenderer gives it.
  std::array<float, 3> colour = defaults.light_colour;
  for (float& c : colour) c /= static_cast<float>(shadows.light_count());
  const HostReceivers r = host_receivers(receivers_);
  for (std::size_t k = 0; k < shadows.light_count(); ++k) shadows.draw_lit(world_to_clip, k, r, colour);
  check_gl_errors("ViewerFrame::draw");
}

void ViewerFrame::draw_overlay(const RgbaImage& overlay) const {
  if (overlay.width != target_.width() || overlay.height != target_.height())
    throw std::invalid_argument("ViewerFrame::draw_overlay: the overlay's size is not the frame's");
  // Its own target, not whatever is bound: work between draw() and here (the viewer renders
  // the exact comparison offscreen) may have bound another framebuffer.
  target_.bind();
  Texture texture = Texture::create(GL_TEXTURE_2D);
  glTextureStorage2D(texture.name(), 1, GL_RGBA8, static_cast<GLsizei>(overlay.width),
                     static_cast<GLsizei>(overlay.height));
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture.name(), 0, 0, 0, static_cast<GLsizei>(overlay.width),
                      static_cast<GLsizei>(overlay.height), GL_RGBA, GL_UNSIGNED_BYTE, overlay.pixels.data());
  glBindTextureUnit(0, texture.name());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);  // the frame's alpha marks coverage
  glUseProgram(overlay_program_.name());
  glBindVertexArray(empty_.name());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_BLEND);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBindTextureUnit(0, 0);
  check_gl_errors("ViewerFrame::draw_overlay");
}

void ViewerFrame::present() const {
  const auto w = static_cast<GLint>(target_.width()), h = static_cast<GLint>(target_.height());
  glBlitNamedFramebuffer(target_.framebuffer(), 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  check_gl_errors("ViewerFrame::present");
}

RgbaImage ViewerFrame::read_colour() const {
  const std::uint32_t width = target_.width(), height = target_.height();
  RgbaImage image(width, height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<std::uint8_t> rows(image.pixels.size());
  glReadPixels(0, 0, static_cast<GLsizei>(width), static_cast<GLsizei>(height), GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  const std::size_t row_bytes = std::size_t{width} * 4;
  for (std::uint32_t r = 0; r < height; ++r)  // GL's row 0 is the bottom one
    std::copy_n(rows.data() + std::size_t{height - 1 - r} * row_bytes, row_bytes, image.pixels.data() + r * row_bytes);
  check_gl_errors("ViewerFrame::read_colour");
  return image;
}

}  // namespace shadowcert::gpu
