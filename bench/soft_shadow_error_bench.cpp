// The soft-shadow error table (docs/smoothies.md#the-error-table): how fake the shadow map
// family's soft shadows are against the exact soft reference (pipeline/soft_reference.h), and
// what each costs per frame.
//
//   error/METHOD                 one frame of METHOD on data/scenes/soft_contact.json at
//                                --resolution (default 640x480) against the reference of a disk
//                                light of radius --light-radius (default 0.25) with 64 samples:
//                                the exact hard shadow (cpu), the hard shadow map at 512 to 4096,
//                                PCF 3, 5, 9 and PCSS at 2048, smoothies of width R/4 (matched:
//                                below), R/2 and R in both spaces. Counters (pipeline/
//                                soft_shadow_comparison.h): mean_err, max_err, umbra_err,
//                                penumbra_err, outside_err, signed_err, leaks / contact, acne /
//                                lit; ms: the mean wall ms of 5 frames without readback.
//   flicker/METHOD               the same methods over a light orbit of 8 frames (the light
//                                moved 0.5 around its place, 45 degrees a frame, at 320x240):
//                                method_change and reference_change (mean |change of light| per
//                                pixel between frames), excess = their difference, change_err =
//                                mean |method's change - reference's change|.
//
//   soft_shadow_error_bench [--resolution=WxH] [--light-radius=R] [Google Benchmark flags]
//
// A smoothie "matched" to R: a caster edge at distance b from the light over a receiver at r
// casts an outer half-penumbra R (r - b) / b wide, and a smoothie D wide at b projects to
// D r / b, so D = R (r - b) / r; on this scene the casters stand about 1 above a floor the light
// is 4 above: D = R / 4.
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/eye_frame.h"
#include "core/scene.h"
#include "gpu/egl_context.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_map_renderer.h"
#include "gpu/shadow_method_renderer.h"
#include "io/scene_input.h"
#include "pipeline/mesh_palette.h"
#include "pipeline/method_inputs.h"
#include "pipeline/soft_reference.h"
#include "pipeline/soft_shadow_comparison.h"
#include "scene/merged_soup.h"

#include "gl_bench_main.h"

