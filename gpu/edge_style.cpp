#include "gpu/edge_style.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gpu/camera_transform.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// Uniform locations fixed by layout(location) in shadow_scene.vert.glsl and
// edge_style_shade.frag.glsl ...
constexpr GLint kWorldToClipLocation = 0;
constexpr GLint kShadeStyleLocation = 1;
constexpr GLint kShadeLightLocation = 2;
constexpr GLint kShadeHasAmountLocation = 3;
constexpr GLint kShadeEyeLocation = 4;
// ... and in edge_style_composite.frag.glsl.
constexpr GLint kCompositeStyleLocation = 0;
constexpr GLint kCompositeThresholdsLocation = 1;

GLint style_index(EdgeStyle style) {
  switch (style) {
    case EdgeStyle::edges: return 0;
    case EdgeStyle::gooch: return 1;
    case EdgeStyle::toon: return 2;
  }
  throw std::invalid_argument("EdgeStyleRenderer: unknown style");
}

using Clock = std::chrono::steady_clock;

}  // namespace

std::string_view edge_style_name(EdgeStyle style) {
  switch (style) {
    case EdgeStyle::edges: return "edges";
    case EdgeStyle::gooch: return "gooch";
    case EdgeStyle::toon: return "toon";
  }
  throw std::invalid_argument("edge_style_name: unknown style " + std::to_string(static_cast<int>(style)));
}

std::optional<EdgeStyle> parse_edge_style(std::string_view name) {
  for (EdgeStyle s : kEdgeStyles)
    if (edge_style_name(s) == name) return s;
  return std::nullopt;
}

