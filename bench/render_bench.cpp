// Issue 4's rendering benchmark: ms per frame of every method (cpu, cs, gs, ts, pertri,
// shadowmap; gpu/shadow_method_renderer.h) and of each stage of its frame, on Milet 2014's
// sphere grid (scene/procedural_mesh.h) over a floor, one point light, a camera that sees the
// whole grid. Target (docs/gpu.md): the silhouette methods at least 2x faster than pertri at
// 1M triangles; on NVIDIA, ts and cs under 2 ms at 1M.
//
//   render_bench [--triangles=32000,128000,512000,1000000] [--resolution=1024x768]
//                [--stage-sync=auto|finish|none] [Google Benchmark flags]
//   render_bench --benchmark_filter=render/pertri/      # one method
//   render_bench --triangles=1000000,2000000,4000000 --resolution=1920x1080   # the NVIDIA run
//
// One benchmark per (triangles, method), named render/METHOD/TRIANGLES and run in size order;
// cs, gs, ts and pertri run twice, with their default exact signs and as METHOD-float with
// `--sign float` (gpu/sign_mode.h), so that the exact signs' cost is a ratio of one run. Their
// exact rows count sign_fallback_pct: the share of triangles whose sign the float filter could
// not decide (gpu/light_side_probe.h on the grid's sorted triples, the evaluations the volume
// shaders make).
// Each iteration is one frame (volumes rebuilt for the GPU methods, no readback, glFinish),
// timed on the wall clock (manual time: the Time column is the mean ms per frame). Counters,
// medians over the iterations, in ms: each stage of the method (volume, depth, stencil, lit;
// shadowmap: depth, shadow_map, lit), frame_ms (wall) and gpu_frame_ms (GL timestamps), and
// tris / vol_tris, the scene's and the first light's volume triangles. Stage figures are GPU
// timer queries on a GPU; on a software renderer (llvmpipe), whose queries do not time its
// stages (gpu/gpu_stage_timer.h), every stage is bounded by glFinish and timed on the wall
// clock (--stage-sync=auto picks this).
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "gpu/camera_transform.h"
#include "gpu/egl_context.h"
#include "gpu/frame_timing.h"
#include "gpu/light_side_probe.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method_renderer.h"
#include "pipeline/method_inputs.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

#include "gl_bench_main.h"

namespace {

using namespace shadowcert;

const std::vector<std::uint64_t> kDefaultTriangles{32'000, 128'000, 512'000, 1'000'000};
// The floor under the grid (x, z in [-12.25, 12.25]): wide enough to catch every shadow of the
// light below, which stands above the grid's corner as in data/scenes/sphere_grid_1m.json.
constexpr double kFloorHalfSize = 16.0;
const Light kLight{{4.0, 30.0, 8.0, 1.0}};
// Frames per benchmark: a frame of pertri at 1M triangles takes ~46 s on llvmpipe, so large
// sizes get the fewest frames that still give a median. One more frame before them is untimed
// (llvmpipe compiles shader variants on first use).
constexpr std::uint64_t kLargeScene = 400'000;
constexpr std::uint64_t kMidScene = 100'000;
constexpr benchmark::IterationCount kLargeFrames = 3;
constexpr benchmark::IterationCount kMidFrames = 5;
constexpr benchmark::IterationCount kSmallFrames = 10;

struct Settings {
  std::vector<std::uint64_t> triangles = kDefaultTriangles;
  std::uint32_t width = 1024;
  std::uint32_t height = 768;
  std::string stage_sync = "auto";
};

// The scene of one size and what every method needs of it; only one size is kept at a time.
struct GridScene {
  std::uint64_t requested = 0;
  Soup soup;  // the grid with the floor appended: the one caster and receiver soup
  std::vector<Light> lights{kLight};
  Camera camera;
  // pipeline/method_inputs.h: canonical soup and edge table, and cpu's volumes (added on
  // cpu's first use).
  MethodInputs inputs;
};

// The grid with floor_quad(kFloorHalfSize) appended; both have vertex normals (the floor's +y),
// so the soup keeps one normal per vertex.
Soup over_floor(Soup soup) {
  append_soup(soup, floor_quad(kFloorHalfSize));
  return soup;
}

Camera grid_camera(std::uint32_t width, std::uint32_t height) {
  Camera camera;
  camera.eye = {0.0, 24.0, 32.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.fov_y_degrees = 45.0;
  camera.width = width;
  camera.height = height;
  return camera;
}

// Throws when a corner of the grid's bounding box falls outside the image: the benchmark's
// premise is that every sphere, hence every volume, is on screen.
void check_grid_in_view(const Soup& grid, const Camera& camera) {
  Vec3 lo = grid.vertices.front(), hi = lo;
  for (const Vec3& v : grid.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1], corner & 4 ? hi[2] : lo[2]};
    const glm::dvec2 xy = gpu::project_to_image(camera, p);
    if (xy.x < 0.0 || xy.y < 0.0 || xy.x > camera.width || xy.y > camera.height)
      throw std::runtime_error(fmt::format("render_bench: the grid's corner ({}, {}, {}) is outside the {}x{} image",
                                           p[0], p[1], p[2], camera.width, camera.height));
  }
}

GridScene& grid_scene(std::uint64_t triangles, const Settings& settings) {
  static std::unique_ptr<GridScene> current;
  if (current && current->requested == triangles) return *current;
  current.reset();  // free the previous size first: the 1M grid's data is hundreds of MiB
  auto s = std::make_unique<GridScene>();
  s->requested = triangles;
  s->camera = grid_camera(settings.width, settings.height);
  Soup grid = sphere_grid(triangles);
  check_grid_in_view(grid, s->camera);
  s->soup = over_floor(std::move(grid));
  const std::array gpu_built{gpu::ShadowMethod::cs};
  s->inputs = prepare_method_inputs(s->soup, s->lights, gpu_built);
  current = std::move(s);
  return *current;
}

void prepare_cpu_volumes(GridScene& s) {
  if (s.inputs.cpu_volumes.empty()) add_cpu_volumes(s.inputs, s.lights);
}

// The percentage of the canonical soup's triangles (repeated indices excepted) whose sorted
// triple the exact signs' float filter leaves to the integer stage, for `light`.
double sign_fallback_percent(const Soup& canonical, const Light& light) {
  std::vector<gpu::Vec3f> points;
  points.reserve(3 * canonical.triangles.size());
  for (const auto& t : canonical.triangles) {
    std::array<std::uint32_t, 3> sorted = t;
    std::sort(sorted.begin(), sorted.end());
    if (sorted[0] == sorted[1] || sorted[1] == sorted[2]) continue;
    for (std::uint32_t i : sorted) {
      const Vec3& v = canonical.vertices[i];
      points.push_back({static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])});
    }
  }
  const auto& l = light.position;
  const std::vector<gpu::LightSideSample> samples = gpu::LightSideProbe{}.evaluate(
      points, {static_cast<float>(l[0]), static_cast<float>(l[1]), static_cast<float>(l[2]), static_cast<float>(l[3])});
  const auto fallbacks = std::count_if(samples.begin(), samples.end(), [](const auto& x) { return x.fallback; });
  return samples.empty() ? 0.0 : 100.0 * static_cast<double>(fallbacks) / static_cast<double>(samples.size());
}

