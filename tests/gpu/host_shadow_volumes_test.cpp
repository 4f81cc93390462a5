// gpu/host_shadow_volumes.h: a host's framebuffer, depth pass and vertex buffer; the frames
// must equal the offscreen renderer's (ShadowMethodRenderer, what `shadowcert render` draws)
// pixel for pixel, other targets must shadow the same pixels, and every call must leave the
// host's GL state as it found it.
#include "gpu/host_shadow_volumes.h"

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gpu/camera_transform.h"
#include "gpu/gl_object.h"
#include "gpu/gl_state_snapshot.h"
#include "gpu/offscreen_target.h"
#include "gpu/shader_compiler.h"
#include "gpu/shadow_method_renderer.h"
#include "io/soup_file.h"
#include "pipeline/drawn_method_scene.h"
#include "pipeline/method_registry.h"
#include "scene/scene_file.h"
#include "support/gl_test_support.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;

// The host's own depth and ambient pass, as docs/engine-integration.md tells a host to write
// it: the position expression of shadow_scene.vert.glsl (invariant, precise), its own program.
constexpr const char* kHostVertex = R"(#version 450 core
layout(location = 0) in vec4 position;
layout(location = 2) in vec3 albedo;
layout(location = 0) uniform mat4 world_to_clip;
invariant gl_Position;
layout(location = 0) out vec3 surface_albedo;
void main() {
  precise vec4 clip = world_to_clip * position;
  gl_Position = clip;
  surface_albedo = albedo;
}
)";
constexpr const char* kHostFragment = R"(#version 450 core
layout(location = 0) in vec3 surface_albedo;
layout(location = 1) uniform vec4 colour;
layout(location = 0) out vec4 fragment;
void main() { fragment = vec4(surface_albedo * colour.rgb, 1.0); }
)";

constexpr std::uint32_t kWidth = 160;  // small: every method on llvmpipe in seconds
constexpr std::uint32_t kHeight = 120;
// A finite far plane and a float depth buffer move pixels on silhouette and shadow edges only
// (depth rounding), MSAA blends the pixels on edges: at most this share of the render's
// shadowed pixels may differ (pixels inside a shadow or a lit area, away from its edge, must
// not differ at all under MSAA beyond it), far below what a missing or leaking shadow changes.
constexpr double kEdgeShareOfShadow = 0.15;

Scene bundled_scene(const std::string& name) {
  Scene scene = load_scene(std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "scenes" / name,
                           [](const std::filesystem::path& f) { return read_soup(f); });
  scene.camera.width = kWidth;
  scene.camera.height = kHeight;
  return scene;
}

