#include "gpu/shadow_map_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gpu/camera_transform.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// Uniform locations fixed by layout(location) in shadow_scene.vert.glsl,
// shadow_map_scene.frag.glsl and shadow_map_depth.vert.glsl.
constexpr GLint kWorldToClipLocation = 0;
constexpr GLint kColourLocation = 1;
constexpr GLint kLightLocation = 2;
constexpr GLint kLambertWeightLocation = 3;
constexpr GLint kLightToClipLocation = 4;
constexpr GLint kDepthBiasLocation = 5;
constexpr GLint kDepthLightToClipLocation = 0;  // shadow_map_depth.vert.glsl
constexpr GLuint kShadowMapUnit = 0;             // layout(binding = 0) of the sampler

// Stencil marks of the first light (the frame's "counts", see the header).
constexpr GLint kShadowedMark = 1;
constexpr GLint kLitMark = 0;

// The light's frustum/box is widened by this factor in each direction (field of view
// tangent, orthographic extent, depth range), so that the bounds' extreme corners, rounded
// through float matrices, still land strictly inside the map and its depth range.
constexpr double kFitMargin = 1.02;
// A point light's half field of view is capped at atan(8) (about 83 degrees): beyond, the
// map's texels stretch so much that it means nothing, and a light inside the box (corners
// behind it) cannot be covered by one frustum at all (that needs a cube map). Receivers
// outside the capped frustum are lit (shadow_map_scene.frag.glsl), a documented limit.
constexpr double kMaxPointLightHalfAngleTangent = 8.0;
// The near plane never comes closer than this fraction of the far one: depth precision of a
// perspective map falls with far / near, and a corner at or behind the light gives no near.
constexpr double kMinNearFraction = 1.0e-3;

glm::dvec3 to_glm(const Vec3& v) { return {v[0], v[1], v[2]}; }

std::array<glm::dvec3, 8> corners(const SceneBounds& b) {
  std::array<glm::dvec3, 8> c;
  for (int k = 0; k < 8; ++k)
    c[k] = {(k & 1) ? b.hi[0] : b.lo[0], (k & 2) ? b.hi[1] : b.lo[1], (k & 4) ? b.hi[2] : b.lo[2]};
  return c;
}

// Any up vector not parallel to `forward`: the map's rotation about its axis is irrelevant.
glm::dvec3 up_for(const glm::dvec3& forward) {
  const glm::dvec3 a = glm::abs(forward);
  return (a.y <= a.x && a.y <= a.z) ? glm::dvec3(0, 1, 0) : (a.x <= a.z ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1));
}

}  // namespace

SceneBounds soup_bounds(const Soup& soup) {
  if (soup.triangles.empty()) throw std::invalid_argument("soup_bounds: no triangle");
  constexpr double inf = std::numeric_limits<double>::infinity();
  SceneBounds b{{inf, inf, inf}, {-inf, -inf, -inf}};
  for (const Triangle& t : soup.triangles)
    for (std::uint32_t id : t)
      for (int k = 0; k < 3; ++k) {
        b.lo[k] = std::min(b.lo[k], soup.vertices[id][k]);
        b.hi[k] = std::max(b.hi[k], soup.vertices[id][k]);
      }
  return b;
}

