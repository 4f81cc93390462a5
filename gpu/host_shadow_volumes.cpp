#include "gpu/host_shadow_volumes.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/detail/compute_pass.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/gl_state_snapshot.h"
#include "gpu/shader_compiler.h"
#include "gpu/shadow_method_renderer.h"
#include "gpu/shadow_volume_set.h"
#include "gpu/stencil_passes.h"

namespace shadowcert::gpu {
namespace {

// Binding points and uniform locations fixed by host_vertex_gather.comp.glsl.
constexpr GLuint kHostWordsBinding = 0;
constexpr GLuint kHostIndexBinding = 1;
constexpr GLuint kVerticesBinding = 2;
constexpr GLint kFirstWordLocation = 0;
constexpr GLint kStrideWordsLocation = 1;
constexpr GLint kDoublesLocation = 2;
constexpr GLint kVertexCountLocation = 3;

// Attribute locations of shadow_scene.vert.glsl.
constexpr GLuint kPositionAttribute = 0;
constexpr GLuint kNormalAttribute = 1;
constexpr GLuint kAlbedoAttribute = 2;

constexpr GLsizeiptr kWordBytes = 4;

GLsizei component_bytes(GLenum type) { return type == GL_DOUBLE ? 8 : 4; }

void require_layout(const HostVertexBuffer& v, const char* function, const char* what, bool three_only) {
  const std::string where = std::string(function) + ": " + what;
  if (v.buffer == 0 || glIsBuffer(v.buffer) == GL_FALSE)
    throw std::invalid_argument(where + " names no buffer of the current context (" + std::to_string(v.buffer) + ")");
  if (v.type != GL_FLOAT && v.type != GL_DOUBLE)
    throw std::invalid_argument(where + ": the component type must be GL_FLOAT or GL_DOUBLE");
  if (v.components != 3 && (three_only || v.components != 4))
    throw std::invalid_argument(where + ": " + std::to_string(v.components) + " components (3" +
                                (three_only ? "" : " or 4") + " expected)");
  const GLsizei bytes = component_bytes(v.type);
  if (v.offset < 0 || v.stride < 0 || v.offset % bytes != 0 || v.stride % bytes != 0)
    throw std::invalid_argument(where + ": offset and stride must be non-negative multiples of " +
                                std::to_string(bytes) + " bytes");
}

void attach(GLuint vao, GLuint attribute, const HostVertexBuffer& v) {
  const GLsizei stride = v.stride != 0 ? v.stride : v.components * component_bytes(v.type);
  glVertexArrayVertexBuffer(vao, attribute, v.buffer, v.offset, stride);
  glVertexArrayAttribFormat(vao, attribute, v.components, v.type, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, attribute, attribute);  // one binding point per attribute
  glEnableVertexArrayAttrib(vao, attribute);
}

}  // namespace

HostReceivers host_receivers(const ShadedSoupMesh& mesh) {
  HostReceivers r;
  const GLuint b = mesh.vertex_buffer();
  const GLsizei stride = ShadedSoupMesh::kVertexStride;
  r.position = {b, ShadedSoupMesh::kPositionOffset, stride, GL_FLOAT, 4};
  r.normal = {b, ShadedSoupMesh::kNormalOffset, stride, GL_FLOAT, 3};
  r.albedo = {b, ShadedSoupMesh::kAlbedoOffset, stride, GL_FLOAT, 3};
  r.count = mesh.vertex_count();
  return r;
}

HostShadowVolumes::HostShadowVolumes(ShadowMethod method, const ShadowMethodScene& casters,
                                     const HostShadowOptions& options)
    : method_(method) {
  const ScopedGlState keep;
  volumes_ = std::make_unique<ShadowVolumeSet>(method, casters, options.sign, options.light_stencil,
                                               "HostShadowVolumes");
  program_ = std::make_unique<ShadowSceneProgram>();
  receivers_ = VertexArray::create();
  if (builds_volume_on_gpu(method)) {
    const Shader shader =
        compile_shader(GL_COMPUTE_SHADER, shaders::host_vertex_gather_comp, "host_vertex_gather.comp.glsl");
    gather_ = link_program({&shader}, "host_vertex_gather");
  }
  stencil_ = options.stencil;  // each light's unless light_stencil chose one
  check_gl_errors("HostShadowVolumes");
}

HostShadowVolumes::~HostShadowVolumes() = default;
HostShadowVolumes::HostShadowVolumes(HostShadowVolumes&&) noexcept = default;
HostShadowVolumes& HostShadowVolumes::operator=(HostShadowVolumes&&) noexcept = default;

std::size_t HostShadowVolumes::light_count() const { return volumes_->lights().size(); }

void HostShadowVolumes::read_vertices_from(const HostVertexBuffer& vertices,
                                           std::span<const std::uint32_t> canonical_id) {
  constexpr const char* kFunction = "HostShadowVolumes::read_vertices_from";
  if (!builds_volume_on_gpu(method_))
    throw std::invalid_argument(std::string(kFunction) + ": " + std::string(shadow_method_name(method_)) +
                                " builds no volume on the GPU (only cs, gs, ts and pertri read the host's vertices)");
  require_layout(vertices, kFunction, "the vertex buffer", true);
  // Canonical vertex c reads the first host vertex welded into it (welded vertices are equal).
  const std::uint32_t n = volumes_->canonical_vertex_count();
  constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> host_index(n, kUnset);
  for (std::size_t i = 0; i < canonical_id.size(); ++i) {
    if (canonical_id[i] >= n)
      throw std::invalid_argument(std::string(kFunction) + ": canonical_id[" + std::to_string(i) + "] = " +
                                  std::to_string(canonical_id[i]) + " is not below the " + std::to_string(n) +
                                  " canonical vertices");
    if (host_index[canonical_id[i]] == kUnset) host_index[canonical_id[i]] = static_cast<std::uint32_t>(i);
  }
  if (std::find(host_index.begin(), host_index.end(), kUnset) != host_index.end())
    throw std::invalid_argument(std::string(kFunction) + ": canonical_id misses a canonical vertex");
  const ScopedGlState keep;
  host_index_ = Buffer::create();
  compute_pass::upload(host_index_, host_index);
  host_vertices_ = vertices;
  check_gl_errors(kFunction);
}

void HostShadowVolumes::set_light(std::size_t k, const Light& light) { volumes_->set_light(k, light); }

void HostShadowVolumes::build() {
  const ScopedGlState keep;
  if (host_vertices_ && volumes_->canonical_vertex_count() != 0) {
    const HostVertexBuffer& v = *host_vertices_;
    // A storage range must start at a multiple of GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT:
    // bind from the aligned start below the offset and skip the rest in words.
    GLint alignment = 1;
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
    GLint64 buffer_bytes = 0;
    glGetNamedBufferParameteri64v(v.buffer, GL_BUFFER_SIZE, &buffer_bytes);
    GLint64 max_block_bytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
    const GLintptr start = v.offset - v.offset % std::max(alignment, 1);
    const GLsizeiptr bytes = std::min<GLint64>(buffer_bytes - start, max_block_bytes) / kWordBytes * kWordBytes;
    if (bytes <= 0) throw std::invalid_argument("HostShadowVolumes::build: the vertex buffer ends before its offset");
    const GLsizei stride = v.stride != 0 ? v.stride : 3 * component_bytes(v.type);
    const GLuint program = gather_.name();
    glProgramUniform1ui(program, kFirstWordLocation, static_cast<GLuint>((v.offset - start) / kWordBytes));
    glProgramUniform1ui(program, kStrideWordsLocation, static_cast<GLuint>(stride / kWordBytes));
    glProgramUniform1ui(program, kDoublesLocation, v.type == GL_DOUBLE ? 1u : 0u);
    glProgramUniform1ui(program, kVertexCountLocation, volumes_->canonical_vertex_count());
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, kHostWordsBinding, v.buffer, start, bytes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kHostIndexBinding, host_index_.name());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVerticesBinding, volumes_->canonical_vertex_buffer());
    glUseProgram(program);
    compute_pass::dispatch(volumes_->canonical_vertex_count());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the builds read the gathered vertices
  }
  // The capture passes of gs and ts use the default transform feedback object's bindings. The
  // outer snapshot holds those of the host's bound object only: a second one, taken with the
  // default object bound, gives the default object's ranges back too (it is the host's as well).
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
  {
    const ScopedGlState keep_default_feedback;
    volumes_->build();
  }
  check_gl_errors("HostShadowVolumes::build");
}

