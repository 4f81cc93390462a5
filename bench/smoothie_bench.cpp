// Issue 13's smoothie benchmark (docs/smoothies.md, "Performance"): per frame at 1024x768, the
// smoothies' generation on the CPU (pipeline/scene_smoothies.h: the exact silhouette edges, then
// contour/smoothie.h's quads), and the frames of the shadow map's methods (gpu/shadow_map_renderer.h)
// with each stage: the hard map alone (shadowmap), PCF 3x3 and 5x5, PCSS, and smoothie (its
// smoothie map pass apart), on render_bench's scene: Milet 2014's sphere grid over a floor, one
// point light, a camera that sees the whole grid.
//
//   smoothie_bench [--triangles=32000,128000] [--resolution=1024x768] [--stage-sync=auto|finish|none]
//                  [Google Benchmark flags]
//
// smoothie/generate/N: one iteration = every light's smoothies of the N-triangle grid (wall
// ms); counters edges_ms (exact multiplicities and edge selection), quads_ms (build_smoothies),
// silhouette_edges, smoothie_tris. frame/METHOD/N: one iteration = one frame (no readback,
// glFinish), as render_bench; counters: each stage's median ms (depth, shadow_map, smoothie_map,
// lit), frame_ms, gpu_frame_ms. On a software renderer the stages are bounded by glFinish and
// timed on the wall clock (--stage-sync=auto picks it), as in render_bench.
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "contour/smoothie.h"
#include "core/camera.h"
#include "core/float_rounding.h"
#include "core/light.h"
#include "core/soup.h"
#include "gpu/egl_context.h"
#include "gpu/frame_timing.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_map_renderer.h"
#include "gpu/shadow_method_renderer.h"
#include "pipeline/method_inputs.h"
#include "pipeline/scene_smoothies.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

#include "gl_bench_main.h"

