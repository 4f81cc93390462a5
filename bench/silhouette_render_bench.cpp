// Smooth silhouettes in GL (docs/smooth-silhouettes.md, "Speed and fill"): what building the
// smooth volume on the GPU costs, and what the smooth volume costs the rasteriser against the
// discrete one (the paper claims "only a small change to the fill rate").
//
//   build/gpu/TRIANGLES        smooth-gpu's build (gpu/smooth_silhouette_volume.h) at eps =
//                              0.01 on a uv sphere of unit radius with about TRIANGLES triangles,
//                              one point light; each iteration is one build: the two dispatches,
//                              the 4-byte readback of the vertices asked for, glFinish.
//   build/cpu/TRIANGLES        the same volume built by contour/ on one core (loops, contour,
//                              caps, strip, sides, back cap: what `smooth` uploads).
//   render/METHOD/SCENE        ms per frame (wall, glFinish) of discrete, accurate, smooth and
//                              smooth-gpu at --resolution (default 1024x768), on
//                              data/scenes/smooth_sphere.json (a 12x6 sphere over a floor) and a
//                              100K-triangle sphere over a floor. Counters: vol_tris, and the
//                              first light's volume fill (StencilShadowFrame): frags (fragments
//                              rasterised) and updates (those that change the stencil).
//
//   silhouette_render_bench [--resolution=WxH] [Google Benchmark flags]
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contour/smooth_volume.h"
#include "core/eye_frame.h"
#include "core/scene.h"
#include "gpu/egl_context.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method_renderer.h"
#include "gpu/smooth_silhouette_volume.h"
#include "io/scene_input.h"
#include "pipeline/mesh_palette.h"
#include "pipeline/method_inputs.h"
#include "pipeline/silhouette_volumes.h"
#include "pipeline/smooth_caster_arrays.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

#include "gl_bench_main.h"