// A host framebuffer: RGBA8 colour and a depth-stencil renderbuffer of `depth_format`, with
// `samples` samples (0: single-sampled).
struct HostTarget {
  Renderbuffer colour = Renderbuffer::create();
  Renderbuffer depth = Renderbuffer::create();
  Framebuffer framebuffer = Framebuffer::create();
  HostTarget(GLenum depth_format, GLsizei samples) {
    glNamedRenderbufferStorageMultisample(colour.name(), samples, GL_RGBA8, kWidth, kHeight);
    glNamedRenderbufferStorageMultisample(depth.name(), samples, depth_format, kWidth, kHeight);
    glNamedFramebufferRenderbuffer(framebuffer.name(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour.name());
    glNamedFramebufferRenderbuffer(framebuffer.name(), GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth.name());
    EXPECT_EQ(glCheckNamedFramebufferStatus(framebuffer.name(), GL_FRAMEBUFFER), GLenum{GL_FRAMEBUFFER_COMPLETE});
  }
  // The colour, resolved into `into` (single-sampled RGBA8) and read back.
  RgbaImage read_colour(const OffscreenTarget& into) const {
    glBlitNamedFramebuffer(framebuffer.name(), into.framebuffer(), 0, 0, kWidth, kHeight, 0, 0, kWidth, kHeight,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    return into.read_colour();
  }
};

// The host: its receivers in its own buffer (a ShadedSoupMesh: every triangle in both orders,
// as the offscreen renderer draws them), its own depth-and-ambient program, its camera.
class Host {
 public:
  explicit Host(const DrawnMethodScene& d) : receivers_(d.parts) {
    const Shader vertex = compile_shader(GL_VERTEX_SHADER, kHostVertex, "host.vert");
    const Shader fragment = compile_shader(GL_FRAGMENT_SHADER, kHostFragment, "host.frag");
    program_ = link_program({&vertex, &fragment}, "host");
  }
  // Clears, then the depth pass in ambient colour, as StencilShadowRenderer's first pass.
  void draw_depth(GLuint framebuffer, const glm::mat4& world_to_clip) const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, kWidth, kHeight);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glStencilMask(0xFF);
    const std::array<float, 4> background{0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, background.data());
    glClearNamedFramebufferfi(framebuffer, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glUseProgram(program_.name());
    glProgramUniformMatrix4fv(program_.name(), 0, 1, GL_FALSE, glm::value_ptr(world_to_clip));
    const std::array<float, 3> ambient = StencilShadowOptions{}.ambient;
    glProgramUniform4f(program_.name(), 1, ambient[0], ambient[1], ambient[2], 1.0f);
    glBindVertexArray(receivers_.vertex_array());
    glDrawArrays(GL_TRIANGLES, 0, receivers_.vertex_count());
    glBindVertexArray(0);
    glUseProgram(0);
  }
  [[nodiscard]] HostReceivers receivers() const { return host_receivers(receivers_); }

 private:
  ShadedSoupMesh receivers_;
  Program program_;
};

// The casters' input vertices as a host keeps them: doubles, 32 bytes apart (x, y, z, a pad
// of junk), behind a 64-byte header, so that the gather must honour offset, stride and type.
Buffer host_caster_buffer(const Soup& casters) {
  std::vector<double> words(8, -7.0);
  for (const Vec3& p : casters.vertices) words.insert(words.end(), {p[0], p[1], p[2], 1e30});
  Buffer buffer = Buffer::create();
  glNamedBufferStorage(buffer.name(), static_cast<GLsizeiptr>(words.size() * sizeof(double)), words.data(), 0);
  return buffer;
}

glm::mat4 world_to_clip(const Camera& camera) { return glm::mat4(projection_matrix(camera) * view_matrix(camera)); }

// The light colour the offscreen renderer gives each of n lights.
std::array<float, 3> light_share(std::size_t n) {
  std::array<float, 3> c = StencilShadowOptions{}.light_colour;
  for (float& x : c) x /= static_cast<float>(n);
  return c;
}

std::vector<ShadowMethod> robust_volume_methods() {
  std::vector<ShadowMethod> out;
  for (const ShadowMethodTraits& t : kShadowMethodTable)
    if (draws_volume(t.method) && robust(t.method)) out.push_back(t.method);
  return out;
}

// The host's whole frame with the full entry: depth pass, then per light draw_lit.
RgbaImage host_frame(const DrawnMethodScene& d, HostShadowVolumes& shadows, const Host& host, const HostTarget& target,
                     const glm::mat4& clip, const OffscreenTarget& resolve) {
  host.draw_depth(target.framebuffer.name(), clip);
  shadows.build();
  for (std::size_t k = 0; k < shadows.light_count(); ++k)
    shadows.draw_lit(clip, k, host.receivers(), light_share(d.scene.lights.size()));
  return target.read_colour(resolve);
}

// Covered pixels (alpha 255) whose first-light count is not 0.
std::uint64_t shadowed_pixels(const StencilShadowFrame& frame) {
  std::uint64_t n = 0;
  for (std::size_t p = 0; p < frame.first_stencil.pixels.size(); ++p)
    n += frame.first_stencil.pixels[p] != 0 && frame.colour.pixels[4 * p + 3] != 0;
  return n;
}

std::uint64_t differing_pixels(const RgbaImage& a, const RgbaImage& b) {
  std::uint64_t n = 0;
  for (std::size_t p = 0; p + 3 < a.pixels.size(); p += 4)
    n += a.pixels[p] != b.pixels[p] || a.pixels[p + 1] != b.pixels[p + 1] || a.pixels[p + 2] != b.pixels[p + 2] ||
         a.pixels[p + 3] != b.pixels[p + 3];
  return n;
}

// Per pixel: covered (alpha not 0) and exactly the ambient-only frame's colour (no light added).
std::vector<bool> shadow_mask(const RgbaImage& frame, const RgbaImage& ambient) {
  std::vector<bool> mask(frame.pixels.size() / 4);
  for (std::size_t p = 0; p < mask.size(); ++p)
    mask[p] = frame.pixels[4 * p + 3] != 0 && frame.pixels[4 * p] == ambient.pixels[4 * p] &&
              frame.pixels[4 * p + 1] == ambient.pixels[4 * p + 1] && frame.pixels[4 * p + 2] == ambient.pixels[4 * p + 2];
  return mask;
}

// Whether pixel p and its 8 neighbours are all shadowed or all not: MSAA blends the others.
bool interior(const std::vector<bool>& mask, std::size_t p) {
  const auto x = static_cast<std::int64_t>(p % kWidth), y = static_cast<std::int64_t>(p / kWidth);
  for (std::int64_t dy = -1; dy <= 1; ++dy)
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      const std::int64_t nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= kWidth || ny >= kHeight) return false;
      if (mask[static_cast<std::size_t>(ny * kWidth + nx)] != mask[p]) return false;
    }
  return true;
}