namespace {

using namespace shadowcert;

constexpr std::uint32_t kSamples = 64;
constexpr std::size_t kTimedFrames = 5;
constexpr std::size_t kOrbitFrames = 8;
constexpr double kOrbitRadius = 0.5;
constexpr std::uint32_t kOrbitWidth = 320, kOrbitHeight = 240;

struct Settings {
  std::uint32_t width = 640;
  std::uint32_t height = 480;
  double light_radius = 0.25;
};

struct Config {
  std::string name;
  gpu::ShadowMethod method = gpu::ShadowMethod::shadowmap;
  std::uint32_t map_size = gpu::kDefaultShadowMapSize;
  std::uint32_t pcf_kernel = gpu::kDefaultPcfKernel;
  double smoothie_width_in_r = 0.0;  // smoothie: D / R
  SmoothieSpace space = SmoothieSpace::world;
};

Scene contact_scene(std::uint32_t width, std::uint32_t height) {
  Scene scene = load_scene_or_mesh(std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/soft_contact.json");
  scene.camera.width = width;
  scene.camera.height = height;
  return scene;
}

// One frame of `config` on the scene's first light, read back, and the mean wall ms of timed
// frames after it when `timed` is not 0.
std::vector<float> render_light(const Scene& scene, const Config& config, double light_radius, std::size_t timed,
                                double* ms) {
  const Scene drawn = eye_relative_scene(scene);
  const std::array methods{config.method};
  MethodInputs inputs = prepare_method_inputs(merged_casters(drawn), drawn.lights, methods);
  if (config.method == gpu::ShadowMethod::smoothie) {
    SceneSmoothieOptions smoothie;
    smoothie.width = config.smoothie_width_in_r * light_radius;
    smoothie.space = config.space;
    add_smoothies(inputs, drawn.lights, gpu::soup_bounds(merged_soup(drawn)), smoothie);
  }
  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(drawn);
  gpu::ShadowMethodOptions options;
  options.shadow_map_size = config.map_size;
  options.pcf_kernel = config.pcf_kernel;
  options.light_radius = light_radius;
  gpu::ShadowMethodRenderer renderer(config.method, light_scene(inputs, parts, drawn.lights, 0), options);
  const gpu::OffscreenTarget target(drawn.camera.width, drawn.camera.height);
  const gpu::StencilShadowFrame frame = renderer.render(target, drawn.camera);
  if (timed > 0 && ms != nullptr) {
    const std::vector<double> wall = renderer.render_frames(target, drawn.camera, timed);
    double sum = 0.0;
    for (double x : wall) sum += x;
    *ms = sum / static_cast<double>(wall.size());
  }
  return frame.first_light;
}

const SoftReference& table_reference(const Settings& s) {
  static std::unique_ptr<SoftReference> reference;
  if (!reference)
    reference = std::make_unique<SoftReference>(
        soft_reference(contact_scene(s.width, s.height), 0, {{s.light_radius, kSamples, 1}}));
  return *reference;
}

void run_error(benchmark::State& state, const Config& config, const Settings& s) {
  const SoftReference& reference = table_reference(s);
  const Scene scene = contact_scene(s.width, s.height);
  std::vector<float> light;
  double ms = 0.0;
  for (auto _ : state) light = render_light(scene, config, s.light_radius, kTimedFrames, &ms);
  const SoftShadowErrors e = compare_soft_shadow(reference, light);
  state.counters["mean_err"] = e.mean_error;
  state.counters["max_err"] = e.max_error;
  state.counters["umbra_err"] = e.umbra_mean_error;
  state.counters["penumbra_err"] = e.penumbra_mean_error;
  state.counters["outside_err"] = e.outside_penumbra_mean_error;
  state.counters["signed_err"] = e.mean_signed_error;
  state.counters["leaks"] = static_cast<double>(e.leaks);
  state.counters["contact"] = static_cast<double>(e.contact);
  state.counters["acne"] = static_cast<double>(e.acne);
  state.counters["lit"] = static_cast<double>(e.lit_facing);
  state.counters["ms"] = ms;
}

// The orbit's scenes: the light moved around its place, one scene per frame.
std::vector<Scene> orbit_scenes() {
  std::vector<Scene> scenes;
  const Scene base = contact_scene(kOrbitWidth, kOrbitHeight);
  for (std::size_t f = 0; f < kOrbitFrames; ++f) {
    Scene s = base;
    const double angle = 2.0 * M_PI * static_cast<double>(f) / static_cast<double>(kOrbitFrames);
    s.lights.front().position[0] += kOrbitRadius * std::cos(angle);
    s.lights.front().position[2] += kOrbitRadius * std::sin(angle);
    scenes.push_back(std::move(s));
  }
  return scenes;
}

const std::vector<SoftShadowImage>& orbit_references(const Settings& s) {
  static std::unique_ptr<std::vector<SoftShadowImage>> references;
  if (!references) {
    references = std::make_unique<std::vector<SoftShadowImage>>();
    for (const Scene& scene : orbit_scenes())
      references->push_back(soft_reference(scene, 0, {{s.light_radius, kSamples, 1}}).image);
  }
  return *references;
}

void run_flicker(benchmark::State& state, const Config& config, const Settings& s) {
  const std::vector<SoftShadowImage>& references = orbit_references(s);
  std::vector<std::vector<float>> frames;
  for (auto _ : state) {
    frames.clear();
    for (const Scene& scene : orbit_scenes()) frames.push_back(render_light(scene, config, s.light_radius, 0, nullptr));
  }
  const SoftFlicker f = soft_flicker(references, frames);
  state.counters["method_change"] = f.method_change;
  state.counters["reference_change"] = f.reference_change;
  state.counters["excess"] = f.excess;
  state.counters["change_err"] = f.change_error;
}

std::vector<Config> configs() {
  using gpu::ShadowMethod;
  std::vector<Config> c{{"cpu", ShadowMethod::cpu}};
  for (std::uint32_t size : {512u, 1024u, 2048u, 4096u})
    c.push_back({fmt::format("shadowmap{}", size), ShadowMethod::shadowmap, size});
  for (std::uint32_t k : {3u, 5u, 9u}) c.push_back({fmt::format("pcf{}", k), ShadowMethod::pcf, 2048, k});
  c.push_back({"pcss", ShadowMethod::pcss});
  for (const auto& [space, space_name] : {std::pair{SmoothieSpace::world, "world"}, {SmoothieSpace::light, "light"}})
    for (const auto& [d, d_name] : {std::pair{0.25, "R/4"}, {0.5, "R/2"}, {1.0, "R"}})
      c.push_back({fmt::format("smoothie-{}-{}", space_name, d_name), ShadowMethod::smoothie, 2048, 3, d, space});
  return c;
}

Settings take_settings(int& argc, char** argv) {
  Settings settings;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const auto value = [&](std::string_view flag) { return bench::flag_value(arg, flag); };
    if (const auto size = value("--resolution=")) {
      const auto [width, height] = bench::image_size(*size, "--resolution");
      settings.width = width;
      settings.height = height;
    } else if (const auto r = value("--light-radius=")) {
      settings.light_radius = std::stod(*r);
      if (!(settings.light_radius > 0.0) || !std::isfinite(settings.light_radius))
        throw std::invalid_argument("--light-radius expects a finite R > 0");
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
  if (!bench::take_command_line("soft_shadow_error_bench", argc, argv, settings, take_settings)) return 2;
  const std::optional<gpu::EglContext> context = bench::open_bench_context("soft_shadow_error_bench");
  if (!context) return 2;
  benchmark::AddCustomContext("renderer", context->renderer());
  benchmark::AddCustomContext("resolution", fmt::format("{}x{}", settings.width, settings.height));
  benchmark::AddCustomContext("light_radius", fmt::format("{}", settings.light_radius));
  for (const Config& c : configs()) {
    benchmark::RegisterBenchmark(("error/" + c.name).c_str(),
                                 [c, &settings](benchmark::State& state) {
                                   try {
                                     run_error(state, c, settings);
                                   } catch (const std::exception& e) {
                                     state.SkipWithError(e.what());
                                   }
                                 })
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  }
  for (const Config& c : configs()) {
    benchmark::RegisterBenchmark(("flicker/" + c.name).c_str(),
                                 [c, &settings](benchmark::State& state) {
                                   try {
                                     run_flicker(state, c, settings);
                                   } catch (const std::exception& e) {
                                     state.SkipWithError(e.what());
                                   }
                                 })
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
