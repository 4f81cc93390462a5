#include "gpu/per_triangle_volume.h"

#include <array>
#include <algorithm>
#include <limits>
#include <stdexcept>

#include "gpu/detail/compute_pass.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// Binding points and uniform locations fixed by layout() in per_triangle_volume.comp.glsl.
constexpr GLuint kVerticesBinding = 0;
constexpr GLuint kTrianglesBinding = 1;
constexpr GLuint kSignsBinding = 2;
constexpr GLuint kCommandBinding = 3;
constexpr GLuint kFirstWindowBinding = 4;
constexpr GLuint kWindows = 4;  // Volume0..3; 4 + 4 blocks is GL 4.3's guaranteed minimum of 8
constexpr GLint kLightLocation = 0;
constexpr GLint kPassKindLocation = 1;
constexpr GLint kItemCountLocation = 2;
constexpr GLint kCapacityLocation = 3;
constexpr GLint kWindowVerticesLocation = 4;
constexpr GLuint kTrianglePass = 0, kFinishPass = 1;

// A point light's V(t): front cap, 3 quads as 6 triangles, back cap (Milet 2014 §2.1).
constexpr std::uint64_t kVerticesPerTriangle = 24;
// Room for the wide far edges (gpu/shaders/far_split.glsl), which add triangles to a V(t)
// whose far edges span more than a right angle (the light close to the triangle, between an
// edge's ends): one V(t) in kSplitHeadroom may grow by up to 87 more triangles at once;
// beyond that the overflow is reported (VolumeCapacityError), never drawn open.
constexpr std::uint64_t kSplitHeadroom = 8;
constexpr std::uint64_t kSplitExtraVertices = 3 * 87;
using compute_pass::kVertexBytes;

// The shader's Command block: the forward part's DrawArraysIndirectCommand, the reversed
// part's (IndirectVolumeDraw::reversed: its triangles count as their own reversals), then the
// vertices each part asked for.
struct DrawCommand {
  GLuint count = 0;
  GLuint instance_count = 1;
  GLuint first = 0;
  GLuint base_instance = 0;
};
struct Commands {
  DrawCommand forward;
  DrawCommand reversed;
  GLuint requested = 0;
  GLuint reversed_requested = 0;
};
static_assert(sizeof(DrawCommand) == 4 * sizeof(GLuint), "the reversed command's offset in draw_volume");
static_assert(sizeof(Commands) == 10 * sizeof(GLuint), "std430 Command block of per_triangle_volume.comp.glsl");

template <class T>
std::vector<T> read_buffer(GLuint buffer, std::size_t offset_items, std::size_t count) {
  return compute_pass::read_buffer<T>(buffer, offset_items, count, "PerTriangleShadowVolume readback");
}

Commands read_commands(GLuint buffer) { return read_buffer<Commands>(buffer, 0, 1).front(); }

}  // namespace

PerTriangleShadowVolume::PerTriangleShadowVolume(const ComputeVolumeSoup& soup, SignMode sign)
    : soup_(&soup),
      signs_(Buffer::create()),
      command_(Buffer::create()),
      volume_(Buffer::create()),
      vertex_array_(VertexArray::create()) {
  const Shader shader =
      compile_shader(GL_COMPUTE_SHADER, shaders::per_triangle_volume_comp, "per_triangle_volume.comp.glsl",
                     sign_mode_defines(sign));
  program_ = link_program({&shader}, "per_triangle_volume");

  // A window is as much as one storage block addresses, rounded down to the binding offset
  // alignment (windows are ranges of one buffer) and to whole vec4.
  GLint64 max_block_bytes = 0;
  GLint alignment = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const std::uint64_t granule = std::max<std::uint64_t>(static_cast<std::uint64_t>(std::max(alignment, 1)), kVertexBytes);
  const std::uint64_t window_bytes = static_cast<std::uint64_t>(std::max<GLint64>(max_block_bytes, 0)) / granule * granule;
  window_vertices_ = std::max<std::uint64_t>(window_bytes / kVertexBytes, 1);
  // No more than the windows address nor a draw count holds; a multiple of 24 so that a
  // clamped count still ends on a whole V(t).
  std::uint64_t limit = std::min<std::uint64_t>(kWindows * window_vertices_, std::numeric_limits<GLint>::max());
  limit = std::min<std::uint64_t>(limit, std::numeric_limits<GLuint>::max() - kVerticesPerTriangle);
  const std::uint64_t triangles = soup.triangle_count();
  const std::uint64_t wanted =
      kVerticesPerTriangle * triangles + kSplitExtraVertices * ((triangles + kSplitHeadroom - 1) / kSplitHeadroom);
  capacity_ = std::min(wanted, limit / kVerticesPerTriangle * kVerticesPerTriangle);
  volume_bytes_ = std::max<std::uint64_t>(capacity_, 1) * kVertexBytes;

  glNamedBufferStorage(signs_.name(),
                       static_cast<GLsizeiptr>(std::max<std::uint64_t>(soup.triangle_count(), 1) * sizeof(GLint)),
                       nullptr, 0);
  const Commands initial{};
  glNamedBufferStorage(command_.name(), sizeof initial, &initial, GL_DYNAMIC_STORAGE_BIT);
  glNamedBufferStorage(volume_.name(), static_cast<GLsizeiptr>(volume_bytes_), nullptr, 0);
  compute_pass::attach_volume(vertex_array_, volume_);
  check_gl_errors("PerTriangleShadowVolume buffers");
}

