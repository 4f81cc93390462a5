#include "gpu/stencil_shadow_renderer.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "core/vector3.h"
#include "gpu/camera_transform.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"
#include "gpu/stencil_passes.h"

namespace shadowcert::gpu {
namespace {

// Attribute locations of shadow_scene.vert.glsl.
constexpr GLuint kPositionAttribute = 0;
constexpr GLuint kNormalAttribute = 1;
constexpr GLuint kAlbedoAttribute = 2;

struct ShadedVertex {
  std::array<float, 4> position;
  std::array<float, 3> normal;
  std::array<float, 3> albedo;
};

static_assert(sizeof(ShadedVertex) == ShadedSoupMesh::kVertexStride &&
              offsetof(ShadedVertex, position) == ShadedSoupMesh::kPositionOffset &&
              offsetof(ShadedVertex, normal) == ShadedSoupMesh::kNormalOffset &&
              offsetof(ShadedVertex, albedo) == ShadedSoupMesh::kAlbedoOffset,
              "ShadedSoupMesh's published layout is ShadedVertex's");

std::array<float, 3> face_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  // In double: only shading reads it (docs/definitions.md#inputs: no decision depends on a normal).
  const Vec3 n = cross(difference(b, a), difference(c, a));
  const double length = std::sqrt(dot(n, n));
  if (!(length > 0.0) || !std::isfinite(length)) return {0.0f, 0.0f, 0.0f};  // unlit in the shader
  return {static_cast<float>(n[0] / length), static_cast<float>(n[1] / length), static_cast<float>(n[2] / length)};
}

}  // namespace

ShadedSoupMesh::ShadedSoupMesh(const Soup& soup) : ShadedSoupMesh(std::span<const ShadedSoupPart>(std::array{ShadedSoupPart{&soup}})) {}

ShadedSoupMesh::ShadedSoupMesh(std::span<const ShadedSoupPart> parts)
    : vertices_(Buffer::create()), vertex_array_(VertexArray::create()) {
  std::vector<ShadedVertex> vertices;
  for (const ShadedSoupPart& part : parts) {
    if (part.soup == nullptr) throw std::invalid_argument("ShadedSoupMesh: a part without a soup");
    const Soup& soup = *part.soup;
    if (part.casts && !soup.triangles.empty()) {
      // GLint/GLsizei overflow is refused below, once every part is in.
      const auto first = static_cast<GLint>(vertices.size());
      const auto count = static_cast<GLsizei>(3 * soup.triangles.size());
      if (!caster_firsts_.empty() && caster_firsts_.back() + caster_counts_.back() == first)
        caster_counts_.back() += count;
      else {
        caster_firsts_.push_back(first);
        caster_counts_.push_back(count);
      }
    }
    const bool vertex_normals = soup.normals.size() == soup.vertices.size() && !soup.normals.empty();
    for (const Triangle& t : soup.triangles) {
      const std::array<float, 3> n = face_normal(soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]);
      for (std::uint32_t id : t) {
        const Vec3& p = soup.vertices[id];
        // Rounded once to float, as the volumes' finite vertices are (cli/ converts them the
        // same way), so a cap and its occluder triangle are the same float triangle.
        vertices.push_back({{static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]), 1.0f},
                            vertex_normals ? soup.normals[id] : n,
                            part.albedo});
      }
    }
  }
  // Every triangle a second time with its last two corners swapped: the order a front cap t'
  // has where s(t) = -1 (docs/definitions.md#counts). The rasteriser interpolates depth from
  // the vertices in their order, and (a, b, c) and (a, c, b) round apart by a unit here and
  // there; the depth pre-pass keeps the nearer of the two, so a cap on its own visible triangle,
  // in either order, is never nearer than the stored depth and always counts as behind it
  // (GL_LESS fails). With one order only, the plane where the two roundings cross shaded a line
  // across the caster (tests/regressions/gl/own_cap_depth_line.json: 16 hard pixels at
  // 256x192). The lit pass draws both copies too; its stencil op lets only the first through.
  // The copy faces the other way, so its normals are negated: the shader turns a normal towards
  // the viewer by gl_FrontFacing, and the copy's flipped facing must flip it back. (Unnegated,
  // wherever the copy won the depth pre-pass the lit pass lit it from behind: 0. A floor seen
  // at a shallow angle showed dark striped wedges in every method's colour frame, never in the
  // masks: tests/gpu/stencil_shadow_renderer_test.cpp, ReversedCopyWinsTheDepthPass_IsLitAlike.)
  const std::size_t forward = vertices.size();
  vertices.reserve(2 * forward);
  for (std::size_t i = 0; i < forward; i += 3) {
    for (const std::size_t k : {i, i + 2, i + 1}) {
      ShadedVertex copy = vertices[k];
      for (float& x : copy.normal) x = -x;
      vertices.push_back(copy);
    }
  }
  if (vertices.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max())) {
    throw std::invalid_argument("ShadedSoupMesh: too many triangles for one draw call");
  }
  const ShadedVertex none{};
  glNamedBufferStorage(vertices_.name(),
                       vertices.empty() ? sizeof none : static_cast<GLsizeiptr>(vertices.size() * sizeof none),
                       vertices.empty() ? &none : vertices.data(), 0);
  vertex_count_ = static_cast<GLsizei>(vertices.size());
  const GLuint vao = vertex_array_.name();
  glVertexArrayVertexBuffer(vao, 0, vertices_.name(), 0, sizeof(ShadedVertex));
  glVertexArrayAttribFormat(vao, kPositionAttribute, 4, GL_FLOAT, GL_FALSE, offsetof(ShadedVertex, position));
  glVertexArrayAttribFormat(vao, kNormalAttribute, 3, GL_FLOAT, GL_FALSE, offsetof(ShadedVertex, normal));
  glVertexArrayAttribFormat(vao, kAlbedoAttribute, 3, GL_FLOAT, GL_FALSE, offsetof(ShadedVertex, albedo));
  for (GLuint attribute : {kPositionAttribute, kNormalAttribute, kAlbedoAttribute}) {
    glVertexArrayAttribBinding(vao, attribute, 0);
    glEnableVertexArrayAttrib(vao, attribute);
  }
  check_gl_errors("ShadedSoupMesh upload");
}