namespace {

using namespace shadowcert;
using Clock = std::chrono::steady_clock;

const std::vector<std::uint64_t> kDefaultTriangles{32'000, 128'000};
// render_bench's scene: the floor under the grid and the light above its corner.
constexpr double kFloorHalfSize = 16.0;
const Light kLight{{4.0, 30.0, 8.0, 1.0}};
constexpr benchmark::IterationCount kFrames = 10;
constexpr benchmark::IterationCount kGenerations = 10;

struct Settings {
  std::vector<std::uint64_t> triangles = kDefaultTriangles;
  std::uint32_t width = 1024;
  std::uint32_t height = 768;
  std::string stage_sync = "auto";
};

struct GridScene {
  std::uint64_t requested = 0;
  Soup soup;  // the grid with the floor: every triangle casts and receives
  std::vector<Light> lights{kLight};
  Camera camera;
  gpu::SceneBounds bounds;
  MethodInputs inputs;  // canonical soup, edge table and the smoothies
};

GridScene& grid_scene(std::uint64_t triangles, const Settings& settings) {
  static std::unique_ptr<GridScene> current;
  if (current && current->requested == triangles) return *current;
  current.reset();
  auto s = std::make_unique<GridScene>();
  s->requested = triangles;
  s->camera.eye = {0.0, 24.0, 32.0};
  s->camera.target = {0.0, 0.0, 0.0};
  s->camera.fov_y_degrees = 45.0;
  s->camera.width = settings.width;
  s->camera.height = settings.height;
  s->soup = sphere_grid(triangles);
  append_soup(s->soup, floor_quad(kFloorHalfSize));
  s->bounds = gpu::soup_bounds(s->soup);
  const std::array methods{gpu::ShadowMethod::smoothie};
  s->inputs = prepare_method_inputs(s->soup, s->lights, methods);
  add_smoothies(s->inputs, s->lights, s->bounds);
  current = std::move(s);
  return *current;
}

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void run_generation(benchmark::State& state, std::uint64_t triangles, const Settings& settings) {
  GridScene& s = grid_scene(triangles, settings);
  const Soup& canonical = s.inputs.canonical.soup;
  std::vector<double> edges_ms, quads_ms;
  std::size_t silhouette_edges = 0, smoothie_triangles = 0;
  for (auto _ : state) {
    // scene_smoothies, split into its two stages (the float rounding counts with the edges).
    auto start = Clock::now();
    const Soup rounded = float_rounded(canonical);
    const Light light = float_rounded(s.lights.front());
    const SmoothieEdges edges = smoothie_edges(rounded, s.inputs.table, light);
    edges_ms.push_back(ms_since(start));
    start = Clock::now();
    SmoothieOptions options;
    options.width = s.inputs.smoothies.width;
    const Smoothies smoothies = build_smoothies(rounded.vertices, edges, light, options);
    quads_ms.push_back(ms_since(start));
    benchmark::DoNotOptimize(smoothies.mesh.triangles.data());
    silhouette_edges = edges.edges.size();
    smoothie_triangles = smoothies.mesh.triangles.size();
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  state.counters["edges_ms"] = median(edges_ms);
  state.counters["quads_ms"] = median(quads_ms);
  state.counters["silhouette_edges"] = static_cast<double>(silhouette_edges);
  state.counters["smoothie_tris"] = static_cast<double>(smoothie_triangles);
  state.counters["tris"] = static_cast<double>(s.soup.triangles.size());
}

struct FrameMethod {
  std::string name;
  gpu::ShadowMethod method;
  std::uint32_t pcf_kernel = gpu::kDefaultPcfKernel;
};

void run_frames(benchmark::State& state, const FrameMethod& m, std::uint64_t triangles, const Settings& settings,
                gpu::StageSync sync) {
  GridScene& s = grid_scene(triangles, settings);
  const std::array<gpu::ShadedSoupPart, 1> receivers{gpu::ShadedSoupPart{&s.soup}};
  gpu::ShadowMethodOptions options;
  options.pcf_kernel = m.pcf_kernel;
  gpu::ShadowMethodRenderer renderer(m.method, method_scene(s.inputs, receivers, s.lights), options);
  const gpu::OffscreenTarget target(s.camera.width, s.camera.height);
  (void)renderer.render_frames(target, s.camera, 1);  // warm-up: shader variants
  gpu::GpuStageTimer timer(sync);
  std::vector<double> wall_ms;
  for (auto _ : state) {
    const double ms = renderer.render_frames(target, s.camera, 1, &timer).front();
    state.SetIterationTime(ms / 1000.0);
    wall_ms.push_back(ms);
  }
  const gpu::FrameTiming t = gpu::summarize_frames(gpu::method_stages(m.method), sync, timer.collect(), wall_ms);
  for (gpu::RenderStage stage : t.stages)
    state.counters[std::string(gpu::render_stage_name(stage)) + "_ms"] =
        sync == gpu::StageSync::finish ? t.wall(stage).median_ms : t.gpu(stage).median_ms;
  state.counters["frame_ms"] = t.frame_cpu.median_ms;
  state.counters["gpu_frame_ms"] = t.frame_gpu.median_ms;
  state.counters["tris"] = static_cast<double>(s.soup.triangles.size());
  if (m.method == gpu::ShadowMethod::smoothie)
    state.counters["smoothie_tris"] = static_cast<double>(s.inputs.smoothies.per_light.front().triangles.size());
}

// Parses and removes this program's own flags (Google Benchmark rejects flags it does not know).
Settings take_settings(int& argc, char** argv) {
  Settings settings;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const auto value = [&](std::string_view flag) { return bench::flag_value(arg, flag); };
    if (const auto list = value("--triangles=")) {
      settings.triangles = bench::count_list(*list);
    } else if (const auto size = value("--resolution=")) {
      const auto [width, height] = bench::image_size(*size, "--resolution");
      settings.width = width;
      settings.height = height;
    } else if (const auto sync = value("--stage-sync=")) {
      settings.stage_sync = bench::stage_sync_setting(*sync);
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  return settings;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  if (!bench::take_command_line("smoothie_bench", argc, argv, settings, take_settings)) return 2;

  const std::optional<gpu::EglContext> context = bench::open_bench_context("smoothie_bench");
  if (!context) return 2;
  const gpu::StageSync sync = bench::chosen_stage_sync(settings.stage_sync, *context);
  bench::add_gl_context(*context, sync, "stages");
  benchmark::AddCustomContext("resolution", fmt::format("{}x{}", settings.width, settings.height));

  const std::vector<FrameMethod> methods{{"shadowmap", gpu::ShadowMethod::shadowmap},
                                         {"pcf3", gpu::ShadowMethod::pcf, 3},
                                         {"pcf5", gpu::ShadowMethod::pcf, 5},
                                         {"pcss", gpu::ShadowMethod::pcss},
                                         {"smoothie", gpu::ShadowMethod::smoothie}};
  for (std::uint64_t triangles : settings.triangles) {
    benchmark::RegisterBenchmark(fmt::format("smoothie/generate/{}", triangles).c_str(),
                                 [triangles, &settings](benchmark::State& state) {
                                   run_generation(state, triangles, settings);
                                 })
        ->Iterations(kGenerations)
        ->Unit(benchmark::kMillisecond);
    for (const FrameMethod& m : methods) {
      benchmark::RegisterBenchmark(fmt::format("frame/{}/{}", m.name, triangles).c_str(),
                                   [m, triangles, &settings, sync](benchmark::State& state) {
                                     try {
                                       run_frames(state, m, triangles, settings, sync);
                                     } catch (const std::exception& e) {
                                       state.SkipWithError(e.what());
                                     }
                                   })
          ->Iterations(kFrames)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