glm::dmat4 light_to_clip(const Light& light, const SceneBounds& bounds) {
  const glm::dvec3 lo = to_glm(bounds.lo), hi = to_glm(bounds.hi);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  // A flat box (a lone floor) still needs a non-zero extent for the fit below.
  const double radius = std::max(0.5 * glm::length(hi - lo), 1.0e-6);
  const glm::dvec3 l(light.position[0], light.position[1], light.position[2]);
  if (light.directional()) {
    if (glm::length(l) == 0.0) throw std::invalid_argument("light_to_clip: directional light with l = 0");
    const glm::dvec3 towards = glm::normalize(l);
    const glm::dmat4 view = glm::lookAt(centre + 2.0 * radius * towards, centre, up_for(towards));
    glm::dvec3 vmin(std::numeric_limits<double>::infinity()), vmax(-std::numeric_limits<double>::infinity());
    for (const glm::dvec3& c : corners(bounds)) {
      const glm::dvec3 v(view * glm::dvec4(c, 1.0));
      vmin = glm::min(vmin, v);
      vmax = glm::max(vmax, v);
    }
    const glm::dvec3 mid = 0.5 * (vmin + vmax), half = 0.5 * kFitMargin * (vmax - vmin) + radius * 1.0e-6;
    // View space looks down -z: near = -max z, far = -min z.
    return glm::orthoRH_NO(mid.x - half.x, mid.x + half.x, mid.y - half.y, mid.y + half.y, -(mid.z + half.z),
                           -(mid.z - half.z)) *
           view;
  }
  if (glm::length(centre - l) == 0.0) throw std::invalid_argument("light_to_clip: point light at the bounds' centre");
  const glm::dmat4 view = glm::lookAt(l, centre, up_for(centre - l));
  double tangent = 0.0, nearest = std::numeric_limits<double>::infinity(), farthest = 0.0;
  for (const glm::dvec3& c : corners(bounds)) {
    const glm::dvec3 v(view * glm::dvec4(c, 1.0));
    const double depth = -v.z;
    farthest = std::max(farthest, depth);
    if (depth <= 0.0) {
      tangent = kMaxPointLightHalfAngleTangent;
      nearest = 0.0;
      continue;
    }
    nearest = std::min(nearest, depth);
    tangent = std::max({tangent, std::abs(v.x) / depth, std::abs(v.y) / depth});
  }
  tangent = std::min(tangent * kFitMargin, kMaxPointLightHalfAngleTangent);
  const double z_far = farthest * kFitMargin;
  const double z_near = std::max(nearest / kFitMargin, z_far * kMinNearFraction);
  return glm::perspectiveRH_NO(2.0 * std::atan(tangent), 1.0, z_near, z_far) * view;
}

