#include "gpu/flat_soup_renderer.h"

#include <glm/gtc/type_ptr.hpp>

#include "gpu/camera_transform.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {
// Uniform locations fixed by layout(location) in the shaders.
constexpr GLint kWorldToClipLocation = 0;
constexpr GLint kColourLocation = 1;
}  // namespace

FlatSoupRenderer::FlatSoupRenderer() {
  const Shader vertex = compile_shader(GL_VERTEX_SHADER, shaders::flat_colour_vert, "flat_colour.vert.glsl");
  const Shader fragment = compile_shader(GL_FRAGMENT_SHADER, shaders::flat_colour_frag, "flat_colour.frag.glsl");
  program_ = link_program({&vertex, &fragment}, "flat_colour");
}

void FlatSoupRenderer::draw(const SoupMesh& mesh, const Camera& camera, const FlatDrawOptions& options) const {
  const glm::mat4 world_to_clip(projection_matrix(camera) * view_matrix(camera));
  glProgramUniformMatrix4fv(program_.name(), kWorldToClipLocation, 1, GL_FALSE, glm::value_ptr(world_to_clip));
  glProgramUniform4fv(program_.name(), kColourLocation, 1, options.colour.data());

  glDisable(GL_CULL_FACE);
  if (options.depth_test) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  if (options.count_in_stencil) {
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 0, 0xFF);
    // Wrap, not saturate: docs/definitions.md#pixel-protocol compares stencil counts modulo 256.
    glStencilOpSeparate(GL_FRONT_AND_BACK, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
  } else {
    glDisable(GL_STENCIL_TEST);
  }
  glUseProgram(program_.name());
  glBindVertexArray(mesh.vertex_array());
  glDrawElements(GL_TRIANGLES, mesh.index_count(), GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glUseProgram(0);
  check_gl_errors("FlatSoupRenderer::draw");
}

}  // namespace shadowcert::gpu