namespace {

// The fragments of the volume that pass the depth test `depth_func` against the receivers'
// depths (the stencil test passes: GL_ALWAYS), by an occlusion query; synchronises.
std::uint64_t samples_passed(GLenum depth_func, const LightVolume& lv, StencilMethod method) {
  const Query query = Query::create(GL_SAMPLES_PASSED);
  glDepthFunc(depth_func);
  glBeginQuery(GL_SAMPLES_PASSED, query.name());
  count_volume(lv, method);
  glEndQuery(GL_SAMPLES_PASSED);
  GLuint64 samples = 0;
  glGetQueryObjectui64v(query.name(), GL_QUERY_RESULT, &samples);  // waits for the draw
  return samples;
}

}  // namespace

StencilShadowRenderer::StencilShadowRenderer() : program_(std::make_unique<ShadowSceneProgram>()) {}

StencilShadowRenderer::~StencilShadowRenderer() = default;
StencilShadowRenderer::StencilShadowRenderer(StencilShadowRenderer&&) noexcept = default;
StencilShadowRenderer& StencilShadowRenderer::operator=(StencilShadowRenderer&&) noexcept = default;

StencilShadowFrame StencilShadowRenderer::render(const OffscreenTarget& target, const ShadedSoupMesh& receivers,
                                                 const Camera& camera, std::span<const LightVolume> lights,
                                                 const StencilShadowOptions& options) const {
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].volume == nullptr && (lights[i].indirect.vertex_array == 0 || lights[i].indirect.command == 0)) {
      throw std::invalid_argument("StencilShadowRenderer::render: light " + std::to_string(i) + " has no volume");
    }
  }
  const ShadowSceneProgram& program = *program_;
  program.set_world_to_clip(glm::mat4(projection_matrix(camera) * view_matrix(camera)));

  target.bind();
  target.clear(options.background);
  glUseProgram(program.name());
  glDisable(GL_CULL_FACE);  // soups have no orientation; volumes need both faces counted
  glDisable(GL_BLEND);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glFrontFace(GL_CCW);      // outward faces seen from outside are front faces

  // 1. Depth pre-pass in ambient colour.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_STENCIL_TEST);
  program.set_ambient(options.ambient);
  glBindVertexArray(receivers.vertex_array());
  {
    const ScopedStage stage(options.timer, RenderStage::depth);
    glDrawArrays(GL_TRIANGLES, 0, receivers.vertex_count());
  }

  StencilShadowFrame frame;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const LightVolume& lv = lights[i];
    // 2. Volume pass: counts only, nothing else written.
    std::optional<ScopedStage> stage(std::in_place, options.timer, RenderStage::stencil);
    const StencilMethod method = lv.stencil.value_or(options.method);
    begin_volume_pass();
    count_volume(lv, method);
    stage.reset();
    if (i == 0 && options.count_fragments) {
      // Nothing written: all fragments (depth test always passes), then those whose count
      // changed in the pass above (z-fail: depth test fails, i.e. GEQUAL; z-pass: LESS).
      glStencilMask(0);
      const bool zfail = method == StencilMethod::zfail;
      frame.first_volume_fragments = samples_passed(GL_ALWAYS, lv, method);
      frame.first_stencil_updates = samples_passed(zfail ? GL_GEQUAL : GL_LESS, lv, method);
      glStencilMask(0xFF);
      glDepthFunc(GL_LESS);
    }
    end_volume_pass();
    if (i == 0 && options.read_back) {
      frame.first_stencil = target.read_stencil();
      frame.first_lit_mask = lit_mask(frame.first_stencil);
    }

    // 3. Lit pass: this light's Lambert term where the count is 0, on the visible surface only.
    stage.emplace(options.timer, RenderStage::lit);
    begin_lit_pass(program, lv.light, options.light_colour);
    glBindVertexArray(receivers.vertex_array());
    glDrawArrays(GL_TRIANGLES, 0, receivers.vertex_count());
    end_lit_pass(program);
    stage.reset();
  }

  glBindVertexArray(0);
  glUseProgram(0);
  glDisable(GL_STENCIL_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  check_gl_errors("StencilShadowRenderer::render");
  if (options.read_back) {
    frame.colour = target.read_colour();
    // The first light's amount of light: all (count 0) or nothing, where a receiver is seen.
    frame.first_light.resize(frame.first_lit_mask.pixels.size());
    for (std::size_t p = 0; p < frame.first_light.size(); ++p)
      frame.first_light[p] = frame.colour.pixels[4 * p + 3] == 0  ? kUncoveredLight
                             : frame.first_lit_mask.pixels[p] != 0 ? 1.0f
                                                                   : 0.0f;
  }
  return frame;
}

}  // namespace shadowcert::gpu
