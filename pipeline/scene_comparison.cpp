#include "cli/scene_comparison.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <span>
#include <stdexcept>

#include "cli/mesh_palette.h"
#include "exact/captured_volume.h"
#include "exact/cpu_volume.h"
#include "exact/input_rounding.h"
#include "gpu/depth_precision.h"
#include "gpu/gl_environment_error.h"
#include "gpu/offscreen_target.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/merged_soup.h"

namespace shadowcert::cli {
namespace {

// The exact image's options: the GL depth band, and with `progress` a bar on stderr.
ExactImageOptions exact_options(bool progress) {
  ExactImageOptions options;
  options.depth_band = [](double view_depth) { return gpu::depth_band(view_depth); };
  if (!progress) return options;
  options.progress = [](std::string_view stage, std::uint64_t done, std::uint64_t total) {
    constexpr int kBarWidth = 32;
    const double fraction = total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total);
    const auto filled = static_cast<std::size_t>(fraction * kBarWidth);
    fmt::print(stderr, "\rexact image, {:<6} [{}{}] {:3.0f}%", stage, std::string(filled, '#'),
               std::string(kBarWidth - filled, '.'), 100.0 * fraction);
    if (done >= total) fmt::print(stderr, "\n");
    std::fflush(stderr);
  };
  return options;
}

// The frame's coverage: 255 where a receiver was drawn (alpha), else 0.
std::vector<std::uint8_t> coverage(const gpu::RgbaImage& colour) {
  std::vector<std::uint8_t> c(std::size_t{colour.width} * colour.height);
  for (std::size_t p = 0; p < c.size(); ++p) c[p] = colour.pixels[4 * p + 3] != 0 ? 255 : 0;
  return c;
}

}  // namespace

std::vector<gpu::ShadowMethod> parse_shadow_methods(const std::string& list, const std::string& option) {
  if (list.empty()) return {gpu::kShadowMethods.begin(), gpu::kShadowMethods.end()};
  std::vector<gpu::ShadowMethod> methods;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    const std::optional<gpu::ShadowMethod> method = gpu::parse_shadow_method(name);
    if (!method)
      throw CLI::ValidationError(option, "unknown method '" + name + "': use cpu, cs, gs, ts, pertri, shadowmap");
    if (std::find(methods.begin(), methods.end(), *method) == methods.end()) methods.push_back(*method);
    start = comma + 1;
  }
  return methods;
}

gpu::EglContext open_gl_context(std::string_view command, std::optional<int> device) {
  try {
    return gpu::EglContext(gpu::EglContextOptions{device, gpu::kGlDebugByDefault});
  } catch (const gpu::GlEnvironmentError& e) {
    throw gpu::GlEnvironmentError(std::string(command) +
                                  " needs OpenGL 4.5 core through headless EGL (a GPU driver or Mesa's llvmpipe: "
                                  "packages libegl-mesa0 libgl1-mesa-dri); " + std::string(e.what()));
  }
}

std::uint64_t MethodRun::sum(std::uint64_t PixelComparison::*figure) const {
  std::uint64_t n = 0;
  for (const LightRun& l : lights) n += l.comparison.*figure;
  return n;
}

std::optional<bool> MethodRun::closed() const {
  if (!gpu::draws_volume(method)) return std::nullopt;
  return std::all_of(lights.begin(), lights.end(), [](const LightRun& l) { return l.closure && l.closure->closed; });
}

double MethodRun::gl_ms() const {
  return std::accumulate(lights.begin(), lights.end(), 0.0, [](double s, const LightRun& l) { return s + l.gl_ms; });
}

bool MethodRun::failed() const {
  return robust(method) && (sum(&PixelComparison::hard_errors) > 0 || closed() == false);
}

bool SceneComparison::passed() const {
  return std::none_of(runs.begin(), runs.end(), [](const MethodRun& r) { return r.failed(); });
}

SceneComparison compare_scene(const Scene& scene, const std::vector<gpu::ShadowMethod>& methods,
                              const SceneComparisonOptions& options) {
  if (scene.lights.empty()) throw std::invalid_argument("compare_scene: the scene has no light");
  if (methods.empty()) throw std::invalid_argument("compare_scene: no method");
  const Soup merged = merged_soup(scene);
  if (merged.triangles.empty()) throw std::invalid_argument("compare_scene: the scene has no triangle");
  const Camera& camera = scene.camera;

  // The reference: every triangle of the scene receives and casts, as in the GL methods. The
  // GPU gets the scene in float: where that rounding changes the exact answer, the pixel is
  // ambiguous (exact/input_rounding.h), so the scene is imaged twice.
  SceneComparison result;
  result.exact =
      exact_image_of_float_input(merged, scene.lights, camera, exact_options(options.progress), &result.rounded_seconds);

  // The volume methods' inputs (as in render): canonical soup, edge table, cpu's exact chains.
  const bool any_volume = std::any_of(methods.begin(), methods.end(), gpu::draws_volume);
  std::optional<CanonicalSoup> canonical;
  EdgeTable table;
  std::vector<HomogeneousMesh> cpu_volumes;
  if (any_volume) {
    canonical = canonical_soup(merged);
    table = build_edge_table(canonical->soup);
  }
  if (std::find(methods.begin(), methods.end(), gpu::ShadowMethod::cpu) != methods.end())
    for (const Light& light : scene.lights) cpu_volumes.push_back(cpu_volume_mesh(canonical->soup, table, light));

  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(scene);
  const gpu::OffscreenTarget target(camera.width, camera.height);
  for (gpu::ShadowMethod method : methods) {
    MethodRun run{method, {}};
    for (std::size_t k = 0; k < scene.lights.size(); ++k) {
      gpu::ShadowMethodScene method_scene;
      method_scene.receivers = parts;
      method_scene.lights = std::span<const Light>(&scene.lights[k], 1);
      if (canonical) method_scene.canonical = &canonical->soup;
      method_scene.table = &table;
      if (method == gpu::ShadowMethod::cpu)
        method_scene.cpu_volumes = std::span<const HomogeneousMesh>(&cpu_volumes[k], 1);
      gpu::ShadowMethodRenderer renderer(method, method_scene, options.method_options);
      LightRun l;
      l.frame = renderer.render(target, camera);
      try {
        renderer.check_capacity();
      } catch (const gpu::VolumeCapacityError& e) {
        l.capacity_error = e.what();  // what was drawn is still compared and certified (open)
      }
      const std::vector<std::uint8_t> covered = coverage(l.frame.colour);
      RenderedPixels rendered{camera.width, camera.height, covered, l.frame.first_lit_mask.pixels, {}};
      if (gpu::draws_volume(method)) rendered.counts = l.frame.first_stencil.pixels;
      l.comparison = compare_pixels(result.exact, k, rendered);
      if (gpu::draws_volume(method)) {
        l.closure = certify_captured_closure(renderer.first_volume()).certificate;
        l.volume_triangles = renderer.volume_triangles();
      }
      if (options.timed_frames > 0) {
        const std::vector<double> ms = renderer.render_frames(target, camera, options.timed_frames);
        l.gl_ms = std::accumulate(ms.begin(), ms.end(), 0.0) / static_cast<double>(ms.size());
      }
      run.lights.push_back(std::move(l));
    }
    result.runs.push_back(std::move(run));
  }
  return result;
}

}  // namespace shadowcert::cli
