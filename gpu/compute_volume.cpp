#include "gpu/compute_volume.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/detail/compute_pass.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// Binding points and uniform locations fixed by layout() in compute_volume.comp.glsl.
constexpr GLuint kVerticesBinding = 0;
constexpr GLuint kEdgesBinding = 1;
constexpr GLuint kFirstOppositeBinding = 2;
constexpr GLuint kOppositeVertexBinding = 3;
constexpr GLuint kTrianglesBinding = 4;
constexpr GLuint kSignsBinding = 5;
constexpr GLuint kCommandBinding = 6;
constexpr GLuint kVolumeBinding = 7;
constexpr GLint kLightLocation = 0;
constexpr GLint kPassKindLocation = 1;
constexpr GLint kItemCountLocation = 2;
constexpr GLint kCapacityLocation = 3;
constexpr GLint kEdgeCountLocation = 4;
constexpr GLuint kEdgePass = 0, kTrianglePass = 1, kFinishPass = 2;

constexpr std::uint64_t kVerticesPerSideOrCaps = 6;  // one quad or front + back cap: two triangles
// Wide far edges (gpu/shaders/far_split.glsl) add up to 7 triangles to a quad and 21 to a back
// cap; they occur only on edges whose diametral sphere holds the light, so the volumes are
// sized for the unsplit worst case plus a quarter and 64 Ki vertices; past that, the overflow
// is reported (`requested`), never drawn open.
constexpr std::uint64_t kSplitHeadroomDivisor = 4;
constexpr std::uint64_t kSplitHeadroomVertices = 65536;
using compute_pass::Command;
using compute_pass::dispatch;
using compute_pass::kVertexBytes;
using compute_pass::upload;

template <class T>
std::vector<T> read_buffer(GLuint buffer, std::size_t offset_items, std::size_t count) {
  return compute_pass::read_buffer<T>(buffer, offset_items, count, "ComputeShadowVolume readback");
}

}  // namespace

ComputeVolumeSoup::ComputeVolumeSoup(const Soup& canonical, const EdgeTable& table)
    : vertices_(Buffer::create()),
      edges_(Buffer::create()),
      first_opposite_(Buffer::create()),
      opposite_vertex_(Buffer::create()),
      triangles_(Buffer::create()) {
  constexpr std::size_t kMax = std::numeric_limits<std::uint32_t>::max();
  if (canonical.vertices.size() > kMax || canonical.triangles.size() > kMax || table.size() >= kMax ||
      table.first_opposite.size() != table.size() + 1 || table.first_opposite.back() != table.opposite_vertex.size())
    throw std::invalid_argument("ComputeVolumeSoup: the edge table does not fit the soup or 32-bit counts");
  require_indices_in_range(canonical, "ComputeVolumeSoup");
  // Rounded once from double, exactly as HomogeneousMesh's finite vertices (and
  // to_precision<float> in core/light_side_formula.h): the shader evaluates these floats.
  std::vector<std::array<float, 4>> vertices;
  vertices.reserve(canonical.vertices.size());
  for (const Vec3& x : canonical.vertices)
    vertices.push_back({static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2]), 1.0f});
  upload(vertices_, vertices);
  upload(edges_, table.edges);
  upload(first_opposite_, table.first_opposite);
  upload(opposite_vertex_, table.opposite_vertex);
  upload(triangles_, canonical.triangles);
  edge_count_ = static_cast<std::uint32_t>(table.size());
  triangle_count_ = static_cast<std::uint32_t>(canonical.triangles.size());
  const std::uint64_t unsplit =
      kVerticesPerSideOrCaps * (static_cast<std::uint64_t>(table.opposite_vertex.size()) + triangle_count_);
  worst_case_vertices_ = unsplit + (unsplit / kSplitHeadroomDivisor + kSplitHeadroomVertices) /
                                       kVerticesPerSideOrCaps * kVerticesPerSideOrCaps;
  check_gl_errors("ComputeVolumeSoup upload");
}

