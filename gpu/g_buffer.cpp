#include "gpu/g_buffer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "gpu/camera_transform.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// Uniform locations fixed by layout(location) in g_buffer.{vert,frag}.glsl.
constexpr GLint kWorldToClipLocation = 0;
constexpr GLint kWorldToViewLocation = 1;
constexpr GLint kDepthRangeLocation = 2;

}  // namespace

DepthRange fitted_depth_range(const Camera& camera, const SceneBounds& bounds) {
  const glm::dmat4 view = view_matrix(camera);
  double nearest = INFINITY, farthest = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec4 p((corner & 1) ? bounds.hi[0] : bounds.lo[0], (corner & 2) ? bounds.hi[1] : bounds.lo[1],
                       (corner & 4) ? bounds.hi[2] : bounds.lo[2], 1.0);
    const double depth = -(view * p).z;  // the camera looks down -z
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  DepthRange range;
  range.near = std::max(nearest, camera.near_plane);
  range.far = farthest > range.near ? farthest : range.near + 1.0;
  return range;
}

GBuffer::GBuffer(std::uint32_t width, std::uint32_t height) : target_(width, height, GL_RGBA32F, true, "GBuffer") {}

void GBuffer::bind_and_clear() const {
  target_.bind();
  const float uncovered[4] = {kUncoveredNormal[0], kUncoveredNormal[1], kUncoveredNormal[2], kBackgroundDepth};
  target_.clear(uncovered);
}

void GBuffer::upload(std::span<const float> rgba) const {
  if (rgba.size() != std::size_t{width()} * height() * 4)
    throw std::invalid_argument("GBuffer::upload: expected " + std::to_string(std::size_t{width()} * height() * 4) +
                                " floats (RGBA per pixel), got " + std::to_string(rgba.size()));
  target_.upload_rgba(rgba.data());
}

std::vector<float> GBuffer::read() const { return target_.read_rgba(); }

GBufferRenderer::GBufferRenderer() {
  const Shader vertex = compile_shader(GL_VERTEX_SHADER, shaders::g_buffer_vert, "g_buffer.vert.glsl");
  const Shader fragment = compile_shader(GL_FRAGMENT_SHADER, shaders::g_buffer_frag, "g_buffer.frag.glsl");
  program_ = link_program({&vertex, &fragment}, "g_buffer");
}

void GBufferRenderer::render(const GBuffer& g_buffer, const ShadedSoupMesh& mesh, const Camera& camera,
                             const DepthRange& range, GpuStageTimer* timer) const {
  if (!(range.far > range.near) || !std::isfinite(range.far) || !std::isfinite(range.near))
    throw std::invalid_argument("GBufferRenderer::render: the depth range needs near < far, got [" +
                                std::to_string(range.near) + ", " + std::to_string(range.far) + "]");
  const GLuint program = program_.name();
  const glm::dmat4 view = view_matrix(camera);
  const glm::mat4 world_to_clip(projection_matrix(camera) * view);
  const glm::mat4 world_to_view(view);
  glProgramUniformMatrix4fv(program, kWorldToClipLocation, 1, GL_FALSE, glm::value_ptr(world_to_clip));
  glProgramUniformMatrix4fv(program, kWorldToViewLocation, 1, GL_FALSE, glm::value_ptr(world_to_view));
  glProgramUniform2f(program, kDepthRangeLocation, static_cast<float>(range.near), static_cast<float>(range.far));

  const ScopedStage stage(timer, RenderStage::g_buffer);
  g_buffer.bind_and_clear();
  glUseProgram(program);
  glDisable(GL_CULL_FACE);  // soups have no orientation
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBindVertexArray(mesh.vertex_array());
  glDrawArrays(GL_TRIANGLES, 0, mesh.single_order_vertex_count());
  glBindVertexArray(0);
  glUseProgram(0);
  check_gl_errors("GBufferRenderer::render");
}

}  // namespace shadowcert::gpu