class HostShadowVolumesTest : public GlTest {};

// The host's frame (full entry, every light) and first-light counts (stencil-only entry) of
// `method` on `name`, against ShadowMethodRenderer's.
void expect_host_equals_render(const std::string& name, ShadowMethod method) {
  SCOPED_TRACE(name + ", " + std::string(shadow_method_name(method)));
  const auto d = prepare_drawn_method_scene(bundled_scene(name), method, StencilChoice::zfail);
  const Camera& camera = d->scene.camera;
  const OffscreenTarget offscreen(kWidth, kHeight);
  ShadowMethodRenderer renderer(method, d->method_scene(), d->renderer_options());
  const StencilShadowFrame expected = renderer.render(offscreen, camera);

  HostShadowVolumes shadows(method, d->method_scene(), d->host_options());
  const Buffer host_vertices = host_caster_buffer(d->casters);
  if (builds_volume_on_gpu(method))
    shadows.read_vertices_from({host_vertices.name(), 64, 32, GL_DOUBLE, 3}, d->inputs.canonical.canonical_id);
  const Host host(*d);
  const HostTarget target(GL_DEPTH24_STENCIL8, 0);
  const OffscreenTarget resolve(kWidth, kHeight);
  const glm::mat4 clip = world_to_clip(camera);
  const RgbaImage colour = host_frame(*d, shadows, host, target, clip, resolve);
  EXPECT_EQ(differing_pixels(colour, expected.colour), 0u);

  // The stencil-only entry: the first light's counts, as render's.
  host.draw_depth(resolve.framebuffer(), clip);
  shadows.draw_stencil(clip, 0);
  EXPECT_EQ(resolve.read_stencil().pixels, expected.first_stencil.pixels);
  EXPECT_GT(shadowed_pixels(expected), 0u);  // the scene has shadows to compare
}

TEST_F(HostShadowVolumesTest, EveryRobustMethod_HostFrameEqualsRender_PixelForPixel) {
  for (const std::string name : {"default.json", "sphere_over_floor.json", "closed_casters.json"})
    for (const ShadowMethod method : robust_volume_methods()) expect_host_equals_render(name, method);
}

// The smooth-silhouette methods (given volumes from pipeline/, smooth-gpu's built on the GPU
// as well): the host layer draws them as render does.
TEST_F(HostShadowVolumesTest, SilhouetteMethods_HostFrameEqualsRender_PixelForPixel) {
  for (const std::string name : {"smooth_sphere.json", "default.json"})
    for (const ShadowMethod method : kSilhouetteMethods) expect_host_equals_render(name, method);
}

