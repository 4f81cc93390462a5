#include "gpu/geometry_shader_volume.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>

#include "gpu/detail/compute_pass.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// Binding points and uniform locations fixed by layout() in the gs shaders.
constexpr GLuint kVerticesBinding = 0;
constexpr GLuint kRecordsBinding = 1;
constexpr GLuint kTrianglesBinding = 2;
constexpr GLuint kCaptureBinding = 0;       // transform feedback buffer
constexpr GLuint kFinishCommandBinding = 0;  // the finish shader's Command
constexpr GLint kLightLocation = 0;
constexpr GLint kRecordCountLocation = 1;
constexpr GLint kFinishCapacityLocation = 0;

constexpr std::uint32_t kRecordHeaderWords = 4;  // u, v, opposite count, unused (uvec4 aligned)
constexpr std::uint32_t kRecordWords = kRecordHeaderWords + kOppositesPerRecord;
constexpr std::uint64_t kVerticesPerSideOrCaps = 6;  // one quad or front + back cap: two triangles
// The capture is one plain buffer (no storage-block window as cs has); bounded so that a huge
// scene's worst case does not claim all memory: an overflow is reported, never drawn past.
constexpr std::uint64_t kMaxCaptureBytes = std::uint64_t{1} << 30;

using compute_pass::Command;
using compute_pass::kVertexBytes;
using compute_pass::upload;

}  // namespace

