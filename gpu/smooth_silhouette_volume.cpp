#include "gpu/smooth_silhouette_volume.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/detail/compute_pass.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// Binding points and uniform locations fixed by layout() in smooth_silhouette_volume.comp.glsl.
constexpr GLuint kVerticesBinding = 0;
constexpr GLuint kWedgeNormalsBinding = 1;
constexpr GLuint kTrianglesBinding = 2;
constexpr GLuint kCommandBinding = 3;
constexpr GLuint kVolumeBinding = 4;
constexpr GLint kLightLocation = 0;
constexpr GLint kPassKindLocation = 1;
constexpr GLint kItemCountLocation = 2;
constexpr GLint kCapacityLocation = 3;
constexpr GLuint kTrianglePass = 0, kFinishPass = 1;

// The first sizing: a triangle away from the silhouette emits its cap and back cap (6
// vertices); one cut by it about twice that. The strips and sides of a silhouette of a few
// hundred segments fit in the headroom; build() grows the buffer for more.
constexpr std::uint64_t kVerticesPerTriangle = 12;
constexpr std::uint64_t kHeadroomVertices = 3 * 65536;
// Growth past a request: a quarter more, so that a light moving along its path does not
// reallocate every frame.
constexpr std::uint64_t kGrowthDivisor = 4;

using compute_pass::Command;
using compute_pass::kVertexBytes;
using compute_pass::upload;

bool finite(const Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

std::uint32_t float_bits(float x) {
  std::uint32_t bits = 0;
  static_assert(sizeof bits == sizeof x);
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

void require(bool condition, const std::string& what) {
  if (!condition) throw std::invalid_argument("SmoothCasterBuffers: " + what);
}

}  // namespace

SmoothCasterBuffers::SmoothCasterBuffers(const SmoothCasterArrays& a)
    : vertices_(Buffer::create()), wedge_normals_(Buffer::create()), triangles_(Buffer::create()) {
  const std::size_t n = a.triangles.size();
  require(a.wedges.size() == n && a.across.size() == n && a.crease_bits.size() == n && a.epsilon.size() == n &&
              a.cap_offset.size() == n,
          "the per-triangle arrays differ in size");
  require(n < kNoTriangleAcross && a.vertices.size() < kNoTriangleAcross && a.wedge_normals.size() < kNoTriangleAcross,
          "more than 32-bit counts");
  for (const Vec3& v : a.vertices) require(finite(v), "a vertex is not finite");
  for (const Vec3& v : a.wedge_normals) require(finite(v), "a normal is not finite");
  // Per triangle three uvec4 (the shader's Triangles): (v0, v1, v2, crease bits),
  // (w0, w1, w2, cap offset bits), (across0, across1, across2, epsilon bits).
  std::vector<std::array<std::uint32_t, 4>> records;
  records.reserve(3 * n);
  for (std::size_t t = 0; t < n; ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      require(a.triangles[t][k] < a.vertices.size(), "triangle " + std::to_string(t) + ": vertex index out of range");
      require(a.wedges[t][k] < a.wedge_normals.size(), "triangle " + std::to_string(t) + ": wedge index out of range");
      require(a.across[t][k] == kNoTriangleAcross || a.across[t][k] < n,
              "triangle " + std::to_string(t) + ": triangle across out of range");
    }
    require(std::isfinite(a.epsilon[t]) && a.epsilon[t] > 0.0f, "epsilon must be finite and > 0");
    require(std::isfinite(a.cap_offset[t]) && a.cap_offset[t] >= 0.0f, "the cap offset must be finite and >= 0");
    records.push_back({a.triangles[t][0], a.triangles[t][1], a.triangles[t][2], a.crease_bits[t] & 7u});
    records.push_back({a.wedges[t][0], a.wedges[t][1], a.wedges[t][2], float_bits(a.cap_offset[t])});
    records.push_back({a.across[t][0], a.across[t][1], a.across[t][2], float_bits(a.epsilon[t])});
  }
  // Rounded once from double, as every GL method's vertices (core/float_rounding.h).
  std::vector<std::array<float, 4>> vertices, normals;
  vertices.reserve(a.vertices.size());
  for (const Vec3& x : a.vertices)
    vertices.push_back({static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2]), 1.0f});
  normals.reserve(a.wedge_normals.size());
  for (const Vec3& x : a.wedge_normals)
    normals.push_back({static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2]), 0.0f});
  upload(vertices_, vertices);
  upload(wedge_normals_, normals);
  upload(triangles_, records);
  triangle_count_ = static_cast<std::uint32_t>(n);
  check_gl_errors("SmoothCasterBuffers upload");
}

