#include "gpu/edge_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// edge_c1.frag.glsl's `rows` uniform: a bit per row of taps (A B C, D E, F G H).
constexpr GLint kC1RowsLocation = 0;
constexpr GLint kC1AllRows = 7;

Program filter_program(std::string_view vertex_source, std::string_view fragment_source, std::string_view name) {
  const Shader vertex = compile_shader(GL_VERTEX_SHADER, vertex_source, "screen_triangle.vert.glsl");
  const Shader fragment = compile_shader(GL_FRAGMENT_SHADER, fragment_source, std::string(name) + ".frag.glsl");
  return link_program({&vertex, &fragment}, name);
}

SceneBounds parts_bounds(std::span<const ShadedSoupPart> parts) {
  bool any = false;
  SceneBounds bounds;
  for (const ShadedSoupPart& part : parts) {
    if (part.soup == nullptr || part.soup->triangles.empty()) continue;
    const SceneBounds b = soup_bounds(*part.soup);
    if (!any) {
      bounds = b;
      any = true;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      bounds.lo[k] = std::min(bounds.lo[k], b.lo[k]);
      bounds.hi[k] = std::max(bounds.hi[k], b.hi[k]);
    }
  }
  if (!any) throw std::invalid_argument("EdgeMapRenderer: no triangle to draw");
  return bounds;
}

}  // namespace

std::string_view edge_filter_name(EdgeFilter filter) {
  switch (filter) {
    case EdgeFilter::diagonal: return "diagonal";
    case EdgeFilter::c1: return "c1";
    case EdgeFilter::sobel: return "sobel";
  }
  throw std::invalid_argument("edge_filter_name: unknown filter " + std::to_string(static_cast<int>(filter)));
}

std::optional<EdgeFilter> parse_edge_filter(std::string_view name) {
  for (EdgeFilter f : kEdgeFilters)
    if (edge_filter_name(f) == name) return f;
  return std::nullopt;
}

double profile_threshold(EdgeFilter filter, double depth_step) {
  if (!(depth_step >= 0.0 && depth_step <= 1.0))
    throw std::invalid_argument("profile_threshold: the depth step must be in [0, 1], got " + std::to_string(depth_step));
  switch (filter) {
    case EdgeFilter::diagonal: return 1.0 - std::pow(1.0 - depth_step / 2.0, 4.0);  // both pairs straddle the step
    case EdgeFilter::c1: return depth_step / 3.0;  // weights 1 + 2 + 1 of 12 across it
    case EdgeFilter::sobel: return depth_step;     // |G| = 4 s, divided by 4
  }
  throw std::invalid_argument("profile_threshold: unknown filter");
}

double inner_threshold(EdgeFilter filter, double crease_angle_degrees) {
  if (!(crease_angle_degrees >= 0.0 && crease_angle_degrees <= 180.0))
    throw std::invalid_argument("inner_threshold: the crease angle must be in [0, 180] degrees, got " +
                                std::to_string(crease_angle_degrees));
  const double a = crease_angle_degrees * std::numbers::pi / 180.0;
  switch (filter) {
    case EdgeFilter::diagonal: return (1.0 - std::cos(a)) / 2.0;  // I_N = cos a
    case EdgeFilter::c1: return (1.0 - std::cos(a)) / 6.0;        // 4 of 12 weights times (1 - cos a) / 2
    case EdgeFilter::sobel: return std::sin(a / 2.0);             // |G_n| = 4 |n_1 - n_2| = 8 sin(a / 2)
  }
  throw std::invalid_argument("inner_threshold: unknown filter");
}

EdgePixelCounts count_edge_pixels(const EdgeMapImage& map, double profile_threshold, double inner_threshold) {
  EdgePixelCounts counts;
  for (std::size_t i = 0; i < map.covered.size(); ++i) {
    counts.profile += map.profile[i] > profile_threshold ? 1 : 0;
    counts.inner += map.inner[i] > inner_threshold ? 1 : 0;
    counts.covered += map.covered[i] != 0 ? 1 : 0;
  }
  return counts;
}

EdgeMap::EdgeMap(std::uint32_t width, std::uint32_t height) : target_(width, height, GL_RGBA32F, false, "EdgeMap") {}

void EdgeMap::bind() const { target_.bind(); }

std::vector<float> EdgeMap::read_texels() const { return target_.read_rgba(); }