namespace {

using namespace shadowcert;

const Light kPointLight{{1.2, 4.0, 0.8, 1.0}};
constexpr double kEpsilon = 0.01;
// Frames per render benchmark, after one untimed frame (llvmpipe compiles shader variants on
// first use).
constexpr benchmark::IterationCount kFrames = 10;

struct Settings {
  std::uint32_t width = 1024;
  std::uint32_t height = 768;
};

// A uv sphere of unit radius with about `triangles` triangles (2 s (s / 2 - 1), s slices).
Soup sphere_of(std::uint64_t triangles) {
  std::uint32_t slices = 4;
  while (2ull * (slices + 2) * ((slices + 2) / 2 - 1) <= triangles) slices += 2;
  return uv_sphere({0, 0, 0}, 1.0, slices, slices / 2);
}

void run_gpu_build(benchmark::State& state, std::uint64_t triangles) {
  const SmoothCaster caster = *smooth_caster(sphere_of(triangles)).caster;
  gpu::SmoothCasterArrays arrays;
  append_smooth_caster(arrays, caster, kEpsilon, 0.0);
  const gpu::SmoothCasterBuffers buffers(arrays);
  gpu::SmoothSilhouetteVolume volume(buffers);
  volume.build(kPointLight);  // warm-up: the shader's first use, and the buffer's growth
  for (auto _ : state) {
    volume.build(kPointLight);
    glFinish();
  }
  state.counters["tris"] = static_cast<double>(caster.triangles.size());
  state.counters["vol_tris"] = static_cast<double>(volume.read_requested_vertices() / 3);
}

void run_cpu_build(benchmark::State& state, std::uint64_t triangles) {
  const SmoothCaster caster = *smooth_caster(sphere_of(triangles)).caster;
  SmoothVolume volume;
  for (auto _ : state) {
    volume = smooth_shadow_volume(caster, kPointLight, {SilhouetteMethod::smooth, kEpsilon});
    benchmark::DoNotOptimize(volume.mesh.triangles.data());
  }
  state.counters["tris"] = static_cast<double>(caster.triangles.size());
  state.counters["vol_tris"] = static_cast<double>(volume.mesh.triangles.size());
}

Scene bundled_smooth_sphere() {
  return load_scene_or_mesh(std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/smooth_sphere.json");
}

// A 100K-triangle unit sphere over a floor, framed as smooth_sphere.json is.
Scene fine_sphere_scene() {
  Scene scene = bundled_smooth_sphere();
  for (SceneMesh& mesh : scene.meshes)
    if (mesh.name == "sphere") {
      Soup fine = sphere_of(100'000);
      const Vec3 centre = mesh.ellipsoid ? mesh.ellipsoid->centre : Vec3{0, 0, 0};
      for (Vec3& v : fine.vertices)
        for (std::size_t k = 0; k < 3; ++k) v[k] += centre[k];
      mesh.soup = std::move(fine);
    }
  return scene;
}

void run_render(benchmark::State& state, gpu::ShadowMethod method, Scene scene, const Settings& settings) {
  scene.camera.width = settings.width;
  scene.camera.height = settings.height;
  const Scene drawn = eye_relative_scene(scene);
  const std::array methods{method};
  MethodInputs inputs = prepare_method_inputs(merged_casters(drawn), drawn.lights, methods);
  SilhouetteOptions options;
  options.near_plane = drawn.camera.near_plane;
  SilhouetteVolumes volumes = silhouette_volumes(drawn.meshes, drawn.lights, method, options);
  inputs.cpu_volumes = volumes.per_light;
  inputs.smooth_casters = volumes.gpu_casters;
  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(drawn);
  gpu::ShadowMethodOptions method_options;
  method_options.count_fragments = true;
  gpu::ShadowMethodRenderer renderer(method, method_scene(inputs, parts, drawn.lights), method_options);
  const gpu::OffscreenTarget target(drawn.camera.width, drawn.camera.height);
  const gpu::StencilShadowFrame frame = renderer.render(target, drawn.camera);  // warm-up, and the fill
  renderer.check_capacity();
  for (auto _ : state) {
    const double ms = renderer.render_frames(target, drawn.camera, 1).front();
    state.SetIterationTime(ms / 1000.0);
  }
  state.counters["vol_tris"] = static_cast<double>(renderer.volume_triangles());
  state.counters["frags"] = static_cast<double>(frame.first_volume_fragments);
  state.counters["updates"] = static_cast<double>(frame.first_stencil_updates);
}

// Parses and removes this program's own flags (Google Benchmark rejects flags it does not know).
Settings take_settings(int& argc, char** argv) {
  Settings settings;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (const auto size = bench::flag_value(arg, "--resolution=")) {
      const auto [width, height] = bench::image_size(*size, "--resolution", "1920x1080");
      settings.width = width;
      settings.height = height;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  return settings;
}

template <class Run, class... Args>
void add(const std::string& name, Run run, benchmark::IterationCount iterations, bool manual_time, Args... args) {
  auto* b = benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
    try {
      run(state, args...);
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
    }
  });
  b->Iterations(iterations)->Unit(benchmark::kMillisecond);
  if (manual_time) b->UseManualTime();
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  if (!bench::take_command_line("silhouette_render_bench", argc, argv, settings, take_settings)) return 2;
  const std::optional<gpu::EglContext> context = bench::open_bench_context("silhouette_render_bench");
  if (!context) return 2;
  benchmark::AddCustomContext("renderer", context->renderer());
  benchmark::AddCustomContext("resolution", fmt::format("{}x{}", settings.width, settings.height));

  for (std::uint64_t triangles : {100'000ull, 400'000ull}) {
    add(fmt::format("build/gpu/{}", triangles), run_gpu_build, 20, false, triangles);
    add(fmt::format("build/cpu/{}", triangles), run_cpu_build, 10, false, triangles);
  }
  const std::vector<std::pair<std::string, Scene>> scenes{{"smooth_sphere", bundled_smooth_sphere()},
                                                          {"sphere100k", fine_sphere_scene()}};
  for (const auto& [name, scene] : scenes)
    for (gpu::ShadowMethod method : gpu::kSilhouetteMethods)
      add(fmt::format("render/{}/{}", gpu::shadow_method_name(method), name), run_render, kFrames, true, method, scene,
          settings);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
