#include "gpu/tessellation_volume.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

#include "gpu/detail/compute_pass.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_environment_error.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// Binding points and uniform locations fixed by layout() in the ts shaders.
constexpr GLuint kVerticesBinding = 0;
constexpr GLuint kDeferredBinding = 1;       // control and finish shaders
constexpr GLuint kCaptureBinding = 0;        // transform feedback buffer
constexpr GLuint kFinishCommandBinding = 2;  // tessellation_volume_finish.comp.glsl
constexpr GLuint kFinishRecordsBinding = 3;
constexpr GLuint kFinishVolumeBinding = 4;
constexpr GLint kLightLocation = 0;
constexpr GLint kFinishLightLocation = 0;
constexpr GLint kFinishCapacityLocation = 1;

// The control shader's float filter alone where signs are exact (its records the filter cannot
// decide go to the finish pass, which has the exact stage): tessellation_volume.tesc.glsl says why.
constexpr std::string_view kFilterOnlyDefine = "#define SHADOWCERT_SIGN_FILTER_ONLY 1\n";

constexpr std::uint32_t kTriangleKind = 1;
constexpr std::uint32_t kRecordWords = 4 + kTessellationOppositesPerRecord;  // u, v, count, kind, opposites
constexpr std::uint64_t kVerticesPerSideOrCaps = 6;
constexpr std::uint64_t kMaxCaptureBytes = std::uint64_t{1} << 30;  // as gs

using compute_pass::Command;
using compute_pass::kVertexBytes;
using compute_pass::upload;

}  // namespace