void run_method(benchmark::State& state, gpu::ShadowMethod method, gpu::SignMode sign, std::uint64_t triangles,
                const Settings& settings, gpu::StageSync sync) {
  GridScene& s = grid_scene(triangles, settings);
  const std::array<gpu::ShadedSoupPart, 1> receivers{gpu::ShadedSoupPart{&s.soup}};
  if (method == gpu::ShadowMethod::cpu) prepare_cpu_volumes(s);
  gpu::ShadowMethodOptions options;
  options.sign = sign;
  gpu::ShadowMethodRenderer renderer(method, method_scene(s.inputs, receivers, s.lights), options);
  const gpu::OffscreenTarget target(s.camera.width, s.camera.height);
  (void)renderer.render_frames(target, s.camera, 1);  // warm-up: shader variants
  renderer.check_capacity();
  const std::uint64_t volume_triangles = renderer.volume_triangles();

  gpu::GpuStageTimer timer(sync);
  std::vector<double> wall_ms;
  for (auto _ : state) {
    const double ms = renderer.render_frames(target, s.camera, 1, &timer).front();
    state.SetIterationTime(ms / 1000.0);
    wall_ms.push_back(ms);
  }
  const gpu::FrameTiming t = gpu::summarize_frames(gpu::method_stages(method), sync, timer.collect(), wall_ms);
  for (gpu::RenderStage stage : t.stages)
    state.counters[std::string(gpu::render_stage_name(stage)) + "_ms"] =
        sync == gpu::StageSync::finish ? t.wall(stage).median_ms : t.gpu(stage).median_ms;
  state.counters["frame_ms"] = t.frame_cpu.median_ms;
  state.counters["gpu_frame_ms"] = t.frame_gpu.median_ms;
  state.counters["tris"] = static_cast<double>(s.soup.triangles.size());
  state.counters["vol_tris"] = static_cast<double>(volume_triangles);
  if (gpu::builds_volume_on_gpu(method) && sign == gpu::SignMode::exact)
    state.counters["sign_fallback_pct"] = sign_fallback_percent(s.inputs.canonical.soup, s.lights.front());
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
      const auto [width, height] = bench::image_size(*size, "--resolution", "1920x1080");
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
  if (!bench::take_command_line("render_bench", argc, argv, settings, take_settings)) return 2;

  const std::optional<gpu::EglContext> context = bench::open_bench_context("render_bench");
  if (!context) return 2;
  const gpu::StageSync sync = bench::chosen_stage_sync(settings.stage_sync, *context);
  bench::add_gl_context(*context, sync, "stages");
  benchmark::AddCustomContext("resolution", fmt::format("{}x{}", settings.width, settings.height));

  for (std::uint64_t triangles : settings.triangles) {
    for (gpu::ShadowMethod method : gpu::kShadowMethods) {
      const benchmark::IterationCount frames = triangles > kLargeScene ? kLargeFrames
                                               : triangles > kMidScene ? kMidFrames
                                                                       : kSmallFrames;
      for (gpu::SignMode sign : {gpu::SignMode::exact, gpu::SignMode::float32}) {
        if (sign == gpu::SignMode::float32 && !gpu::builds_volume_on_gpu(method)) continue;
        const std::string name = sign == gpu::SignMode::exact
                                     ? fmt::format("render/{}/{}", gpu::shadow_method_name(method), triangles)
                                     : fmt::format("render/{}-float/{}", gpu::shadow_method_name(method), triangles);
        benchmark::RegisterBenchmark(name.c_str(),
                                     [method, sign, triangles, &settings, sync](benchmark::State& state) {
                                       try {
                                         run_method(state, method, sign, triangles, settings, sync);
                                       } catch (const std::exception& e) {  // e.g. a volume past its buffers
                                         state.SkipWithError(e.what());
                                       }
                                     })
            ->Iterations(frames)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
      }
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