GeometryShaderShadowVolume::GeometryShaderShadowVolume(const ComputeVolumeSoup& soup, const EdgeTable& table,
                                                       SignMode sign)
    : soup_(&soup),
      records_(Buffer::create()),
      command_(Buffer::create()),
      volume_(Buffer::create()),
      points_(VertexArray::create()),
      vertex_array_(VertexArray::create()),
      generated_(Query::create(GL_PRIMITIVES_GENERATED)),
      no_attachments_(Framebuffer::create()) {
  if (table.size() != soup.edge_count() || table.first_opposite.size() != table.size() + 1)
    throw std::invalid_argument("GeometryShaderShadowVolume: the edge table is not the soup's");
  // Records: an edge's opposites in chunks of kOppositesPerRecord (Milet's per-edge loop,
  // split so that the geometry shader's output has a small fixed bound).
  std::vector<std::uint32_t> records;
  // At most one partial record per edge beyond the full ones.
  records.reserve(kRecordWords * (table.size() + table.opposite_vertex.size() / kOppositesPerRecord));
  std::uint64_t record_count = 0;
  for (std::size_t e = 0; e < table.size(); ++e) {
    for (std::uint32_t first = table.first_opposite[e]; first < table.first_opposite[e + 1];
         first += kOppositesPerRecord) {
      const std::uint32_t count = std::min(kOppositesPerRecord, table.first_opposite[e + 1] - first);
      records.insert(records.end(), {table.edges[e][0], table.edges[e][1], count, 0u});
      for (std::uint32_t k = 0; k < kOppositesPerRecord; ++k)
        records.push_back(k < count ? table.opposite_vertex[first + k] : 0u);
      ++record_count;
    }
  }
  if (record_count + soup.triangle_count() > static_cast<std::uint64_t>(std::numeric_limits<GLsizei>::max()))
    throw std::invalid_argument("GeometryShaderShadowVolume: more records and triangles than one draw holds");
  record_count_ = static_cast<std::uint32_t>(record_count);
  upload(records_, records);

  const Shader vertex =
      compile_shader(GL_VERTEX_SHADER, shaders::geometry_shader_volume_vert, "geometry_shader_volume.vert.glsl");
  const Shader geometry =
      compile_shader(GL_GEOMETRY_SHADER, shaders::geometry_shader_volume_geom, "geometry_shader_volume.geom.glsl",
                     sign_mode_defines(sign));
  program_ = link_program({&vertex, &geometry}, "geometry_shader_volume");
  const Shader finish = compile_shader(GL_COMPUTE_SHADER, shaders::geometry_shader_volume_finish_comp,
                                       "geometry_shader_volume_finish.comp.glsl");
  finish_ = link_program({&finish}, "geometry_shader_volume_finish");

  // A multiple of 6 so that a clamped count still ends on a whole quad or cap pair.
  std::uint64_t limit = kMaxCaptureBytes / kVertexBytes;
  limit = std::min<std::uint64_t>(limit, std::numeric_limits<GLint>::max());
  capacity_ = std::min(soup.worst_case_vertices(), limit / kVerticesPerSideOrCaps * kVerticesPerSideOrCaps);
  const Command initial{};
  glNamedBufferStorage(command_.name(), sizeof initial, &initial, GL_DYNAMIC_STORAGE_BIT);
  glNamedBufferStorage(volume_.name(), static_cast<GLsizeiptr>(std::max<std::uint64_t>(capacity_, 1) * kVertexBytes),
                       nullptr, 0);
  compute_pass::attach_volume(vertex_array_, volume_);
  // A surfaceless context has no default framebuffer: the capture draw gets a framebuffer
  // without attachments (GL 4.3), complete with any default size.
  glNamedFramebufferParameteri(no_attachments_.name(), GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
  glNamedFramebufferParameteri(no_attachments_.name(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
  check_gl_errors("GeometryShaderShadowVolume buffers");
}

void GeometryShaderShadowVolume::build(const Light& light) {
  const GLuint program = program_.name();
  compute_pass::set_light_uniform(program, kLightLocation, light, "GeometryShaderShadowVolume::build");
  glProgramUniform1ui(program, kRecordCountLocation, record_count_);
  glProgramUniform1ui(finish_.name(), kFinishCapacityLocation, static_cast<GLuint>(capacity_));

  const Command reset{};
  glNamedBufferSubData(command_.name(), 0, sizeof reset, &reset);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVerticesBinding, soup_->vertices_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRecordsBinding, records_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTrianglesBinding, soup_->triangles_.name());
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, kCaptureBinding, volume_.name());

  // Capture only: nothing of this draw reaches the framebuffer.
  GLint previous_framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_framebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, no_attachments_.name());
  glEnable(GL_RASTERIZER_DISCARD);
  glUseProgram(program);
  glBindVertexArray(points_.name());
  glBeginQueryIndexed(GL_PRIMITIVES_GENERATED, 0, generated_.name());
  glBeginTransformFeedback(GL_TRIANGLES);
  const std::uint32_t items = record_count_ + soup_->triangle_count();
  if (items != 0) glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(items));
  glEndTransformFeedback();
  glEndQueryIndexed(GL_PRIMITIVES_GENERATED, 0);
  glBindVertexArray(0);
  // Unbind the capture program before the finish program is made current: Mesa (llvmpipe,
  // Debian 12) keeps a compute program made current straight after a graphics program
  // referenced after glUseProgram(0), so the deleted finish program stayed alive (glIsProgram
  // true) once this object was destroyed (tests/gpu/gl_resource_test.cpp).
  glUseProgram(0);
  glDisable(GL_RASTERIZER_DISCARD);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous_framebuffer));
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, kCaptureBinding, 0);

  // Every primitive generated, captured or not, into `requested`, on the GPU (no stall);
  // the finish dispatch turns it into the draw count.
  glGetQueryBufferObjectuiv(generated_.name(), command_.name(), GL_QUERY_RESULT,
                            static_cast<GLintptr>(offsetof(Command, requested)));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFinishCommandBinding, command_.name());
  glUseProgram(finish_.name());
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);
  for (GLuint binding = kVerticesBinding; binding <= kTrianglesBinding; ++binding)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
  check_gl_errors("GeometryShaderShadowVolume::build");
}

std::uint64_t GeometryShaderShadowVolume::read_requested_vertices() const {
  return compute_pass::read_command(command_.name(), "GeometryShaderShadowVolume readback").requested;
}

std::vector<VolumeTriangle> GeometryShaderShadowVolume::read_triangles() const {
  return compute_pass::read_drawn_triangles<VolumeTriangle>(command_.name(), volume_.name(), "GeometryShaderShadowVolume readback");
}

}  // namespace shadowcert::gpu
