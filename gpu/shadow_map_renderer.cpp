#include "gpu/shadow_map_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gpu/camera_transform.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"
#include "gpu/shadow_scene_uniforms.h"

namespace shadowcert::gpu {
namespace {

// Uniform locations fixed by layout(location) in shadow_map_scene.frag.glsl and
// shadow_map_depth.vert.glsl, after the lit scene pass's (gpu/shadow_scene_uniforms.h).
constexpr GLint kLightToClipLocation = 4;
constexpr GLint kDepthBiasLocation = 5;
constexpr GLint kFilterModeLocation = 6;  // shadow_filter.glsl
constexpr GLint kPcfKernelLocation = 7;
constexpr GLint kLightViewLocation = 8;
constexpr GLint kLightFrustumLocation = 9;
constexpr GLint kOrthographicLocation = 10;
constexpr GLint kLightRadiusLocation = 11;
constexpr GLint kLightImagePassLocation = 12;  // shadow_map_scene.frag.glsl
constexpr GLint kCubeMapLocation = 13;          // shadow_map_scene.frag.glsl
constexpr GLint kCubeFacesLocation = 14;
constexpr GLint kCubeLightToClipLocation = 16;  // 6 matrices
constexpr GLint kCubeLightViewLocation = 22;    // 6 matrices
constexpr GLint kCubeFrustumLocation = 28;      // 6 vec4
constexpr GLint kDepthLightToClipLocation = 0;  // shadow_map_depth.vert.glsl
constexpr GLuint kShadowMapUnit = 0;             // layout(binding = 0) of the sampler
constexpr GLuint kDepthValuesUnit = 1;           // binding 1: the map without comparison (pcss)
constexpr GLuint kSmoothieMapUnit = 2;           // binding 2: the smoothie map
constexpr GLuint kCubeShadowMapUnit = 3;         // bindings 3 to 5: the same three of a cube map
constexpr GLuint kCubeDepthValuesUnit = 4;
constexpr GLuint kCubeSmoothieMapUnit = 5;

// Stencil marks of the first light (the frame's "counts", see the header).
constexpr GLint kShadowedMark = 1;
constexpr GLint kLitMark = 0;

// The light's frustum/box is widened by this factor in each direction (field of view
// tangent, orthographic extent, depth range), so that the bounds' extreme corners, rounded
// through float matrices, still land strictly inside the map and its depth range.
constexpr double kFitMargin = 1.02;
// A point light's half field of view is capped at atan(8) (about 83 degrees): beyond, the
// map's texels stretch so much that it means nothing, and a light inside the box (corners
// behind it) cannot be covered by one frustum at all: such a light gets a cube map.
constexpr double kMaxPointLightHalfAngleTangent = 8.0;
// The near plane never comes closer than this fraction of the far one: depth precision of a
// perspective map falls with far / near, and a corner at or behind the light gives no near.
constexpr double kMinNearFraction = 1.0e-3;
// A cube face's near plane when the nearest receiver is unknown (ShadowMapOptions::
// nearest_receivers empty): this fraction of its far plane. The constant depth bias (1e-4 of
// window depth) is then about 64e-4 of the far plane at the far end (peter-panning), and
// casters nearer than the plane still cast (GL_DEPTH_CLAMP), at depth 0.
constexpr double kCubeNearFraction = 1.0 / 64.0;
// A cube face's near plane never lies past this fraction of its far one (a face no receiver
// is near: the plane only has to stay in front of the far one).
constexpr double kMaxCubeNearFraction = 0.5;

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

double default_light_radius(const SceneBounds& bounds) {
  const glm::dvec3 diagonal = to_glm(bounds.hi) - to_glm(bounds.lo);
  return kDefaultLightRadiusFraction * glm::length(diagonal);
}

double light_angle_tangent(double degrees) {
  if (!std::isfinite(degrees) || !(degrees > 0.0) || !(degrees < kMaxLightAngleDegrees))
    throw std::invalid_argument("light_angle_tangent: a light's angular radius must be in (0, 90) degrees, got " +
                                std::to_string(degrees));
  return std::tan(degrees * (std::numbers::pi / 180.0));
}

namespace {

void require_finite(const Light& light) {
  for (double x : light.position)
    if (!std::isfinite(x)) throw std::invalid_argument("light_views: the light is not finite");
}

struct SingleFrustum {
  LightFrustum frustum;
  bool capped = false;  // a point light whose half angle reached kMaxPointLightHalfAngleTangent
};

// The one frustum or box of a light (the top of the header). A point light at the box's centre
// is reported capped (no direction to aim at), its frustum left unset.
SingleFrustum single_frustum(const Light& light, const SceneBounds& bounds) {
  const glm::dvec3 lo = to_glm(bounds.lo), hi = to_glm(bounds.hi);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  // A flat box (a lone floor) still needs a non-zero extent for the fit below.
  const double radius = std::max(0.5 * glm::length(hi - lo), 1.0e-6);
  const glm::dvec3 l(light.position[0], light.position[1], light.position[2]);
  LightFrustum frustum;
  if (light.directional()) {
    if (glm::length(l) == 0.0) throw std::invalid_argument("light_views: directional light with l = 0");
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
    frustum.view = view;
    frustum.projection = glm::orthoRH_NO(mid.x - half.x, mid.x + half.x, mid.y - half.y, mid.y + half.y,
                                         -(mid.z + half.z), -(mid.z - half.z));
    frustum.near = -(mid.z + half.z);
    frustum.far = -(mid.z - half.z);
    frustum.half_extent = {half.x, half.y};
    frustum.orthographic = true;
    return {frustum, false};
  }
  if (glm::length(centre - l) == 0.0) return {frustum, true};
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
  const bool capped = tangent * kFitMargin >= kMaxPointLightHalfAngleTangent;
  tangent = std::min(tangent * kFitMargin, kMaxPointLightHalfAngleTangent);
  const double z_far = farthest * kFitMargin;
  const double z_near = std::max(nearest / kFitMargin, z_far * kMinNearFraction);
  frustum.view = view;
  frustum.projection = glm::perspectiveRH_NO(2.0 * std::atan(tangent), 1.0, z_near, z_far);
  frustum.near = z_near;
  frustum.far = z_far;
  frustum.tangent = tangent;
  return {frustum, capped};
}

// The cube's faces in shaders/cube_face.glsl's order: the axis each looks along, and an up
// vector across it (the face's rotation about its axis is irrelevant).
constexpr std::array<std::array<double, 6>, 6> kCubeFaces{{{1, 0, 0, 0, 1, 0},
                                                           {-1, 0, 0, 0, 1, 0},
                                                           {0, 1, 0, 0, 0, 1},
                                                           {0, -1, 0, 0, 0, 1},
                                                           {0, 0, 1, 0, 1, 0},
                                                           {0, 0, -1, 0, 1, 0}}};

std::vector<LightFrustum> cube_faces(const Light& light, const SceneBounds& bounds, double nearest_receiver) {
  const glm::dvec3 l(light.position[0], light.position[1], light.position[2]);
  std::vector<LightFrustum> faces;
  for (int face = 0; face < 6; ++face) {
    const glm::dvec3 axis(kCubeFaces[face][0], kCubeFaces[face][1], kCubeFaces[face][2]);
    const glm::dvec3 up(kCubeFaces[face][3], kCubeFaces[face][4], kCubeFaces[face][5]);
    double deepest = 0.0;  // the box's farthest point along the axis, ahead of the light
    for (const glm::dvec3& c : corners(bounds)) deepest = std::max(deepest, glm::dot(c - l, axis));
    if (!(deepest > 0.0)) continue;  // the whole box lies behind the face's plane: nothing to draw
    const double z_far = deepest * kFitMargin;
    const double wanted = std::isfinite(nearest_receiver) && nearest_receiver > 0.0
                              ? nearest_receiver / (std::sqrt(3.0) * kFitMargin)
                              : z_far * kCubeNearFraction;
    const double z_near = std::min(std::max(wanted, z_far * kMinNearFraction), z_far * kMaxCubeNearFraction);
    LightFrustum f;
    f.view = glm::lookAt(l, l + axis, up);
    f.projection = glm::perspectiveRH_NO(2.0 * std::atan(kFitMargin), 1.0, z_near, z_far);
    f.near = z_near;
    f.far = z_far;
    f.tangent = kFitMargin;
    f.cube_face = face;
    faces.push_back(f);
  }
  return faces;
}

// The distance from p to the segment [a, b] (a point when a == b).
double segment_distance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double length2 = glm::dot(ab, ab);
  const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

// The distance from p to the closed triangle abc (degenerate ones too): to its plane where p
// projects inside it, else to the nearest edge.
double triangle_distance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double n2 = glm::dot(n, n);
  if (n2 > 0.0 && glm::dot(glm::cross(b - a, p - a), n) >= 0.0 && glm::dot(glm::cross(c - b, p - b), n) >= 0.0 &&
      glm::dot(glm::cross(a - c, p - c), n) >= 0.0)
    return std::abs(glm::dot(p - a, n)) / std::sqrt(n2);
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

}  // namespace

bool needs_cube_map(const Light& light, const SceneBounds& bounds) {
  return !light.directional() && single_frustum(light, bounds).capped;
}

std::vector<LightFrustum> light_views(const Light& light, const SceneBounds& bounds, double nearest_receiver) {
  require_finite(light);
  const SingleFrustum single = single_frustum(light, bounds);
  if (light.directional() || !single.capped) return {single.frustum};
  return cube_faces(light, bounds, nearest_receiver);
}

double nearest_receiver_distance(std::span<const ShadedSoupPart> parts, const Light& light) {
  if (light.directional()) throw std::invalid_argument("nearest_receiver_distance: a directional light");
  const glm::dvec3 l(light.position[0], light.position[1], light.position[2]);
  const auto drawn = [](const Vec3& v) {  // as GL receives the vertex
    return glm::dvec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
  };
  double nearest = std::numeric_limits<double>::infinity();
  for (const ShadedSoupPart& part : parts) {
    if (part.soup == nullptr) continue;
    for (const Triangle& t : part.soup->triangles)
      nearest = std::min(nearest, triangle_distance(l, drawn(part.soup->vertices[t[0]]),
                                                    drawn(part.soup->vertices[t[1]]), drawn(part.soup->vertices[t[2]])));
  }
  return nearest;
}

ShadowMapRenderer::ShadowMapRenderer(std::uint32_t size, ShadowFilter filter) : size_(size), filter_(filter) {
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
  // pcss reads the stored depths themselves through this sampler (the texture's own state
  // compares): nearest, clamped, no comparison.
  depth_values_ = Sampler::create();
  glSamplerParameteri(depth_values_.name(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glSamplerParameteri(depth_values_.name(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glSamplerParameteri(depth_values_.name(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(depth_values_.name(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(depth_values_.name(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
  check_gl_errors("ShadowMapRenderer: depth texture");
  if (filter == ShadowFilter::smoothie) smoothie_map_.emplace(size);

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

const ShadowMapRenderer::CubeMap& ShadowMapRenderer::cube_map() const {
  if (cube_map_) return *cube_map_;
  const auto side = static_cast<GLsizei>(size_);
  CubeMap cube{Texture::create(GL_TEXTURE_2D_ARRAY), {}, {}};
  const GLuint depth = cube.depth.name();
  glTextureStorage3D(depth, 1, GL_DEPTH_COMPONENT32F, side, side, 6);
  // As the one map's texture: nearest texel, clamped, the hardware comparison (1 lit).
  glTextureParameteri(depth, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(depth, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(depth, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(depth, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTextureParameteri(depth, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(depth, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  for (int face = 0; face < 6; ++face) {
    Framebuffer& layer = cube.layers[static_cast<std::size_t>(face)];
    layer = Framebuffer::create();
    glNamedFramebufferTextureLayer(layer.name(), GL_DEPTH_ATTACHMENT, depth, 0, face);
    glNamedFramebufferDrawBuffer(layer.name(), GL_NONE);
    glNamedFramebufferReadBuffer(layer.name(), GL_NONE);
    if (glCheckNamedFramebufferStatus(layer.name(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("ShadowMapRenderer: the cube map's 6 x " + std::to_string(size_) + "^2 depth layers are incomplete");
  }
  if (smoothie_map_) {
    cube.smoothie = Texture::create(GL_TEXTURE_2D_ARRAY);
    const GLuint smoothie = cube.smoothie.name();
    glTextureStorage3D(smoothie, 1, GL_RG32F, side, side, 6);
    glTextureParameteri(smoothie, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(smoothie, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(smoothie, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(smoothie, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  // GL_OUT_OF_MEMORY for a map the driver cannot hold six times (6 GiB of depth at 16384).
  const std::string where = "ShadowMapRenderer: the cube map's 6 x " + std::to_string(size_) + "^2 layers";
  check_gl_errors(where.c_str());
  cube_map_.emplace(std::move(cube));
  return *cube_map_;
}

namespace {

int filter_mode(ShadowFilter filter) {
  switch (filter) {
    case ShadowFilter::hard: return 0;  // the kFilter* constants of shadow_filter.glsl
    case ShadowFilter::pcf: return 1;
    case ShadowFilter::pcss: return 2;
    case ShadowFilter::smoothie: return 3;
  }
  return 0;
}

void validate(ShadowFilter filter, std::span<const Light> lights, const ShadowMapOptions& options) {
  const std::string where = "ShadowMapRenderer::render: ";
  if (filter == ShadowFilter::pcf &&
      (options.pcf_kernel < 1 || options.pcf_kernel > kMaxPcfKernel || options.pcf_kernel % 2 == 0))
    throw std::invalid_argument(where + "the pcf kernel must be odd and in [1, " + std::to_string(kMaxPcfKernel) +
                                "], got " + std::to_string(options.pcf_kernel));
  if (filter == ShadowFilter::pcss && (!std::isfinite(options.light_radius) || !(options.light_radius > 0.0)))
    throw std::invalid_argument(where + "the pcss light radius must be finite and > 0, got " +
                                std::to_string(options.light_radius));
  if (filter == ShadowFilter::pcss &&
      (!std::isfinite(options.light_angle_degrees) || !(options.light_angle_degrees > 0.0) ||
       !(options.light_angle_degrees < kMaxLightAngleDegrees)))
    throw std::invalid_argument(where + "the pcss light angle must be in (0, 90) degrees, got " +
                                std::to_string(options.light_angle_degrees));
  if (!options.nearest_receivers.empty() && options.nearest_receivers.size() != lights.size())
    throw std::invalid_argument(where + "nearest_receivers needs one distance per light (" +
                                std::to_string(options.nearest_receivers.size()) + " for " +
                                std::to_string(lights.size()) + " lights)");
  if (filter == ShadowFilter::smoothie) {
    if (options.smoothies.size() != lights.size())
      throw std::invalid_argument(where + "smoothie needs one smoothie mesh per light (" +
                                  std::to_string(options.smoothies.size()) + " for " + std::to_string(lights.size()) +
                                  " lights)");
    for (const SmoothieQuads* quads : options.smoothies)
      if (quads == nullptr) throw std::invalid_argument(where + "a null smoothie mesh");
  }
}

}  // namespace

StencilShadowFrame ShadowMapRenderer::render(const OffscreenTarget& target, const ShadedSoupMesh& receivers,
                                             const SceneBounds& bounds, const Camera& camera,
                                             std::span<const Light> lights, const ShadowMapOptions& options) const {
  validate(filter_, lights, options);
  const GLuint scene = scene_program_.name();
  const GLuint depth = depth_program_.name();
  const glm::mat4 world_to_clip(projection_matrix(camera) * view_matrix(camera));
  glProgramUniformMatrix4fv(scene, shadow_scene_uniforms::kWorldToClip, 1, GL_FALSE, glm::value_ptr(world_to_clip));
  glProgramUniform1f(scene, kDepthBiasLocation, options.depth_bias);
  glProgramUniform1i(scene, kFilterModeLocation, filter_mode(filter_));
  glProgramUniform1i(scene, kPcfKernelLocation, static_cast<GLint>(options.pcf_kernel));
  glProgramUniform1i(scene, kLightImagePassLocation, 0);
  glProgramUniform1i(scene, kCubeMapLocation, 0);
  // pcss's light size as the filter reads it: world units for a point light, a tangent for a
  // directional one (shadow_filter.glsl).
  const double angle_tangent = filter_ == ShadowFilter::pcss ? light_angle_tangent(options.light_angle_degrees) : 0.0;

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
  glProgramUniform1f(scene, shadow_scene_uniforms::kLambertWeight, 0.0f);
  glProgramUniform4f(scene, shadow_scene_uniforms::kColour, options.ambient[0], options.ambient[1], options.ambient[2], 1.0f);
  glBindVertexArray(receivers.vertex_array());
  {
    const ScopedStage stage(options.timer, RenderStage::depth);
    glDrawArrays(GL_TRIANGLES, 0, receivers.single_order_vertex_count());
  }

  std::vector<float> first_light;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const double nearest = options.nearest_receivers.empty() ? 0.0 : options.nearest_receivers[i];
    const std::vector<LightFrustum> views = light_views(lights[i], bounds, nearest);
    const bool cube = views.front().cube_face >= 0;
    const CubeMap* cube_map = cube ? &this->cube_map() : nullptr;

    // 2. Depth pass from the light, per view (a cube map's faces into their layers). Only the
    //    slope term of glPolygonOffset: the constant bias is applied in the comparison
    //    (depth_bias), in depth units the user can read. A cube face clamps depth instead of
    //    clipping at its near plane: a caster nearer than it still hides what lies behind it.
    //    2b. smoothie: the light's smoothies into the smoothie map (nearest alpha and depth),
    //    a cube face's then copied into its layer.
    for (const LightFrustum& view : views) {
      const glm::mat4 to_light_clip(view.projection * view.view);
      std::optional<ScopedStage> stage(std::in_place, options.timer, RenderStage::shadow_map);
      glBindFramebuffer(GL_FRAMEBUFFER, cube ? cube_map->layers[static_cast<std::size_t>(view.cube_face)].name()
                                             : framebuffer_.name());
      glViewport(0, 0, static_cast<GLsizei>(size_), static_cast<GLsizei>(size_));
      glDisable(GL_STENCIL_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_TRUE);
      glClear(GL_DEPTH_BUFFER_BIT);
      glUseProgram(depth);
      glProgramUniformMatrix4fv(depth, kDepthLightToClipLocation, 1, GL_FALSE, glm::value_ptr(to_light_clip));
      glBindVertexArray(receivers.vertex_array());  // the previous face's smoothie pass bound its own
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(options.slope_scale, 0.0f);
      if (cube) glEnable(GL_DEPTH_CLAMP);
      // The casters only: a part that only receives (ShadedSoupPart::casts) shadows nothing.
      const std::span<const GLint> firsts = receivers.caster_firsts();
      if (!firsts.empty())
        glMultiDrawArrays(GL_TRIANGLES, firsts.data(), receivers.caster_counts().data(),
                          static_cast<GLsizei>(firsts.size()));
      glDisable(GL_DEPTH_CLAMP);
      glDisable(GL_POLYGON_OFFSET_FILL);
      stage.reset();
      if (smoothie_map_) {
        stage.emplace(options.timer, RenderStage::smoothie_map);
        smoothie_map_->render(*options.smoothies[i], to_light_clip, glm::mat4(view.view));
        if (cube) {
          const auto side = static_cast<GLsizei>(size_);
          glCopyImageSubData(smoothie_map_->texture(), GL_TEXTURE_2D, 0, 0, 0, 0, cube_map->smoothie.name(),
                             GL_TEXTURE_2D_ARRAY, 0, 0, 0, view.cube_face, side, side, 1);
        }
        stage.reset();
      }
    }

    // 3. Lit pass on the visible surface only; the first light clears the shadowed mark where
    //    its comparison says lit (shadowed fragments are discarded in the shader).
    std::optional<ScopedStage> stage(std::in_place, options.timer, RenderStage::lit);
    target.bind();
    glUseProgram(scene);
    if (cube) {
      glBindTextureUnit(kCubeShadowMapUnit, cube_map->depth.name());
      if (filter_ == ShadowFilter::pcss) {
        glBindTextureUnit(kCubeDepthValuesUnit, cube_map->depth.name());
        glBindSampler(kCubeDepthValuesUnit, depth_values_.name());
      }
      if (smoothie_map_) glBindTextureUnit(kCubeSmoothieMapUnit, cube_map->smoothie.name());
      std::array<glm::mat4, 6> to_clip{}, light_view{};
      std::array<glm::vec4, 6> frustum{};
      GLint faces = 0;
      for (const LightFrustum& view : views) {
        const auto f = static_cast<std::size_t>(view.cube_face);
        to_clip[f] = glm::mat4(view.projection * view.view);
        light_view[f] = glm::mat4(view.view);
        frustum[f] = glm::vec4(static_cast<float>(view.near), static_cast<float>(view.far),
                               static_cast<float>(view.tangent), static_cast<float>(view.tangent));
        faces |= 1 << view.cube_face;
      }
      glProgramUniformMatrix4fv(scene, kCubeLightToClipLocation, 6, GL_FALSE, glm::value_ptr(to_clip[0]));
      glProgramUniformMatrix4fv(scene, kCubeLightViewLocation, 6, GL_FALSE, glm::value_ptr(light_view[0]));
      glProgramUniform4fv(scene, kCubeFrustumLocation, 6, glm::value_ptr(frustum[0]));
      glProgramUniform1i(scene, kCubeFacesLocation, faces);
      glProgramUniform1i(scene, kOrthographicLocation, 0);
    } else {
      const LightFrustum& frustum = views.front();
      const glm::mat4 to_light_clip(frustum.projection * frustum.view);
      const glm::mat4 light_view(frustum.view);
      glBindTextureUnit(kShadowMapUnit, depth_.name());
      if (filter_ == ShadowFilter::pcss) {
        glBindTextureUnit(kDepthValuesUnit, depth_.name());
        glBindSampler(kDepthValuesUnit, depth_values_.name());
      }
      if (smoothie_map_) glBindTextureUnit(kSmoothieMapUnit, smoothie_map_->texture());
      glProgramUniformMatrix4fv(scene, kLightToClipLocation, 1, GL_FALSE, glm::value_ptr(to_light_clip));
      glProgramUniformMatrix4fv(scene, kLightViewLocation, 1, GL_FALSE, glm::value_ptr(light_view));
      glProgramUniform4f(scene, kLightFrustumLocation, static_cast<float>(frustum.near),
                         static_cast<float>(frustum.far),
                         static_cast<float>(frustum.orthographic ? frustum.half_extent[0] : frustum.tangent),
                         static_cast<float>(frustum.orthographic ? frustum.half_extent[1] : frustum.tangent));
      glProgramUniform1i(scene, kOrthographicLocation, frustum.orthographic ? 1 : 0);
    }
    glProgramUniform1i(scene, kCubeMapLocation, cube ? 1 : 0);
    glProgramUniform1f(scene, kLightRadiusLocation,
                       static_cast<float>(lights[i].directional() ? angle_tangent : options.light_radius));
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, kLitMark, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glStencilMask(i == 0 ? 0xFF : 0x00);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    const std::array<double, 4>& l = lights[i].position;
    glProgramUniform4f(scene, shadow_scene_uniforms::kLight, static_cast<float>(l[0]), static_cast<float>(l[1]),
                       static_cast<float>(l[2]), static_cast<float>(l[3]));
    glProgramUniform1f(scene, shadow_scene_uniforms::kLambertWeight, 1.0f);
    glProgramUniform4f(scene, shadow_scene_uniforms::kColour, options.light_colour[0], options.light_colour[1],
                       options.light_colour[2], 1.0f);
    glBindVertexArray(receivers.vertex_array());  // the smoothie map bound its own
    glDrawArrays(GL_TRIANGLES, 0, receivers.single_order_vertex_count());
    glDisable(GL_BLEND);
    stage.reset();

    // 4. The first light's amount of light per pixel (readback frames only): the receivers once
    //    more into the light image, nearest surface per pixel, the filter's amount as colour.
    if (i == 0 && options.read_back) {
      if (!light_image_ || light_image_->width() != target.width() || light_image_->height() != target.height())
        light_image_.emplace(target.width(), target.height());
      light_image_->bind();
      light_image_->clear();
      glDisable(GL_STENCIL_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_TRUE);
      glProgramUniform1i(scene, kLightImagePassLocation, 1);
      glDrawArrays(GL_TRIANGLES, 0, receivers.single_order_vertex_count());
      glProgramUniform1i(scene, kLightImagePassLocation, 0);
      first_light = light_image_->read_light();
    }
    glProgramUniform1i(scene, kCubeMapLocation, 0);
    for (GLuint unit : {kShadowMapUnit, kDepthValuesUnit, kSmoothieMapUnit, kCubeShadowMapUnit, kCubeDepthValuesUnit,
                        kCubeSmoothieMapUnit}) {
      glBindTextureUnit(unit, 0);
      glBindSampler(unit, 0);
    }
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
    frame.first_light = std::move(first_light);
    if (filter_ != ShadowFilter::hard) {
      // A soft amount: shadowed where below the middle of the penumbra (kLitThreshold); the
      // stencil marked every pixel with any light at all.
      for (std::size_t p = 0; p < frame.first_stencil.pixels.size(); ++p) {
        const bool covered = frame.colour.pixels[4 * p + 3] != 0;
        frame.first_stencil.pixels[p] =
            static_cast<std::uint8_t>(covered && frame.first_light[p] < kLitThreshold ? kShadowedMark : kLitMark);
      }
    }
    frame.first_lit_mask = lit_mask(frame.first_stencil);
  }
  return frame;
}

}  // namespace shadowcert::gpu
