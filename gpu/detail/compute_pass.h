#pragma once
// Plumbing shared by the GPU-built volumes (gpu/compute_volume.h `cs`,
// gpu/per_triangle_volume.h `pertri`, and the capture and finish passes of `gs` and `ts`):
// storage uploads, 1D work split over a 2D grid, the indirect draw command with its request
// counter, the light uniform, and the volume readbacks (over gpu/detail/gl_readback.h). Internal to gpu/: the shaders'
// layouts (Command, local size 64) are fixed here once.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/light.h"
#include "gpu/detail/gl_readback.h"
#include "gpu/gl_error.h"
#include "gpu/gl_object.h"

namespace shadowcert::gpu::compute_pass {

constexpr GLuint kLocalSize = 64;      // local_size_x of every volume shader
constexpr GLuint kMaxGroupsX = 65535;  // GL_MAX_COMPUTE_WORK_GROUP_COUNT[0]'s guaranteed minimum
constexpr std::uint64_t kVertexBytes = 4 * sizeof(float);  // one vec4 volume vertex

// DrawArraysIndirectCommand, then the vertices the passes reserved (the shaders' Command).
struct Command {
  GLuint count = 0;
  GLuint instance_count = 1;
  GLuint first = 0;
  GLuint base_instance = 0;
  GLuint requested = 0;
};

// glNamedBufferStorage rejects size 0: an empty array still gets a 4-byte buffer.
template <class T>
void upload(const Buffer& buffer, const std::vector<T>& data) {
  const std::uint32_t none = 0;
  glNamedBufferStorage(buffer.name(), data.empty() ? sizeof none : static_cast<GLsizeiptr>(data.size() * sizeof(T)),
                       data.empty() ? static_cast<const void*>(&none) : data.data(), 0);
}

// Sets a volume shader's `light` uniform (vec4 (l, w)) for a build: the light rounded once to
// float, as FloatSide<float> in exact/edge_multiplicity.cpp rounds it, so that the shaders'
// signs are refedge float32's. `function` names the caller for the error: throws as
// core/light.h's require_defined for a light docs/definitions.md#inputs does not define
// (nothing is set then).
inline void set_light_uniform(GLuint program, GLint location, const Light& light, const char* function) {
  require_defined(light, function);
  const std::array<double, 4>& l = light.position;
  glProgramUniform4f(program, location, static_cast<float>(l[0]), static_cast<float>(l[1]), static_cast<float>(l[2]),
                     static_cast<float>(l[3]));
}

// One invocation per item; the shaders skip ids past their item count and fold the y rows
// back into one index (gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64 + x).
inline void dispatch(std::uint32_t items) {
  const GLuint groups = (items + kLocalSize - 1) / kLocalSize;
  if (groups == 0) return;
  const GLuint x = std::min(groups, kMaxGroupsX);
  glDispatchCompute(x, (groups + x - 1) / x, 1);
}

using detail::read_buffer;  // gpu/detail/gl_readback.h: every readback of gpu/ is there

// What a build left in its indirect command: the vertices drawn (count) and reserved (requested).
inline Command read_command(GLuint command, const char* what) { return read_buffer<Command>(command, 0, 1, what).front(); }

// The triangles a build drew: the command's `count` vertices of `volume`, three per triangle.
template <class Triangle>
std::vector<Triangle> read_drawn_triangles(GLuint command, GLuint volume, const char* what) {
  return read_buffer<Triangle>(volume, 0, read_command(command, what).count / 3, what);
}

// A vertex array reading `volume` as tightly packed vec4 at attribute 0 (what
// StencilShadowRenderer's volume pass expects of an IndirectVolumeDraw).
inline void attach_volume(const VertexArray& vertex_array, const Buffer& volume) {
  glVertexArrayVertexBuffer(vertex_array.name(), 0, volume.name(), 0, static_cast<GLsizei>(kVertexBytes));
  glVertexArrayAttribFormat(vertex_array.name(), 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vertex_array.name(), 0, 0);
  glEnableVertexArrayAttrib(vertex_array.name(), 0);
}

}  // namespace shadowcert::gpu::compute_pass