SmoothSilhouetteVolume::SmoothSilhouetteVolume(const SmoothCasterBuffers& casters)
    : casters_(&casters), command_(Buffer::create()), vertex_array_(VertexArray::create()) {
  const std::string defines =
      "#define SHADOWCERT_MAX_SUBDIVISION_DEPTH " + std::to_string(kSmoothGpuMaxSubdivisionDepth) + "\n";
  const Shader shader = compile_shader(GL_COMPUTE_SHADER, shaders::smooth_silhouette_volume_comp,
                                       "smooth_silhouette_volume.comp.glsl", defines);
  program_ = link_program({&shader}, "smooth_silhouette_volume");

  // No more than one storage block addresses nor a draw count holds; whole triangles.
  GLint64 max_block_bytes = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
  std::uint64_t limit = static_cast<std::uint64_t>(std::max<GLint64>(max_block_bytes, 0)) / kVertexBytes;
  limit = std::min<std::uint64_t>(limit, std::numeric_limits<GLint>::max());
  limit_ = limit / 3 * 3;
  const Command initial{};
  glNamedBufferStorage(command_.name(), sizeof initial, &initial, GL_DYNAMIC_STORAGE_BIT);
  allocate(kVerticesPerTriangle * casters.triangle_count() + kHeadroomVertices);
  check_gl_errors("SmoothSilhouetteVolume buffers");
}

void SmoothSilhouetteVolume::allocate(std::uint64_t vertices) {
  capacity_ = std::min(vertices / 3 * 3, limit_);
  volume_ = Buffer::create();  // immutable storage: a new buffer for a new size
  glNamedBufferStorage(volume_.name(), static_cast<GLsizeiptr>(std::max<std::uint64_t>(capacity_, 1) * kVertexBytes),
                       nullptr, 0);
  compute_pass::attach_volume(vertex_array_, volume_);
}

void SmoothSilhouetteVolume::dispatch_build(const Light& light) {
  const GLuint program = program_.name();
  compute_pass::set_light_uniform(program, kLightLocation, light, "SmoothSilhouetteVolume::build");
  glProgramUniform1ui(program, kCapacityLocation, static_cast<GLuint>(capacity_));

  const Command reset{};
  glNamedBufferSubData(command_.name(), 0, sizeof reset, &reset);
  const SmoothCasterBuffers& c = *casters_;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVerticesBinding, c.vertices_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kWedgeNormalsBinding, c.wedge_normals_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTrianglesBinding, c.triangles_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCommandBinding, command_.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVolumeBinding, volume_.name());
  glUseProgram(program);
  glProgramUniform1ui(program, kPassKindLocation, kTrianglePass);
  glProgramUniform1ui(program, kItemCountLocation, c.triangle_count());
  compute_pass::dispatch(c.triangle_count());
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the finish pass reads the final counter
  glProgramUniform1ui(program, kPassKindLocation, kFinishPass);
  glProgramUniform1ui(program, kItemCountLocation, 1);
  glDispatchCompute(1, 1, 1);
  // The indirect draw reads the command, the vertex pass the volume, readbacks both.
  glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);
  for (GLuint binding = kVerticesBinding; binding <= kVolumeBinding; ++binding)
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
  check_gl_errors("SmoothSilhouetteVolume::build");
}

void SmoothSilhouetteVolume::build(const Light& light) {
  dispatch_build(light);
  const std::uint64_t requested = read_requested_vertices();
  if (requested <= capacity_ || capacity_ == limit_) return;
  allocate(requested + requested / kGrowthDivisor);
  dispatch_build(light);
}

std::uint64_t SmoothSilhouetteVolume::read_requested_vertices() const {
  return compute_pass::read_command(command_.name(), "SmoothSilhouetteVolume readback").requested;
}

std::vector<VolumeTriangle> SmoothSilhouetteVolume::read_triangles() const {
  return compute_pass::read_drawn_triangles<VolumeTriangle>(command_.name(), volume_.name(), "SmoothSilhouetteVolume readback");
}

}  // namespace shadowcert::gpu