void PerTriangleShadowVolume::build(const Light& light) {
  const GLuint program = program_.name();
  compute_pass::set_light_uniform(program, kLightLocation, light, "PerTriangleShadowVolume::build");
  glProgramUniform1ui(program, kCapacityLocation, static_cast<GLuint>(capacity_));
  glProgramUniform1ui(program, kWindowVerticesLocation, static_cast<GLuint>(window_vertices_));

  const Commands reset{};
  glNamedBufferSubData(command_.name(), 0, sizeof reset, &reset);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVerticesBinding, soup_->vertices_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTrianglesBinding, soup_->triangles_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSignsBinding, signs_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCommandBinding, command_.name());
  for (GLuint w = 0; w < kWindows; ++w) {
    // Windows past the buffer's end alias the first one: the shader never reaches them.
    std::uint64_t offset = w * window_vertices_ * kVertexBytes;
    if (offset >= volume_bytes_) offset = 0;
    const std::uint64_t size = std::min(window_vertices_ * kVertexBytes, volume_bytes_ - offset);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kFirstWindowBinding + w, volume_.name(),
                      static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(size));
  }
  glUseProgram(program);
  glProgramUniform1ui(program, kPassKindLocation, kTrianglePass);
  glProgramUniform1ui(program, kItemCountLocation, soup_->triangle_count());
  compute_pass::dispatch(soup_->triangle_count());
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the finish pass reads the final counter
  glProgramUniform1ui(program, kPassKindLocation, kFinishPass);
  glProgramUniform1ui(program, kItemCountLocation, 1);
  glDispatchCompute(1, 1, 1);
  // The indirect draw reads the command, the vertex pass the volume, readbacks both.
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);
  for (GLuint binding = kVerticesBinding; binding < kFirstWindowBinding + kWindows; ++binding)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
  check_gl_errors("PerTriangleShadowVolume::build");
}

std::vector<std::int32_t> PerTriangleShadowVolume::read_triangle_signs() const {
  return read_buffer<std::int32_t>(signs_.name(), 0, soup_->triangle_count());
}

std::uint64_t PerTriangleShadowVolume::read_requested_vertices() const {
  const Commands c = read_commands(command_.name());
  return std::uint64_t{c.requested} + c.reversed_requested;
}

std::vector<VolumeTriangle> PerTriangleShadowVolume::read_triangles() const {
  const Commands c = read_commands(command_.name());
  std::vector<VolumeTriangle> triangles = read_buffer<VolumeTriangle>(volume_.name(), 0, c.forward.count / 3);
  const std::vector<VolumeTriangle> reversed =
      read_buffer<VolumeTriangle>(volume_.name(), c.reversed.first / 3, c.reversed.count / 3);
  // As counted: each reversed triangle with its last two vertices swapped.
  for (const VolumeTriangle& t : reversed) triangles.push_back({t[0], t[2], t[1]});
  return triangles;
}

}  // namespace shadowcert::gpu
