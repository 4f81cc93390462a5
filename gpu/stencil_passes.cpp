#include "gpu/stencil_passes.h"

#include <glm/gtc/type_ptr.hpp>

#include "gpu/embedded_shaders.h"
#include "gpu/shader_compiler.h"
#include "gpu/shadow_scene_uniforms.h"

namespace shadowcert::gpu {
namespace {

// The volume pass's stencil operations: z-fail counts back faces +1 and front faces -1 where
// the depth test fails, z-pass front +1 and back -1 where it passes; `swapped` exchanges the
// facings (IndirectVolumeDraw::reversed: each triangle counts as its own reversal).
void set_volume_stencil_ops(StencilMethod method, bool swapped) {
  const GLenum front = swapped ? GL_BACK : GL_FRONT;
  const GLenum back = swapped ? GL_FRONT : GL_BACK;
  if (method == StencilMethod::zfail) {
    glStencilOpSeparate(back, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
    glStencilOpSeparate(front, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
  } else {
    // z-pass. The caps are drawn as well and never count here (GL_LESS fails for them): a
    // front cap lies on a receiver at the visible point's depth or behind it, a back cap at
    // depth 1. A cap between the eye and the near plane (depth-clamped to 0) would count;
    // a z-pass proven by exact/zpass_proof.h has no face there.
    glStencilOpSeparate(front, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
    glStencilOpSeparate(back, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
  }
}

}  // namespace

ShadowSceneProgram::ShadowSceneProgram() {
  const Shader vertex = compile_shader(GL_VERTEX_SHADER, shaders::shadow_scene_vert, "shadow_scene.vert.glsl");
  const Shader fragment = compile_shader(GL_FRAGMENT_SHADER, shaders::shadow_scene_frag, "shadow_scene.frag.glsl");
  program_ = link_program({&vertex, &fragment}, "shadow_scene");
}

void ShadowSceneProgram::set_world_to_clip(const glm::mat4& world_to_clip) const {
  glProgramUniformMatrix4fv(program_.name(), shadow_scene_uniforms::kWorldToClip, 1, GL_FALSE, glm::value_ptr(world_to_clip));
}

void ShadowSceneProgram::set_ambient(const std::array<float, 3>& rgb) const {
  glProgramUniform1f(program_.name(), shadow_scene_uniforms::kLambertWeight, 0.0f);
  glProgramUniform4f(program_.name(), shadow_scene_uniforms::kColour, rgb[0], rgb[1], rgb[2], 1.0f);
}

void ShadowSceneProgram::set_lit(const Light& light, const std::array<float, 3>& rgb) const {
  const std::array<double, 4>& l = light.position;
  glProgramUniform4f(program_.name(), shadow_scene_uniforms::kLight, static_cast<float>(l[0]), static_cast<float>(l[1]),
                     static_cast<float>(l[2]), static_cast<float>(l[3]));
  glProgramUniform1f(program_.name(), shadow_scene_uniforms::kLambertWeight, 1.0f);
  glProgramUniform4f(program_.name(), shadow_scene_uniforms::kColour, rgb[0], rgb[1], rgb[2], 1.0f);
}

void begin_volume_pass() {
  glStencilMask(0xFF);
  const GLint zero = 0;
  glClearBufferiv(GL_STENCIL, 0, &zero);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 0, 0xFF);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_LESS);      // a cap at the visible point's own depth fails: "behind" it
  glEnable(GL_DEPTH_CLAMP);  // w = 0 caps reach depth 1 exactly; rounding must not clip them
}

void count_volume(const LightVolume& lv, StencilMethod method) {
  set_volume_stencil_ops(method, false);
  if (lv.volume != nullptr) {
    glBindVertexArray(lv.volume->vertex_array());
    glDrawElements(GL_TRIANGLES, lv.volume->index_count(), GL_UNSIGNED_INT, nullptr);
  }
  if (lv.indirect.vertex_array != 0 && lv.indirect.command != 0) {
    glBindVertexArray(lv.indirect.vertex_array);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, lv.indirect.command);
    glDrawArraysIndirect(GL_TRIANGLES, nullptr);
    if (lv.indirect.reversed) {
      set_volume_stencil_ops(method, true);
      // The second DrawArraysIndirectCommand: four GLuint after the first.
      glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(4 * sizeof(GLuint)));
      set_volume_stencil_ops(method, false);
    }
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  }
  glBindVertexArray(0);
}

void end_volume_pass() { glDisable(GL_DEPTH_CLAMP); }

void begin_lit_pass(const ShadowSceneProgram& program, const Light& light, const std::array<float, 3>& rgb) {
  glStencilFunc(GL_EQUAL, 0, 0xFF);
  // A pixel lit once: its count becomes 1 and the receivers' second copy (ShadedSoupMesh)
  // fails the test. The next light clears the stencil first.
  glStencilOpSeparate(GL_FRONT_AND_BACK, GL_KEEP, GL_KEEP, GL_INCR);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_EQUAL);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  program.set_lit(light, rgb);
}

void end_lit_pass(const ShadowSceneProgram& program) {
  glDisable(GL_BLEND);
  glProgramUniform1f(program.name(), shadow_scene_uniforms::kLambertWeight, 0.0f);
}

}  // namespace shadowcert::gpu