// A host's own target kinds: a finite far plane (with depth clamp), 4x MSAA, and a float
// depth buffer with 8 stencil bits: the shadow falls where render puts it.
TEST_F(HostShadowVolumesTest, FiniteFarPlane_Msaa_Depth32fStencil8_ShadowWhereRenderPutsIt) {
  const Scene scene = bundled_scene("default.json");
  for (const ShadowMethod method : {ShadowMethod::cpu, ShadowMethod::cs, ShadowMethod::pertri}) {
    SCOPED_TRACE(std::string(shadow_method_name(method)));
    const auto d = prepare_drawn_method_scene(scene, method, StencilChoice::zfail);
    const Camera& camera = d->scene.camera;
    const OffscreenTarget offscreen(kWidth, kHeight);
    ShadowMethodRenderer renderer(method, d->method_scene(), d->renderer_options());
    const StencilShadowFrame expected = renderer.render(offscreen, camera);
    const std::uint64_t shadowed = shadowed_pixels(expected);
    ASSERT_GT(shadowed, 0u);

    HostShadowVolumes shadows(method, d->method_scene(), d->host_options());
    const Host host(*d);
    const OffscreenTarget resolve(kWidth, kHeight);
    // A finite far plane well beyond the scene: the infinite projection's rows with a far term.
    glm::dmat4 projection = projection_matrix(camera);
    const double n = camera.near_plane, f = 1e4;
    projection[2][2] = -(f + n) / (f - n);
    projection[3][2] = -2.0 * f * n / (f - n);
    const glm::mat4 finite(projection * view_matrix(camera));
    struct Case {
      const char* what;
      GLenum depth;
      GLsizei samples;
      glm::mat4 clip;
    };
    // Shadowed: covered, and the colour of the same target's ambient-only frame (MSAA blends
    // only where a pixel's samples differ, so inside a shadow the resolved colour is ambient).
    const HostTarget plain(GL_DEPTH24_STENCIL8, 0);
    host.draw_depth(plain.framebuffer.name(), world_to_clip(camera));
    const std::vector<bool> expected_mask = shadow_mask(expected.colour, plain.read_colour(resolve));
    std::uint64_t expected_shadow = 0;
    for (const bool b : expected_mask) expected_shadow += b;
    ASSERT_GT(expected_shadow, 0u);
    for (const Case& c : {Case{"finite far plane", GL_DEPTH24_STENCIL8, 0, finite},
                          Case{"4x MSAA", GL_DEPTH24_STENCIL8, 4, world_to_clip(camera)},
                          Case{"depth32F-stencil8", GL_DEPTH32F_STENCIL8, 0, world_to_clip(camera)},
                          Case{"4x MSAA, depth32F-stencil8, finite far plane", GL_DEPTH32F_STENCIL8, 4, finite}}) {
      SCOPED_TRACE(c.what);
      const HostTarget target(c.depth, c.samples);
      host.draw_depth(target.framebuffer.name(), c.clip);
      const RgbaImage ambient = target.read_colour(resolve);
      const RgbaImage colour = host_frame(*d, shadows, host, target, c.clip, resolve);
      if (c.samples == 0) {
        EXPECT_LE(static_cast<double>(differing_pixels(colour, expected.colour)),
                  kEdgeShareOfShadow * static_cast<double>(shadowed));
      }
      const std::vector<bool> mask = shadow_mask(colour, ambient);
      std::uint64_t differ = 0;
      for (std::size_t p = 0; p < mask.size(); ++p) differ += interior(expected_mask, p) && mask[p] != expected_mask[p];
      EXPECT_LE(static_cast<double>(differ), kEdgeShareOfShadow * static_cast<double>(expected_shadow));
      // (A frame without the volumes has no shadowed pixel: `differ` would be expected_shadow.)
    }
  }
}

// Host state set away from every default the passes touch.
void set_host_state(GLuint program, GLuint vao, GLuint buffer, GLuint feedback) {
  glUseProgram(program);
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, buffer);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, buffer, 256, 512);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, buffer);
  // A range on the default transform feedback object too (gs and ts capture through it),
  // then the host's own object bound with a buffer of its own.
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
  glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer, 1024, 256);
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, feedback);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer);
  glPatchParameteri(GL_PATCH_VERTICES, 4);
  glEnable(GL_CULL_FACE);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glEnable(GL_BLEND);
  glBlendEquation(GL_MIN);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_DST_ALPHA);
  glDepthFunc(GL_GEQUAL);
  glDepthMask(GL_FALSE);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  glFrontFace(GL_CW);
  glStencilFuncSeparate(GL_FRONT, GL_NOTEQUAL, 3, 0x0F);
  glStencilFuncSeparate(GL_BACK, GL_GREATER, 5, 0xF0);
  glStencilOpSeparate(GL_FRONT, GL_ZERO, GL_REPLACE, GL_INVERT);
  glStencilOpSeparate(GL_BACK, GL_INCR, GL_DECR, GL_REPLACE);
  glStencilMask(0x7F);
  glClearStencil(9);
  glEnable(GL_STENCIL_TEST);
  glDisable(GL_DEPTH_TEST);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
}