ComputeShadowVolume::ComputeShadowVolume(const ComputeVolumeSoup& soup, SignMode sign)
    : soup_(&soup),
      signs_(Buffer::create()),
      command_(Buffer::create()),
      volume_(Buffer::create()),
      vertex_array_(VertexArray::create()) {
  const Shader shader =
      compile_shader(GL_COMPUTE_SHADER, shaders::compute_volume_comp, "compute_volume.comp.glsl",
                     sign_mode_defines(sign));
  program_ = link_program({&shader}, "compute_volume");

  // Worst case, but no more than one storage block may address (llvmpipe: 128 MiB) nor a
  // draw count hold; a multiple of 6 so that a clamped count still ends on a triangle.
  GLint64 max_block_bytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
  std::uint64_t limit = static_cast<std::uint64_t>(std::max<GLint64>(max_block_bytes, 0)) / kVertexBytes;
  limit = std::min<std::uint64_t>(limit, std::numeric_limits<GLint>::max());
  capacity_ = std::min(soup.worst_case_vertices(), limit / kVerticesPerSideOrCaps * kVerticesPerSideOrCaps);
  const std::uint64_t sign_count = std::uint64_t{soup.edge_count()} + soup.triangle_count();
  glNamedBufferStorage(signs_.name(), static_cast<GLsizeiptr>(std::max<std::uint64_t>(sign_count, 1) * sizeof(GLint)),
                       nullptr, 0);
  const Command initial{};
  glNamedBufferStorage(command_.name(), sizeof initial, &initial, GL_DYNAMIC_STORAGE_BIT);
  glNamedBufferStorage(volume_.name(),
                       static_cast<GLsizeiptr>(std::max<std::uint64_t>(capacity_, 1) * kVertexBytes), nullptr, 0);
  compute_pass::attach_volume(vertex_array_, volume_);
  check_gl_errors("ComputeShadowVolume buffers");
}

void ComputeShadowVolume::build(const Light& light) {
  const GLuint program = program_.name();
  compute_pass::set_light_uniform(program, kLightLocation, light, "ComputeShadowVolume::build");
  glProgramUniform1ui(program, kCapacityLocation, static_cast<GLuint>(capacity_));
  glProgramUniform1ui(program, kEdgeCountLocation, soup_->edge_count());

  const Command reset{};
  glNamedBufferSubData(command_.name(), 0, sizeof reset, &reset);
  const ComputeVolumeSoup& s = *soup_;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVerticesBinding, s.vertices_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kEdgesBinding, s.edges_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFirstOppositeBinding, s.first_opposite_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOppositeVertexBinding, s.opposite_vertex_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTrianglesBinding, s.triangles_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSignsBinding, signs_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCommandBinding, command_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVolumeBinding, volume_.name());
  glUseProgram(program);

  // Edges and triangles only add to the counter and write disjoint ranges: no barrier between.
  glProgramUniform1ui(program, kPassKindLocation, kEdgePass);
  glProgramUniform1ui(program, kItemCountLocation, s.edge_count());
  dispatch(s.edge_count());
  glProgramUniform1ui(program, kPassKindLocation, kTrianglePass);
  glProgramUniform1ui(program, kItemCountLocation, s.triangle_count());
  dispatch(s.triangle_count());
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the finish pass reads the final counter
  glProgramUniform1ui(program, kPassKindLocation, kFinishPass);
  glProgramUniform1ui(program, kItemCountLocation, 1);
  glDispatchCompute(1, 1, 1);
  // The indirect draw reads the command, the vertex pass the volume, readbacks both.
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);
  for (GLuint binding = kVerticesBinding; binding <= kVolumeBinding; ++binding)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
  check_gl_errors("ComputeShadowVolume::build");
}

std::vector<std::int32_t> ComputeShadowVolume::read_multiplicities() const {
  return read_buffer<std::int32_t>(signs_.name(), 0, soup_->edge_count());
}

std::vector<std::int32_t> ComputeShadowVolume::read_triangle_signs() const {
  return read_buffer<std::int32_t>(signs_.name(), soup_->edge_count(), soup_->triangle_count());
}

std::uint64_t ComputeShadowVolume::read_requested_vertices() const {
  return compute_pass::read_command(command_.name(), "ComputeShadowVolume readback").requested;
}

std::vector<VolumeTriangle> ComputeShadowVolume::read_triangles() const {
  return compute_pass::read_drawn_triangles<VolumeTriangle>(command_.name(), volume_.name(), "ComputeShadowVolume readback");
}

}  // namespace shadowcert::gpu
