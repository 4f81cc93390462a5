// Issue 14's edge-map benchmark (docs/edge-maps.md, "Timing"): ms per pass of the edge map and
// its styles (gpu/edge_map.h, gpu/edge_style.h): the G-buffer pass, the filter pass (the
// diagonal filter, C1 in one pass and in the paper's three, Sobel) and the composite (a style's
// scene pass and screen pass), at 1024x768 and 1920x1080, on three scenes:
//   creases  data/scenes/edges_creases.json (2,258 triangles), its own camera;
//   grid     render_bench's scene: Milet 2014's sphere grid (--triangles=, default 1,000,000)
//            over a floor, the camera of data/scenes/sphere_grid_1m.json;
//   ogre     ../shared/data/soups/ogre.obj over a floor, seen from the front and above (as
//            exact_image_bench); skipped when the shared data is absent.
//
//   edge_map_bench [--resolutions=1024x768,1920x1080] [--triangles=1000000] [--stage-sync=auto|finish|none]
//                  [Google Benchmark flags, e.g. --benchmark_filter=edges/creases/]
//
// edges/SCENE/FILTER/WxH: one iteration = one frame: the G-buffer, the filter and the gooch
// composite, no readback, ended by glFinish (wall ms, manual time); counters: each pass's median
// ms (g_buffer_ms, edge_filter_ms, composite_ms), frame_ms, gpu_frame_ms, tris.
// style/SCENE/STYLE/WxH: the same frame with the diagonal filter and each style (toon's
// composite samples nine texels of the cartoon map). On a software renderer each pass is bounded
// by glFinish and timed on the wall clock (--stage-sync=auto picks it), as in render_bench.
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/eye_frame.h"
#include "core/light.h"
#include "core/near_plane.h"
#include "core/scene.h"
#include "core/soup.h"
#include "gpu/edge_map.h"
#include "gpu/edge_style.h"
#include "gpu/egl_context.h"
#include "gpu/frame_timing.h"
#include "gpu/offscreen_target.h"
#include "io/scene_input.h"
#include "io/soup_file.h"
#include "pipeline/mesh_palette.h"
#include "scene/procedural_mesh.h"

#include "gl_bench_main.h"