TEST_F(HostShadowVolumesTest, EveryCall_RestoresTheHostsState) {
  const Scene scene = bundled_scene("default.json");
  for (const ShadowMethod method : {ShadowMethod::cpu, ShadowMethod::cs, ShadowMethod::gs, ShadowMethod::ts,
                                    ShadowMethod::pertri, ShadowMethod::smooth_gpu}) {
    SCOPED_TRACE(std::string(shadow_method_name(method)));
    const auto d = prepare_drawn_method_scene(scene, method, StencilChoice::zfail);
    const Host host(*d);
    const OffscreenTarget target(kWidth, kHeight);
    host.draw_depth(target.framebuffer(), world_to_clip(d->scene.camera));
    const Buffer host_vertices = host_caster_buffer(d->casters);
    const Buffer scratch = Buffer::create();
    glNamedBufferStorage(scratch.name(), 4096, nullptr, 0);
    const VertexArray host_vao = VertexArray::create();
    const Program host_program = [] {
      const Shader v = compile_shader(GL_VERTEX_SHADER, kHostVertex, "host.vert");
      const Shader f = compile_shader(GL_FRAGMENT_SHADER, kHostFragment, "host.frag");
      return link_program({&v, &f}, "host");
    }();
    GLuint feedback = 0;
    glCreateTransformFeedbacks(1, &feedback);
    set_host_state(host_program.name(), host_vao.name(), scratch.name(), feedback);
    const GlStateSnapshot before = GlStateSnapshot::capture();

    HostShadowVolumes shadows(method, d->method_scene(), d->host_options());
    EXPECT_EQ(before.differences(GlStateSnapshot::capture()), std::vector<std::string>{}) << "constructor";
    if (builds_volume_on_gpu(method))
      shadows.read_vertices_from({host_vertices.name(), 64, 32, GL_DOUBLE, 3}, d->inputs.canonical.canonical_id);
    shadows.build();
    EXPECT_EQ(before.differences(GlStateSnapshot::capture()), std::vector<std::string>{}) << "build";
    const glm::mat4 clip = world_to_clip(d->scene.camera);
    shadows.draw_stencil(clip, 0);
    EXPECT_EQ(before.differences(GlStateSnapshot::capture()), std::vector<std::string>{}) << "draw_stencil";
    shadows.draw_lit(clip, 0, host.receivers(), light_share(1));
    EXPECT_EQ(before.differences(GlStateSnapshot::capture()), std::vector<std::string>{}) << "draw_lit";

    // The same, asked of GL directly for the values a stencil pass is most likely to leave.
    GLint value = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &value);
    EXPECT_EQ(static_cast<GLuint>(value), host_program.name());
    glGetIntegerv(GL_STENCIL_FUNC, &value);
    EXPECT_EQ(value, GL_NOTEQUAL);
    glGetIntegerv(GL_STENCIL_BACK_PASS_DEPTH_FAIL, &value);
    EXPECT_EQ(value, GL_DECR);
    glGetIntegerv(GL_STENCIL_WRITEMASK, &value);
    EXPECT_EQ(value, 0x7F);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &value);
    EXPECT_EQ(value, GL_MIN);
    glGetIntegerv(GL_DEPTH_FUNC, &value);
    EXPECT_EQ(value, GL_GEQUAL);
    EXPECT_EQ(glIsEnabled(GL_DEPTH_CLAMP), GL_FALSE);
    EXPECT_EQ(glIsEnabled(GL_CULL_FACE), GL_TRUE);
    GLint64 range = 0;
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 2, &range);
    EXPECT_EQ(range, 256);
    glGetIntegerv(GL_TRANSFORM_FEEDBACK_BINDING, &value);
    EXPECT_EQ(static_cast<GLuint>(value), feedback);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
    glGetIntegeri_v(GL_TRANSFORM_FEEDBACK_BUFFER_BINDING, 0, &value);
    EXPECT_EQ(static_cast<GLuint>(value), scratch.name()) << "the default transform feedback object's binding 0";
    glGetInteger64i_v(GL_TRANSFORM_FEEDBACK_BUFFER_START, 0, &range);
    EXPECT_EQ(range, 1024);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    glDeleteTransformFeedbacks(1, &feedback);
    glUseProgram(0);
    glBindVertexArray(0);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
}