ShadowMapRenderer::ShadowMapRenderer(std::uint32_t size) : size_(size) {
  if (size == 0 || size > kMaxShadowMapSize) {
    throw std::invalid_argument("ShadowMapRenderer: shadow map size " + std::to_string(size) + " is not in [1, " +
                                std::to_string(kMaxShadowMapSize) + "]");
  }
  GLint max_texture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
  if (static_cast<std::int64_t>(size) > max_texture) {
    throw GlError("ShadowMapRenderer: shadow map size " + std::to_string(size) + " exceeds GL_MAX_TEXTURE_SIZE " +
                  std::to_string(max_texture));
  }
  depth_ = Texture::create(GL_TEXTURE_2D);
  const GLuint texture = depth_.name();
  glTextureStorage2D(texture, 1, GL_DEPTH_COMPONENT32F, static_cast<GLsizei>(size), static_cast<GLsizei>(size));
  // Nearest texel, no PCF: a hard, binary shadow comparable pixel by pixel with the lit masks
  // of the volume methods (GL_LINEAR would blend 2x2 comparisons on most drivers).
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(texture, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);  // 1 (lit) where ref <= stored
  framebuffer_ = Framebuffer::create();
  glNamedFramebufferTexture(framebuffer_.name(), GL_DEPTH_ATTACHMENT, texture, 0);
  glNamedFramebufferDrawBuffer(framebuffer_.name(), GL_NONE);
  glNamedFramebufferReadBuffer(framebuffer_.name(), GL_NONE);
  if (glCheckNamedFramebufferStatus(framebuffer_.name(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("ShadowMapRenderer: the " + std::to_string(size) + "^2 depth framebuffer is incomplete");
  }
  check_gl_errors("ShadowMapRenderer: depth texture");

  const Shader depth_vertex =
      compile_shader(GL_VERTEX_SHADER, shaders::shadow_map_depth_vert, "shadow_map_depth.vert.glsl");
  const Shader depth_fragment =
      compile_shader(GL_FRAGMENT_SHADER, shaders::shadow_map_depth_frag, "shadow_map_depth.frag.glsl");
  depth_program_ = link_program({&depth_vertex, &depth_fragment}, "shadow_map_depth");
  const Shader vertex = compile_shader(GL_VERTEX_SHADER, shaders::shadow_scene_vert, "shadow_scene.vert.glsl");
  const Shader fragment =
      compile_shader(GL_FRAGMENT_SHADER, shaders::shadow_map_scene_frag, "shadow_map_scene.frag.glsl");
  scene_program_ = link_program({&vertex, &fragment}, "shadow_map_scene");
}

StencilShadowFrame ShadowMapRenderer::render(const OffscreenTarget& target, const ShadedSoupMesh& receivers,
                                             const SceneBounds& bounds, const Camera& camera,
                                             std::span<const Light> lights, const ShadowMapOptions& options) const {
  const GLuint scene = scene_program_.name();
  const GLuint depth = depth_program_.name();
  const glm::mat4 world_to_clip(projection_matrix(camera) * view_matrix(camera));
  glProgramUniformMatrix4fv(scene, kWorldToClipLocation, 1, GL_FALSE, glm::value_ptr(world_to_clip));
  glProgramUniform1f(scene, kDepthBiasLocation, options.depth_bias);

  target.bind();
  target.clear(options.background);
  glDisable(GL_CULL_FACE);  // soups have no orientation: both sides cast and receive
  glDisable(GL_BLEND);
  glDisable(GL_POLYGON_OFFSET_FILL);

  // 1. Depth pre-pass in ambient colour; every covered pixel is marked shadowed until the
  //    first light's lit pass proves otherwise.
  glUseProgram(scene);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glEnable(GL_STENCIL_TEST);
  glStencilMask(0xFF);
  glStencilFunc(GL_ALWAYS, kShadowedMark, 0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  glProgramUniform1f(scene, kLambertWeightLocation, 0.0f);
  glProgramUniform4f(scene, kColourLocation, options.ambient[0], options.ambient[1], options.ambient[2], 1.0f);
  glBindVertexArray(receivers.vertex_array());
  {
    const ScopedStage stage(options.timer, RenderStage::depth);
    glDrawArrays(GL_TRIANGLES, 0, receivers.single_order_vertex_count());
  }

  for (std::size_t i = 0; i < lights.size(); ++i) {
    const glm::mat4 to_light_clip(light_to_clip(lights[i], bounds));

    // 2. Depth pass from the light. Only the slope term of glPolygonOffset: the constant
    //    bias is applied in the comparison (depth_bias), in depth units the user can read.
    std::optional<ScopedStage> stage(std::in_place, options.timer, RenderStage::shadow_map);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.name());
    glViewport(0, 0, static_cast<GLsizei>(size_), static_cast<GLsizei>(size_));
    glDisable(GL_STENCIL_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClear(GL_DEPTH_BUFFER_BIT);
    glUseProgram(depth);
    glProgramUniformMatrix4fv(depth, kDepthLightToClipLocation, 1, GL_FALSE, glm::value_ptr(to_light_clip));
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(options.slope_scale, 0.0f);
    // The casters only: a part that only receives (ShadedSoupPart::casts) shadows nothing.
    const std::span<const GLint> firsts = receivers.caster_firsts();
    if (!firsts.empty())
      glMultiDrawArrays(GL_TRIANGLES, firsts.data(), receivers.caster_counts().data(),
                        static_cast<GLsizei>(firsts.size()));
    glDisable(GL_POLYGON_OFFSET_FILL);
    stage.reset();

    // 3. Lit pass on the visible surface only; the first light clears the shadowed mark
    //    where its comparison says lit (shadowed fragments are discarded in the shader).
    stage.emplace(options.timer, RenderStage::lit);
    target.bind();
    glUseProgram(scene);
    glBindTextureUnit(kShadowMapUnit, depth_.name());
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, kLitMark, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glStencilMask(i == 0 ? 0xFF : 0x00);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    const std::array<double, 4>& l = lights[i].position;
    glProgramUniform4f(scene, kLightLocation, static_cast<float>(l[0]), static_cast<float>(l[1]),
                       static_cast<float>(l[2]), static_cast<float>(l[3]));
    glProgramUniformMatrix4fv(scene, kLightToClipLocation, 1, GL_FALSE, glm::value_ptr(to_light_clip));
    glProgramUniform1f(scene, kLambertWeightLocation, 1.0f);
    glProgramUniform4f(scene, kColourLocation, options.light_colour[0], options.light_colour[1],
                       options.light_colour[2], 1.0f);
    glDrawArrays(GL_TRIANGLES, 0, receivers.single_order_vertex_count());
    glDisable(GL_BLEND);
    glBindTextureUnit(kShadowMapUnit, 0);
    stage.reset();
  }

  glBindVertexArray(0);
  glUseProgram(0);
  glStencilMask(0xFF);
  glDisable(GL_STENCIL_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  check_gl_errors("ShadowMapRenderer::render");
  StencilShadowFrame frame;
  if (options.read_back) {
    frame.colour = target.read_colour();
    frame.first_stencil = target.read_stencil();
    frame.first_lit_mask = lit_mask(frame.first_stencil);
  }
  return frame;
}

}  // namespace shadowcert::gpu