void HostShadowVolumes::count(const glm::mat4& world_to_clip, std::size_t light) const {
  const std::span<const LightVolume> lights = volumes_->light_volumes();
  if (light >= lights.size())
    throw std::out_of_range("HostShadowVolumes: light " + std::to_string(light) + " of " +
                            std::to_string(lights.size()));
  program_->set_world_to_clip(world_to_clip);
  glUseProgram(program_->name());
  glDisable(GL_CULL_FACE);  // both faces count
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDisable(GL_RASTERIZER_DISCARD);
  glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  glDisable(GL_SAMPLE_COVERAGE);
  glDisable(GL_COLOR_LOGIC_OP);
  glDisable(GL_BLEND);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glFrontFace(GL_CCW);  // outward faces seen from outside are front faces
  glEnable(GL_DEPTH_TEST);
  const LightVolume& lv = lights[light];
  begin_volume_pass();
  count_volume(lv, lv.stencil.value_or(stencil_));
  end_volume_pass();
}

void HostShadowVolumes::draw_stencil(const glm::mat4& world_to_clip, std::size_t light) const {
  const ScopedGlState keep;
  count(world_to_clip, light);
  check_gl_errors("HostShadowVolumes::draw_stencil");
}

void HostShadowVolumes::draw_lit(const glm::mat4& world_to_clip, std::size_t light, const HostReceivers& receivers,
                                 const std::array<float, 3>& light_colour) const {
  constexpr const char* kFunction = "HostShadowVolumes::draw_lit";
  require_layout(receivers.position, kFunction, "the receivers' positions", false);
  require_layout(receivers.normal, kFunction, "the receivers' normals", true);
  require_layout(receivers.albedo, kFunction, "the receivers' albedo", true);
  if (receivers.count < 0 || receivers.first < 0)
    throw std::invalid_argument(std::string(kFunction) + ": negative first or count");
  const ScopedGlState keep;
  count(world_to_clip, light);
  const GLuint vao = receivers_.name();
  attach(vao, kPositionAttribute, receivers.position);
  attach(vao, kNormalAttribute, receivers.normal);
  attach(vao, kAlbedoAttribute, receivers.albedo);
  glVertexArrayElementBuffer(vao, receivers.index_buffer);
  begin_lit_pass(*program_, volumes_->lights()[light], light_colour);
  glBindVertexArray(vao);
  if (receivers.index_buffer != 0)
    glDrawElements(GL_TRIANGLES, receivers.count, receivers.index_type,
                   reinterpret_cast<const void*>(receivers.index_offset));
  else
    glDrawArrays(GL_TRIANGLES, receivers.first, receivers.count);
  end_lit_pass(*program_);
  check_gl_errors(kFunction);
}

void HostShadowVolumes::check_capacity() const { volumes_->check_capacity(); }

}  // namespace shadowcert::gpu