// A moving light: set_light then build counts what a set built for that light counts.
TEST_F(HostShadowVolumesTest, SetLight_CountsAsASetBuiltForThatLight) {
  Scene scene = bundled_scene("default.json");
  const auto d = prepare_drawn_method_scene(scene, ShadowMethod::cs, StencilChoice::zfail);
  HostShadowVolumes moving(ShadowMethod::cs, d->method_scene(), d->host_options());
  Light moved = d->scene.lights.front();
  moved.position[0] += 1.5;
  moved.position[2] -= 0.5;
  moving.set_light(0, moved);
  std::vector<Light> lights = d->scene.lights;
  lights.front() = moved;
  gpu::ShadowMethodScene fresh_scene = d->method_scene();
  fresh_scene.lights = lights;
  HostShadowVolumes fresh(ShadowMethod::cs, fresh_scene, d->host_options());
  const Host host(*d);
  const OffscreenTarget target(kWidth, kHeight);
  const glm::mat4 clip = world_to_clip(d->scene.camera);
  GrayImage counts[2];
  HostShadowVolumes* sets[2] = {&moving, &fresh};
  for (int i = 0; i < 2; ++i) {
    host.draw_depth(target.framebuffer(), clip);
    sets[i]->build();
    sets[i]->draw_stencil(clip, 0);
    counts[i] = target.read_stencil();
  }
  EXPECT_EQ(counts[0].pixels, counts[1].pixels);
  host.draw_depth(target.framebuffer(), clip);
  HostShadowVolumes unmoved(ShadowMethod::cs, d->method_scene(), d->host_options());
  unmoved.build();
  unmoved.draw_stencil(clip, 0);
  EXPECT_NE(target.read_stencil().pixels, counts[0].pixels);  // the light did move the shadow
}

TEST_F(HostShadowVolumesTest, Misuse_ThrowsNamingTheFunction) {
  const Scene scene = bundled_scene("default.json");
  const auto cpu = prepare_drawn_method_scene(scene, ShadowMethod::cpu, StencilChoice::zfail);
  HostShadowVolumes shadows(ShadowMethod::cpu, cpu->method_scene(), cpu->host_options());
  const Buffer buffer = host_caster_buffer(cpu->casters);
  try {
    shadows.read_vertices_from({buffer.name(), 0, 0, GL_FLOAT, 3}, cpu->inputs.canonical.canonical_id);
    FAIL() << "cpu read the host's vertices";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("HostShadowVolumes::read_vertices_from"), std::string::npos) << e.what();
  }
  EXPECT_THROW(shadows.draw_stencil(glm::mat4(1.0f), 5), std::out_of_range);
  EXPECT_THROW(shadows.set_light(0, cpu->scene.lights.front()), std::invalid_argument);  // cpu's chain is the light's
  const auto cs = prepare_drawn_method_scene(scene, ShadowMethod::cs, StencilChoice::zfail);
  HostShadowVolumes built(ShadowMethod::cs, cs->method_scene(), cs->host_options());
  EXPECT_THROW(built.read_vertices_from({buffer.name(), 4, 0, GL_DOUBLE, 3}, cs->inputs.canonical.canonical_id),
               std::invalid_argument);  // a double at a 4-byte offset
  EXPECT_THROW(built.read_vertices_from({buffer.name(), 0, 0, GL_INT, 3}, cs->inputs.canonical.canonical_id),
               std::invalid_argument);
  const std::vector<std::uint32_t> short_map(1, 0);
  EXPECT_THROW(built.read_vertices_from({buffer.name(), 0, 0, GL_DOUBLE, 3}, short_map), std::invalid_argument);
  EXPECT_THROW(HostShadowVolumes(ShadowMethod::shadowmap, cs->method_scene()), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert::gpu