EdgeStyleRenderer::EdgeStyleRenderer() : empty_(VertexArray::create()), toon_shades_(Texture::create(GL_TEXTURE_1D)) {
  {
    const Shader vertex = compile_shader(GL_VERTEX_SHADER, shaders::shadow_scene_vert, "shadow_scene.vert.glsl");
    const Shader fragment =
        compile_shader(GL_FRAGMENT_SHADER, shaders::edge_style_shade_frag, "edge_style_shade.frag.glsl");
    shade_ = link_program({&vertex, &fragment}, "edge_style_shade");
  }
  {
    const Shader vertex = compile_shader(GL_VERTEX_SHADER, shaders::screen_triangle_vert, "screen_triangle.vert.glsl");
    const Shader fragment =
        compile_shader(GL_FRAGMENT_SHADER, shaders::edge_style_composite_frag, "edge_style_composite.frag.glsl");
    composite_ = link_program({&vertex, &fragment}, "edge_style_composite");
  }
  const GLuint shades = toon_shades_.name();
  glTextureStorage1D(shades, 1, GL_R32F, static_cast<GLsizei>(kToonShades.size()));
  glTextureSubImage1D(shades, 0, 0, static_cast<GLsizei>(kToonShades.size()), GL_RED, GL_FLOAT, kToonShades.data());
  glTextureParameteri(shades, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // Lake et al.: hard bands
  glTextureParameteri(shades, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(shades, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  check_gl_errors("EdgeStyleRenderer");
}

void EdgeStyleRenderer::draw(const OffscreenTarget& target, const EdgeMapRenderer& edges, const Camera& camera,
                             EdgeStyle style, const EdgeStyleOptions& options, GpuStageTimer* timer) {
  const EdgeMap& edge_map = edges.edge_map();
  const std::uint32_t w = target.width(), h = target.height();
  if (edge_map.width() != w || edge_map.height() != h)
    throw std::invalid_argument("EdgeStyleRenderer::draw: the edge map is " + std::to_string(edge_map.width()) + "x" +
                                std::to_string(edge_map.height()) + ", the target " + std::to_string(w) + "x" +
                                std::to_string(h));
  const bool shadows = !options.light_amount.empty();
  if (shadows && options.light_amount.size() != std::size_t{w} * h)
    throw std::invalid_argument("EdgeStyleRenderer::draw: the light amount has " +
                                std::to_string(options.light_amount.size()) + " values for " + std::to_string(w) +
                                "x" + std::to_string(h) + " pixels");
  if (!shade_target_ || shade_target_->width() != w || shade_target_->height() != h) {
    shade_target_.reset();
    shade_target_.emplace(w, h, GL_RGBA8, true, "EdgeStyleRenderer shade");
  }
  if (shadows) {
    if (!light_amount_ || light_amount_width_ != w || light_amount_height_ != h) {
      light_amount_ = Texture::create(GL_TEXTURE_2D);
      glTextureStorage2D(light_amount_.name(), 1, GL_R32F, static_cast<GLsizei>(w), static_cast<GLsizei>(h));
      glTextureParameteri(light_amount_.name(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(light_amount_.name(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      light_amount_width_ = w;
      light_amount_height_ = h;
    }
    std::vector<float> rows(options.light_amount.size());  // GL's rows run bottom-up
    for (std::uint32_t r = 0; r < h; ++r)
      std::copy_n(options.light_amount.data() + std::size_t{h - 1 - r} * w, w, rows.data() + std::size_t{r} * w);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(light_amount_.name(), 0, 0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h), GL_RED,
                        GL_FLOAT, rows.data());
  }

  const GLuint shade = shade_.name();
  const glm::mat4 world_to_clip(projection_matrix(camera) * view_matrix(camera));
  glProgramUniformMatrix4fv(shade, kWorldToClipLocation, 1, GL_FALSE, glm::value_ptr(world_to_clip));
  glProgramUniform1i(shade, kShadeStyleLocation, style_index(style));
  const std::array<double, 4>& l = options.light.position;
  glProgramUniform4f(shade, kShadeLightLocation, static_cast<float>(l[0]), static_cast<float>(l[1]),
                     static_cast<float>(l[2]), static_cast<float>(l[3]));
  glProgramUniform1i(shade, kShadeHasAmountLocation, shadows ? 1 : 0);
  glProgramUniform3f(shade, kShadeEyeLocation, static_cast<float>(camera.eye[0]), static_cast<float>(camera.eye[1]),
                     static_cast<float>(camera.eye[2]));
  const GLuint composite = composite_.name();
  glProgramUniform1i(composite, kCompositeStyleLocation, style_index(style));
  glProgramUniform2f(composite, kCompositeThresholdsLocation, static_cast<float>(options.profile_threshold),
                     static_cast<float>(options.inner_threshold));

  const ScopedStage stage(timer, RenderStage::composite);
  // 1. The scene shaded in the style (each triangle once), into the shade texture.
  shade_target_->bind();
  const float cleared[4] = {0.0f, 0.0f, 0.0f, 0.0f};  // alpha 0: no surface
  shade_target_->clear(cleared);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glUseProgram(shade);
  glBindTextureUnit(0, shadows ? light_amount_.name() : 0);
  glBindTextureUnit(1, toon_shades_.name());
  glBindVertexArray(edges.mesh().vertex_array());
  glDrawArrays(GL_TRIANGLES, 0, edges.mesh().single_order_vertex_count());

  // 2. The edges over it, into the target: colour only, every pixel once.
  target.bind();
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glUseProgram(composite);
  glBindTextureUnit(0, shade_target_->texture());
  glBindTextureUnit(1, edge_map.texture());
  glBindVertexArray(empty_.name());
  glDrawArrays(GL_TRIANGLES, 0, 3);

  glBindVertexArray(0);
  glBindTextureUnit(0, 0);
  glBindTextureUnit(1, 0);
  glUseProgram(0);
  glDepthMask(GL_TRUE);
  check_gl_errors("EdgeStyleRenderer::draw");
}

RgbaImage EdgeStyleRenderer::render(const OffscreenTarget& target, const EdgeMapRenderer& edges, const Camera& camera,
                                    EdgeStyle style, const EdgeStyleOptions& options, GpuStageTimer* timer) {
  draw(target, edges, camera, style, options, timer);
  return target.read_colour();
}

FrameTiming time_edge_frames(EdgeMapRenderer& edges, EdgeStyleRenderer& style, const OffscreenTarget& target,
                             const Camera& camera, EdgeFilter filter, EdgeStyle style_kind,
                             const EdgeStyleOptions& options, std::size_t warm_up, std::size_t frames,
                             StageSync sync) {
  if (frames == 0) throw std::invalid_argument("time_edge_frames: frames must be at least 1");
  const auto frame = [&](GpuStageTimer* timer) {
    edges.draw(target.width(), target.height(), camera, filter, timer);
    style.draw(target, edges, camera, style_kind, options, timer);
  };
  for (std::size_t i = 0; i < warm_up; ++i) {
    frame(nullptr);
    glFinish();
  }
  GpuStageTimer timer(sync);
  std::vector<double> wall_ms;
  wall_ms.reserve(frames);
  for (std::size_t i = 0; i < frames; ++i) {
    const auto start = Clock::now();
    timer.begin_frame();
    frame(&timer);
    timer.end_frame();
    glFinish();
    wall_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  const std::vector<FrameStageTimes> gpu = timer.collect();
  return summarize_frames(kEdgeStages, sync, gpu, wall_ms);
}

}  // namespace shadowcert::gpu