EdgeMapImage EdgeMap::read() const {
  const std::vector<float> texels = read_texels();
  EdgeMapImage image;
  image.width = width();
  image.height = height();
  const std::size_t n = std::size_t{image.width} * image.height;
  image.profile.resize(n);
  image.inner.resize(n);
  image.covered.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    image.profile[i] = texels[4 * i];
    image.inner[i] = texels[4 * i + 1];
    image.covered[i] = texels[4 * i + 2] > 0.5f ? 1 : 0;
  }
  return image;
}

EdgeMapFilter::EdgeMapFilter()
    : empty_(VertexArray::create()),
      diagonal_(filter_program(shaders::screen_triangle_vert, shaders::edge_diagonal_frag, "edge_diagonal")),
      c1_(filter_program(shaders::screen_triangle_vert, shaders::edge_c1_frag, "edge_c1")),
      sobel_(filter_program(shaders::screen_triangle_vert, shaders::edge_sobel_frag, "edge_sobel")) {}

void EdgeMapFilter::apply(const GBuffer& g_buffer, const EdgeMap& out, EdgeFilter filter,
                          const EdgeMapOptions& options, GpuStageTimer* timer) const {
  if (g_buffer.width() != out.width() || g_buffer.height() != out.height())
    throw std::invalid_argument("EdgeMapFilter::apply: the G-buffer is " + std::to_string(g_buffer.width()) + "x" +
                                std::to_string(g_buffer.height()) + ", the edge map " + std::to_string(out.width()) +
                                "x" + std::to_string(out.height()));
  const ScopedStage stage(timer, RenderStage::edge_filter);
  out.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_FALSE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glBindTextureUnit(0, g_buffer.texture());
  glBindVertexArray(empty_.name());
  const bool three_passes = filter == EdgeFilter::c1 && options.c1_three_passes;
  if (three_passes) {
    // The paper's form: each pass adds one row of taps (A B C, then D E, then F G H) to a
    // cleared map by blending.
    const std::array<float, 4> zero{0.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, zero.data());
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(c1_.name());
    for (const GLint rows : {1, 2, 4}) {
      glProgramUniform1i(c1_.name(), kC1RowsLocation, rows);
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDisable(GL_BLEND);
  } else {
    glDisable(GL_BLEND);
    const Program& program = filter == EdgeFilter::diagonal ? diagonal_ : filter == EdgeFilter::c1 ? c1_ : sobel_;
    if (filter == EdgeFilter::c1) glProgramUniform1i(c1_.name(), kC1RowsLocation, kC1AllRows);
    glUseProgram(program.name());
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glBindVertexArray(0);
  glBindTextureUnit(0, 0);
  glUseProgram(0);
  glDepthMask(GL_TRUE);
  check_gl_errors("EdgeMapFilter::apply");
}

EdgeMapRenderer::EdgeMapRenderer(std::span<const ShadedSoupPart> parts, const EdgeMapOptions& options)
    : options_(options), mesh_(parts), bounds_(parts_bounds(parts)) {}

DepthRange EdgeMapRenderer::depth_range(const Camera& camera) const { return fitted_depth_range(camera, bounds_); }

void EdgeMapRenderer::draw(std::uint32_t width, std::uint32_t height, const Camera& camera, EdgeFilter filter,
                           GpuStageTimer* timer) {
  if (!g_buffer_ || g_buffer_->width() != width || g_buffer_->height() != height) {
    edge_map_.reset();
    g_buffer_.reset();
    g_buffer_.emplace(width, height);
    edge_map_.emplace(width, height);
  }
  g_buffer_pass_.render(*g_buffer_, mesh_, camera, depth_range(camera), timer);
  filter_.apply(*g_buffer_, *edge_map_, filter, options_, timer);
}

EdgeMapImage EdgeMapRenderer::render(const OffscreenTarget& target, const Camera& camera, EdgeFilter filter,
                                     GpuStageTimer* timer) {
  draw(target.width(), target.height(), camera, filter, timer);
  return edge_map_->read();
}

const GBuffer& EdgeMapRenderer::g_buffer() const {
  if (!g_buffer_) throw std::logic_error("EdgeMapRenderer::g_buffer: nothing drawn yet");
  return *g_buffer_;
}

const EdgeMap& EdgeMapRenderer::edge_map() const {
  if (!edge_map_) throw std::logic_error("EdgeMapRenderer::edge_map: nothing drawn yet");
  return *edge_map_;
}

}  // namespace shadowcert::gpu