namespace {

using namespace shadowcert;
using Clock = std::chrono::steady_clock;

constexpr benchmark::IterationCount kFrames = 10;
constexpr double kGridFloorHalfSize = 16.0;  // render_bench's floor under the grid

struct Resolution {
  std::uint32_t width = 0, height = 0;
};

struct Settings {
  std::vector<Resolution> resolutions{{1024, 768}, {1920, 1080}};
  std::uint64_t grid_triangles = 1'000'000;
  std::string stage_sync = "auto";
};

// A scene as `shadowcert edges` draws it: in the eye's frame, the camera's near plane fitted.
struct BenchScene {
  std::string name;
  Scene scene;
  std::vector<gpu::ShadedSoupPart> parts;
  std::size_t triangles = 0;
};

SceneMesh scene_mesh(std::string name, Soup soup) {
  SceneMesh mesh;
  mesh.name = std::move(name);
  mesh.soup = std::move(soup);
  return mesh;
}

std::unique_ptr<BenchScene> finish(std::string name, Scene scene) {
  auto s = std::make_unique<BenchScene>();
  s->name = std::move(name);
  scene.camera = camera_fitted_to(scene);
  s->scene = eye_relative_scene(scene);
  s->parts = shaded_parts(s->scene);
  for (const SceneMesh& m : s->scene.meshes) s->triangles += m.soup.triangles.size();
  return s;
}

std::unique_ptr<BenchScene> creases_scene() {
  return finish("creases", load_scene_or_mesh(std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/edges_creases.json"));
}

std::unique_ptr<BenchScene> grid_scene(std::uint64_t triangles) {
  Scene scene;
  scene.meshes.push_back(scene_mesh("grid", sphere_grid(triangles)));
  scene.meshes.push_back(scene_mesh("floor", floor_quad(kGridFloorHalfSize)));
  scene.lights = {Light{{4.0, 30.0, 8.0, 1.0}}};
  scene.camera.eye = {0.0, 24.0, 32.0};
  scene.camera.target = {0.0, 0.0, 0.0};
  scene.camera.fov_y_degrees = 45.0;
  return finish(fmt::format("grid{}", triangles), std::move(scene));
}

// ogre.obj over a floor just below it, seen from the front and above (exact_image_bench's view).
std::unique_ptr<BenchScene> ogre_scene() {
  const std::filesystem::path file = std::filesystem::path(SHADOWCERT_SHARED_DATA) / "soups" / "ogre.obj";
  if (!std::filesystem::exists(file)) return nullptr;
  Soup mesh = read_soup(file);
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  const Vec3 c{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  Soup floor = floor_quad(1.5 * size);
  floor.normals.clear();
  for (Vec3& v : floor.vertices) v = {v[0] + c[0], lo[1] - 0.01 * size, v[2] + c[2]};
  Scene scene;
  scene.meshes.push_back(scene_mesh("floor", std::move(floor)));
  scene.meshes.push_back(scene_mesh("ogre", std::move(mesh)));
  scene.lights = {Light{{c[0] + 0.4 * size, c[1] + 2.0 * size, c[2] + 0.6 * size, 1.0}}};
  scene.camera.eye = {c[0], c[1] + 0.8 * size, c[2] + 1.6 * size};
  scene.camera.target = c;
  return finish("ogre", std::move(scene));
}

struct Variant {
  std::string name;
  gpu::EdgeFilter filter = gpu::EdgeFilter::diagonal;
  bool c1_three_passes = false;
  gpu::EdgeStyle style = gpu::EdgeStyle::gooch;
};

void run_frames(benchmark::State& state, const BenchScene& s, const Variant& v, Resolution r, gpu::StageSync sync) {
  Camera camera = s.scene.camera;
  camera.width = r.width;
  camera.height = r.height;
  gpu::EdgeMapRenderer edges(s.parts, gpu::EdgeMapOptions{v.c1_three_passes});
  gpu::EdgeStyleRenderer style;
  const gpu::OffscreenTarget target(r.width, r.height);
  gpu::EdgeStyleOptions options;
  options.profile_threshold = gpu::profile_threshold(v.filter, gpu::kDefaultEdgeDepthStep);
  options.inner_threshold = gpu::inner_threshold(v.filter, gpu::kDefaultEdgeCreaseAngleDegrees);
  options.light = s.scene.lights.front();
  const auto frame = [&](gpu::GpuStageTimer* timer) {
    const auto start = Clock::now();
    if (timer != nullptr) timer->begin_frame();
    edges.draw(r.width, r.height, camera, v.filter, timer);
    style.draw(target, edges, camera, v.style, options, timer);
    if (timer != nullptr) timer->end_frame();
    glFinish();
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  };
  (void)frame(nullptr);  // warm-up: shader variants, the textures at this size
  gpu::GpuStageTimer timer(sync);
  std::vector<double> wall_ms;
  for (auto _ : state) {
    const double ms = frame(&timer);
    state.SetIterationTime(ms / 1000.0);
    wall_ms.push_back(ms);
  }
  const gpu::FrameTiming t = gpu::summarize_frames(gpu::kEdgeStages, sync, timer.collect(), wall_ms);
  for (gpu::RenderStage stage : t.stages)
    state.counters[std::string(gpu::render_stage_name(stage)) + "_ms"] =
        sync == gpu::StageSync::finish ? t.wall(stage).median_ms : t.gpu(stage).median_ms;
  state.counters["frame_ms"] = t.frame_cpu.median_ms;
  state.counters["gpu_frame_ms"] = t.frame_gpu.median_ms;
  state.counters["tris"] = static_cast<double>(s.triangles);
}

// Parses and removes this program's own flags (Google Benchmark rejects flags it does not know).
Settings take_settings(int& argc, char** argv) {
  Settings settings;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const auto value = [&](std::string_view flag) { return bench::flag_value(arg, flag); };
    if (const auto list = value("--resolutions=")) {
      settings.resolutions.clear();
      for (std::size_t begin = 0; begin <= list->size();) {
        const std::size_t end = std::min(list->find(',', begin), list->size());
        const auto [width, height] = bench::image_size(list->substr(begin, end - begin), "--resolutions");
        settings.resolutions.push_back({width, height});
        begin = end + 1;
      }
    } else if (const auto triangles = value("--triangles=")) {
      settings.grid_triangles = bench::count_list(*triangles).front();
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
  if (!bench::take_command_line("edge_map_bench", argc, argv, settings, take_settings)) return 2;

  const std::optional<gpu::EglContext> context = bench::open_bench_context("edge_map_bench");
  if (!context) return 2;
  const gpu::StageSync sync = bench::chosen_stage_sync(settings.stage_sync, *context);
  bench::add_gl_context(*context, sync, "passes");

  // Scenes are built once (the grid and the ogre take seconds) and live until the end.
  std::vector<std::unique_ptr<BenchScene>> scenes;
  scenes.push_back(creases_scene());
  scenes.push_back(grid_scene(settings.grid_triangles));
  if (auto ogre = ogre_scene()) scenes.push_back(std::move(ogre));
  else std::cerr << "edge_map_bench: ../shared/data/soups/ogre.obj absent: the ogre scene is skipped\n";

  const std::vector<Variant> filters{{"diagonal", gpu::EdgeFilter::diagonal},
                                     {"c1", gpu::EdgeFilter::c1},
                                     {"c1x3", gpu::EdgeFilter::c1, true},
                                     {"sobel", gpu::EdgeFilter::sobel}};
  const std::vector<Variant> styles{{"edges", gpu::EdgeFilter::diagonal, false, gpu::EdgeStyle::edges},
                                    {"toon", gpu::EdgeFilter::diagonal, false, gpu::EdgeStyle::toon}};
  for (const auto& scene : scenes) {
    for (const Resolution r : settings.resolutions) {
      const auto add = [&](const std::string& kind, const Variant& v) {
        const BenchScene* s = scene.get();
        benchmark::RegisterBenchmark(fmt::format("{}/{}/{}/{}x{}", kind, s->name, v.name, r.width, r.height).c_str(),
                                     [s, v, r, sync](benchmark::State& state) {
                                       try {
                                         run_frames(state, *s, v, r, sync);
                                       } catch (const std::exception& e) {
                                         state.SkipWithError(e.what());
                                       }
                                     })
            ->Iterations(kFrames)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
      };
      for (const Variant& v : filters) add("edges", v);
      for (const Variant& v : styles) add("style", v);
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
