#include "gpu/gl_state_snapshot.h"

#include <array>
#include <stdexcept>
#include <string>

namespace shadowcert::gpu {
namespace {

// The capabilities captured (glIsEnabled) and set back (glEnable / glDisable) as a whole.
constexpr std::array<std::pair<GLenum, const char*>, 12> kCapabilities{{
    {GL_DEPTH_TEST, "GL_DEPTH_TEST"},
    {GL_STENCIL_TEST, "GL_STENCIL_TEST"},
    {GL_CULL_FACE, "GL_CULL_FACE"},
    {GL_DEPTH_CLAMP, "GL_DEPTH_CLAMP"},
    {GL_POLYGON_OFFSET_FILL, "GL_POLYGON_OFFSET_FILL"},
    {GL_RASTERIZER_DISCARD, "GL_RASTERIZER_DISCARD"},
    {GL_SAMPLE_ALPHA_TO_COVERAGE, "GL_SAMPLE_ALPHA_TO_COVERAGE"},
    {GL_SAMPLE_COVERAGE, "GL_SAMPLE_COVERAGE"},
    {GL_COLOR_LOGIC_OP, "GL_COLOR_LOGIC_OP"},
    {GL_PRIMITIVE_RESTART, "GL_PRIMITIVE_RESTART"},
    {GL_PRIMITIVE_RESTART_FIXED_INDEX, "GL_PRIMITIVE_RESTART_FIXED_INDEX"},
    {GL_MULTISAMPLE, "GL_MULTISAMPLE"},
}};

// Single-valued integer state, captured with glGetIntegerv; restored by the functions below.
constexpr std::array<std::pair<GLenum, const char*>, 33> kIntegers{{
    {GL_CURRENT_PROGRAM, "GL_CURRENT_PROGRAM"},
    {GL_VERTEX_ARRAY_BINDING, "GL_VERTEX_ARRAY_BINDING"},
    {GL_DRAW_INDIRECT_BUFFER_BINDING, "GL_DRAW_INDIRECT_BUFFER_BINDING"},
    {GL_ARRAY_BUFFER_BINDING, "GL_ARRAY_BUFFER_BINDING"},
    {GL_TRANSFORM_FEEDBACK_BINDING, "GL_TRANSFORM_FEEDBACK_BINDING"},
    {GL_SHADER_STORAGE_BUFFER_BINDING, "GL_SHADER_STORAGE_BUFFER_BINDING"},
    {GL_TRANSFORM_FEEDBACK_BUFFER_BINDING, "GL_TRANSFORM_FEEDBACK_BUFFER_BINDING"},
    {GL_PATCH_VERTICES, "GL_PATCH_VERTICES"},
    {GL_DEPTH_FUNC, "GL_DEPTH_FUNC"},
    {GL_DEPTH_WRITEMASK, "GL_DEPTH_WRITEMASK"},
    {GL_FRONT_FACE, "GL_FRONT_FACE"},
    {GL_STENCIL_FUNC, "GL_STENCIL_FUNC"},
    {GL_STENCIL_REF, "GL_STENCIL_REF"},
    {GL_STENCIL_VALUE_MASK, "GL_STENCIL_VALUE_MASK"},
    {GL_STENCIL_WRITEMASK, "GL_STENCIL_WRITEMASK"},
    {GL_STENCIL_FAIL, "GL_STENCIL_FAIL"},
    {GL_STENCIL_PASS_DEPTH_FAIL, "GL_STENCIL_PASS_DEPTH_FAIL"},
    {GL_STENCIL_PASS_DEPTH_PASS, "GL_STENCIL_PASS_DEPTH_PASS"},
    {GL_STENCIL_BACK_FUNC, "GL_STENCIL_BACK_FUNC"},
    {GL_STENCIL_BACK_REF, "GL_STENCIL_BACK_REF"},
    {GL_STENCIL_BACK_VALUE_MASK, "GL_STENCIL_BACK_VALUE_MASK"},
    {GL_STENCIL_BACK_WRITEMASK, "GL_STENCIL_BACK_WRITEMASK"},
    {GL_STENCIL_BACK_FAIL, "GL_STENCIL_BACK_FAIL"},
    {GL_STENCIL_BACK_PASS_DEPTH_FAIL, "GL_STENCIL_BACK_PASS_DEPTH_FAIL"},
    {GL_STENCIL_BACK_PASS_DEPTH_PASS, "GL_STENCIL_BACK_PASS_DEPTH_PASS"},
    {GL_STENCIL_CLEAR_VALUE, "GL_STENCIL_CLEAR_VALUE"},
    {GL_BLEND_SRC_RGB, "GL_BLEND_SRC_RGB"},
    {GL_BLEND_DST_RGB, "GL_BLEND_DST_RGB"},
    {GL_BLEND_SRC_ALPHA, "GL_BLEND_SRC_ALPHA"},
    {GL_BLEND_DST_ALPHA, "GL_BLEND_DST_ALPHA"},
    {GL_BLEND_EQUATION_RGB, "GL_BLEND_EQUATION_RGB"},
    {GL_BLEND_EQUATION_ALPHA, "GL_BLEND_EQUATION_ALPHA"},
    {GL_MAX_DRAW_BUFFERS, "GL_MAX_DRAW_BUFFERS"},  // how many per-draw-buffer values follow
}};

std::string indexed(const char* name, GLuint i) { return std::string(name) + "[" + std::to_string(i) + "]"; }

GLint integer(GLenum pname) {
  GLint v = 0;
  glGetIntegerv(pname, &v);
  return v;
}

GLint64 integer64(GLenum pname, GLuint index) {
  GLint64 v = 0;
  glGetInteger64i_v(pname, index, &v);
  return v;
}

}  // namespace

GlStateSnapshot GlStateSnapshot::capture() {
  GlStateSnapshot s;
  for (const auto& [cap, name] : kCapabilities) s.add(name, glIsEnabled(cap));
  for (const auto& [pname, name] : kIntegers) s.add(name, integer(pname));
  GLint polygon_mode[2] = {0, 0};
  glGetIntegerv(GL_POLYGON_MODE, polygon_mode);  // core profile: one mode for both faces
  s.add("GL_POLYGON_MODE", polygon_mode[0]);
  const auto draw_buffers = static_cast<GLuint>(integer(GL_MAX_DRAW_BUFFERS));
  for (GLuint i = 0; i < draw_buffers; ++i) {
    s.add(indexed("GL_BLEND", i), glIsEnabledi(GL_BLEND, i));
    GLboolean mask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    glGetBooleani_v(GL_COLOR_WRITEMASK, i, mask);
    s.add(indexed("GL_COLOR_WRITEMASK", i), mask[0] | mask[1] << 1 | mask[2] << 2 | mask[3] << 3);
  }
  for (GLuint i = 0; i < kSnapshotBufferBindings; ++i) {
    s.add(indexed("GL_SHADER_STORAGE_BUFFER_BINDING", i), integer64(GL_SHADER_STORAGE_BUFFER_BINDING, i));
    s.add(indexed("GL_SHADER_STORAGE_BUFFER_START", i), integer64(GL_SHADER_STORAGE_BUFFER_START, i));
    s.add(indexed("GL_SHADER_STORAGE_BUFFER_SIZE", i), integer64(GL_SHADER_STORAGE_BUFFER_SIZE, i));
  }
  // The transform feedback buffer bindings belong to the bound transform feedback object:
  // read here while the host's is bound (restore() binds it back before setting them).
  GLint max_feedback_buffers = 0;
  glGetIntegerv(GL_MAX_TRANSFORM_FEEDBACK_BUFFERS, &max_feedback_buffers);
  for (GLuint i = 0; i < static_cast<GLuint>(max_feedback_buffers) && i < kSnapshotBufferBindings; ++i) {
    s.add(indexed("GL_TRANSFORM_FEEDBACK_BUFFER_BINDING", i), integer64(GL_TRANSFORM_FEEDBACK_BUFFER_BINDING, i));
    s.add(indexed("GL_TRANSFORM_FEEDBACK_BUFFER_START", i), integer64(GL_TRANSFORM_FEEDBACK_BUFFER_START, i));
    s.add(indexed("GL_TRANSFORM_FEEDBACK_BUFFER_SIZE", i), integer64(GL_TRANSFORM_FEEDBACK_BUFFER_SIZE, i));
  }
  s.add("GL_MAX_TRANSFORM_FEEDBACK_BUFFERS", max_feedback_buffers);
  return s;
}

std::int64_t GlStateSnapshot::get(const std::string& name) const {
  for (const Value& v : values_)
    if (v.name == name) return v.value;
  throw std::logic_error("GlStateSnapshot::get: no value named " + name);
}

void GlStateSnapshot::restore() const {
  const auto u = [&](const std::string& name) { return static_cast<GLuint>(get(name)); };
  const auto e = [&](const std::string& name) { return static_cast<GLenum>(get(name)); };
  const auto i = [&](const std::string& name) { return static_cast<GLint>(get(name)); };
  for (const auto& [cap, name] : kCapabilities) get(name) != 0 ? glEnable(cap) : glDisable(cap);

  // The indexed bindings first: binding a range also sets the generic binding, which follows.
  // An indexed binding with size 0 was made by glBindBufferBase (the whole buffer).
  const auto rebind = [&](GLenum target, const char* binding, const char* start, const char* size, GLuint k) {
    const GLuint buffer = u(indexed(binding, k));
    const auto bytes = static_cast<GLsizeiptr>(get(indexed(size, k)));
    if (buffer != 0 && bytes != 0)
      glBindBufferRange(target, k, buffer, static_cast<GLintptr>(get(indexed(start, k))), bytes);
    else
      glBindBufferBase(target, k, buffer);
  };
  for (GLuint k = 0; k < kSnapshotBufferBindings; ++k)
    rebind(GL_SHADER_STORAGE_BUFFER, "GL_SHADER_STORAGE_BUFFER_BINDING", "GL_SHADER_STORAGE_BUFFER_START",
           "GL_SHADER_STORAGE_BUFFER_SIZE", k);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, u("GL_SHADER_STORAGE_BUFFER_BINDING"));
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, u("GL_TRANSFORM_FEEDBACK_BINDING"));
  const auto feedback_buffers = static_cast<GLuint>(get("GL_MAX_TRANSFORM_FEEDBACK_BUFFERS"));
  for (GLuint k = 0; k < feedback_buffers && k < kSnapshotBufferBindings; ++k)
    rebind(GL_TRANSFORM_FEEDBACK_BUFFER, "GL_TRANSFORM_FEEDBACK_BUFFER_BINDING", "GL_TRANSFORM_FEEDBACK_BUFFER_START",
           "GL_TRANSFORM_FEEDBACK_BUFFER_SIZE", k);
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, u("GL_TRANSFORM_FEEDBACK_BUFFER_BINDING"));

  glUseProgram(u("GL_CURRENT_PROGRAM"));
  glBindVertexArray(u("GL_VERTEX_ARRAY_BINDING"));
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, u("GL_DRAW_INDIRECT_BUFFER_BINDING"));
  glBindBuffer(GL_ARRAY_BUFFER, u("GL_ARRAY_BUFFER_BINDING"));
  glPatchParameteri(GL_PATCH_VERTICES, i("GL_PATCH_VERTICES"));

  glDepthFunc(e("GL_DEPTH_FUNC"));
  glDepthMask(get("GL_DEPTH_WRITEMASK") != 0 ? GL_TRUE : GL_FALSE);
  glFrontFace(e("GL_FRONT_FACE"));
  glPolygonMode(GL_FRONT_AND_BACK, e("GL_POLYGON_MODE"));
  glStencilFuncSeparate(GL_FRONT, e("GL_STENCIL_FUNC"), i("GL_STENCIL_REF"), u("GL_STENCIL_VALUE_MASK"));
  glStencilFuncSeparate(GL_BACK, e("GL_STENCIL_BACK_FUNC"), i("GL_STENCIL_BACK_REF"), u("GL_STENCIL_BACK_VALUE_MASK"));
  glStencilMaskSeparate(GL_FRONT, u("GL_STENCIL_WRITEMASK"));
  glStencilMaskSeparate(GL_BACK, u("GL_STENCIL_BACK_WRITEMASK"));
  glStencilOpSeparate(GL_FRONT, e("GL_STENCIL_FAIL"), e("GL_STENCIL_PASS_DEPTH_FAIL"), e("GL_STENCIL_PASS_DEPTH_PASS"));
  glStencilOpSeparate(GL_BACK, e("GL_STENCIL_BACK_FAIL"), e("GL_STENCIL_BACK_PASS_DEPTH_FAIL"),
                      e("GL_STENCIL_BACK_PASS_DEPTH_PASS"));
  glClearStencil(i("GL_STENCIL_CLEAR_VALUE"));
  glBlendFuncSeparate(e("GL_BLEND_SRC_RGB"), e("GL_BLEND_DST_RGB"), e("GL_BLEND_SRC_ALPHA"), e("GL_BLEND_DST_ALPHA"));
  glBlendEquationSeparate(e("GL_BLEND_EQUATION_RGB"), e("GL_BLEND_EQUATION_ALPHA"));
  const auto draw_buffers = static_cast<GLuint>(get("GL_MAX_DRAW_BUFFERS"));
  for (GLuint k = 0; k < draw_buffers; ++k) {
    get(indexed("GL_BLEND", k)) != 0 ? glEnablei(GL_BLEND, k) : glDisablei(GL_BLEND, k);
    const std::int64_t m = get(indexed("GL_COLOR_WRITEMASK", k));
    glColorMaski(k, (m & 1) != 0, (m & 2) != 0, (m & 4) != 0, (m & 8) != 0);
  }
}

std::vector<std::string> GlStateSnapshot::differences(const GlStateSnapshot& other) const {
  std::vector<std::string> lines;
  for (const Value& v : values_) {
    bool found = false;
    for (const Value& w : other.values_) {
      if (w.name != v.name) continue;
      found = true;
      if (w.value != v.value) lines.push_back(v.name + ": " + std::to_string(v.value) + " -> " + std::to_string(w.value));
    }
    if (!found) lines.push_back(v.name + ": missing in the other snapshot");
  }
  return lines;
}

}  // namespace shadowcert::gpu