TessellationShadowVolume::TessellationShadowVolume(const ComputeVolumeSoup& soup, const EdgeTable& table,
                                                   SignMode sign)
    : soup_(&soup),
      records_(Buffer::create()),
      deferred_(Buffer::create()),
      command_(Buffer::create()),
      volume_(Buffer::create()),
      patches_(VertexArray::create()),
      vertex_array_(VertexArray::create()),
      generated_(Query::create(GL_PRIMITIVES_GENERATED)),
      no_attachments_(Framebuffer::create()) {
  if (table.size() != soup.edge_count() || table.first_opposite.size() != table.size() + 1)
    throw std::invalid_argument("TessellationShadowVolume: the edge table is not the soup's");
  GLint max_level = 0;
  GLint max_patch_vertices = 0;
  glGetIntegerv(GL_MAX_TESS_GEN_LEVEL, &max_level);
  glGetIntegerv(GL_MAX_PATCH_VERTICES, &max_patch_vertices);
  // |partial m| <= K isolines per patch: K below half the maximal level (Milet's 2|m| - 1).
  if (static_cast<std::int64_t>(kTessellationOppositesPerRecord) >= max_level / 2 ||
      static_cast<std::int64_t>(kRecordWords) > max_patch_vertices)
    throw GlEnvironmentError("TessellationShadowVolume: GL_MAX_TESS_GEN_LEVEL " + std::to_string(max_level) +
                             " / GL_MAX_PATCH_VERTICES " + std::to_string(max_patch_vertices) +
                             " too small for records of " + std::to_string(kTessellationOppositesPerRecord) +
                             " opposites");

  std::vector<std::uint32_t> records;
  std::uint64_t record_count = 0;
  for (std::size_t e = 0; e < table.size(); ++e) {
    for (std::uint32_t first = table.first_opposite[e]; first < table.first_opposite[e + 1];
         first += kTessellationOppositesPerRecord) {
      const std::uint32_t count = std::min(kTessellationOppositesPerRecord, table.first_opposite[e + 1] - first);
      records.insert(records.end(), {table.edges[e][0], table.edges[e][1], count, 0u});
      for (std::uint32_t k = 0; k < kTessellationOppositesPerRecord; ++k)
        records.push_back(k < count ? table.opposite_vertex[first + k] : 0u);
      ++record_count;
    }
  }
  // Triangle records (caps): a, b, c, kind, padding to the patch size.
  const std::vector<std::uint32_t> triangles = compute_pass::read_buffer<std::uint32_t>(
      soup.triangles_.name(), 0, std::size_t{3} * soup.triangle_count(), "TessellationShadowVolume triangles");
  for (std::uint32_t t = 0; t < soup.triangle_count(); ++t) {
    records.insert(records.end(), {triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2], kTriangleKind});
    records.insert(records.end(), kTessellationOppositesPerRecord, 0u);
  }
  const std::uint64_t items = record_count + soup.triangle_count();
  if (items * kRecordWords > static_cast<std::uint64_t>(std::numeric_limits<GLsizei>::max()))
    throw std::invalid_argument("TessellationShadowVolume: more records and triangles than one draw holds");
  record_count_ = static_cast<std::uint32_t>(record_count);
  item_count_ = static_cast<std::uint32_t>(items);
  upload(records_, records);
  glVertexArrayVertexBuffer(patches_.name(), 0, records_.name(), 0, sizeof(std::uint32_t));
  glVertexArrayAttribIFormat(patches_.name(), 0, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(patches_.name(), 0, 0);
  glEnableVertexArrayAttrib(patches_.name(), 0);

  const Shader vertex =
      compile_shader(GL_VERTEX_SHADER, shaders::tessellation_volume_vert, "tessellation_volume.vert.glsl");
  const Shader control =
      compile_shader(GL_TESS_CONTROL_SHADER, shaders::tessellation_volume_tesc, "tessellation_volume.tesc.glsl",
                     sign == SignMode::exact ? kFilterOnlyDefine : sign_mode_defines(sign));
  const Shader evaluation =
      compile_shader(GL_TESS_EVALUATION_SHADER, shaders::tessellation_volume_tese, "tessellation_volume.tese.glsl");
  const Shader geometry =
      compile_shader(GL_GEOMETRY_SHADER, shaders::tessellation_volume_geom, "tessellation_volume.geom.glsl",
                     sign_mode_defines(sign));
  program_ = link_program({&vertex, &control, &evaluation, &geometry}, "tessellation_volume");
  const Shader finish = compile_shader(GL_COMPUTE_SHADER, shaders::tessellation_volume_finish_comp,
                                       "tessellation_volume_finish.comp.glsl", sign_mode_defines(sign));
  finish_ = link_program({&finish}, "tessellation_volume_finish");
  // Deferred: a count, then at most one entry per edge record.
  const std::vector<std::uint32_t> no_deferred(std::size_t{1} + record_count_, 0u);
  glNamedBufferStorage(deferred_.name(), static_cast<GLsizeiptr>(no_deferred.size() * sizeof(std::uint32_t)),
                       no_deferred.data(), GL_DYNAMIC_STORAGE_BIT);

  std::uint64_t limit = kMaxCaptureBytes / kVertexBytes;
  limit = std::min<std::uint64_t>(limit, std::numeric_limits<GLint>::max());
  capacity_ = std::min(soup.worst_case_vertices(), limit / kVerticesPerSideOrCaps * kVerticesPerSideOrCaps);
  const Command initial{};
  glNamedBufferStorage(command_.name(), sizeof initial, &initial, GL_DYNAMIC_STORAGE_BIT);
  glNamedBufferStorage(volume_.name(), static_cast<GLsizeiptr>(std::max<std::uint64_t>(capacity_, 1) * kVertexBytes),
                       nullptr, 0);
  compute_pass::attach_volume(vertex_array_, volume_);
  glNamedFramebufferParameteri(no_attachments_.name(), GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
  glNamedFramebufferParameteri(no_attachments_.name(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
  check_gl_errors("TessellationShadowVolume buffers");
}

void TessellationShadowVolume::build(const Light& light) {
  const GLuint program = program_.name();
  compute_pass::set_light_uniform(program, kLightLocation, light, "TessellationShadowVolume::build");
  compute_pass::set_light_uniform(finish_.name(), kFinishLightLocation, light, "TessellationShadowVolume::build");
  glProgramUniform1ui(finish_.name(), kFinishCapacityLocation, static_cast<GLuint>(capacity_));

  const Command reset{};
  glNamedBufferSubData(command_.name(), 0, sizeof reset, &reset);
  const std::uint32_t no_deferred = 0;
  glNamedBufferSubData(deferred_.name(), 0, sizeof no_deferred, &no_deferred);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVerticesBinding, soup_->vertices_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDeferredBinding, deferred_.name());
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, kCaptureBinding, volume_.name());

  GLint previous_framebuffer = 0;
  GLint previous_patch_vertices = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_framebuffer);
  glGetIntegerv(GL_PATCH_VERTICES, &previous_patch_vertices);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, no_attachments_.name());
  glEnable(GL_RASTERIZER_DISCARD);
  glUseProgram(program);
  glBindVertexArray(patches_.name());
  glPatchParameteri(GL_PATCH_VERTICES, static_cast<GLint>(kRecordWords));
  glBeginQueryIndexed(GL_PRIMITIVES_GENERATED, 0, generated_.name());
  glBeginTransformFeedback(GL_TRIANGLES);
  if (item_count_ != 0) glDrawArrays(GL_PATCHES, 0, static_cast<GLsizei>(item_count_ * kRecordWords));
  glEndTransformFeedback();
  glEndQueryIndexed(GL_PRIMITIVES_GENERATED, 0);
  glPatchParameteri(GL_PATCH_VERTICES, previous_patch_vertices);
  glBindVertexArray(0);
  // Unbind the capture program before the finish program is made current: Mesa (llvmpipe,
  // Debian 12) keeps a compute program made current straight after a graphics program
  // referenced after glUseProgram(0), so the deleted finish program stayed alive (glIsProgram
  // true) once this object was destroyed (tests/gpu/gl_resource_test.cpp).
  glUseProgram(0);
  glDisable(GL_RASTERIZER_DISCARD);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous_framebuffer));
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, kCaptureBinding, 0);

  glGetQueryBufferObjectuiv(generated_.name(), command_.name(), GL_QUERY_RESULT,
                            static_cast<GLintptr>(offsetof(Command, requested)));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFinishCommandBinding, command_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFinishRecordsBinding, records_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFinishVolumeBinding, volume_.name());
  // The control shader's Deferred writes and the captured triangles, before the finish reads
  // and appends to them.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TRANSFORM_FEEDBACK_BARRIER_BIT);
  glUseProgram(finish_.name());
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                  GL_SHADER_STORAGE_BARRIER_BIT);
  glUseProgram(0);
  for (GLuint binding : {kVerticesBinding, kDeferredBinding, kFinishCommandBinding, kFinishRecordsBinding,
                         kFinishVolumeBinding})
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
  check_gl_errors("TessellationShadowVolume::build");
}

std::uint32_t TessellationShadowVolume::read_deferred_records() const {
  return compute_pass::read_buffer<std::uint32_t>(deferred_.name(), 0, 1, "TessellationShadowVolume readback").front();
}

std::uint64_t TessellationShadowVolume::read_requested_vertices() const {
  return compute_pass::read_command(command_.name(), "TessellationShadowVolume readback").requested;
}

std::vector<VolumeTriangle> TessellationShadowVolume::read_triangles() const {
  return compute_pass::read_drawn_triangles<VolumeTriangle>(command_.name(), volume_.name(), "TessellationShadowVolume readback");
}

}  // namespace shadowcert::gpu
