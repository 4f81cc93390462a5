// Smooth silhouettes pixel by pixel (docs/smooth-silhouettes.md, "Per-pixel error against the
// analytic shadow"): each method's GL frame against the analytic shadow of the ellipsoid its
// caster approximates (pipeline/analytic_comparison.h), with the GL time per frame; and, on the
// real meshes of ../shared/data/, each method against the polyhedral exact image (what `diff`
// computes), with the qualification and the time per frame. Needs EGL (llvmpipe will do).
//
//   analytic_shadow_bench [--resolution=1024x768] [--mesh-resolution=512x384] [Google Benchmark flags]
//   analytic_shadow_bench --benchmark_filter='^pixels/'     # the per-pixel table
//   analytic_shadow_bench --benchmark_filter='^offset/'     # the cap offset against self-shadowing
//   analytic_shadow_bench --benchmark_filter='^mesh/'       # the real meshes
//
//   pixels/METHOD/SHAPE/LIGHT   discrete, accurate and smooth at eps in {0.1, 0.03, 0.01, 0.003}
//       (caster radius 1 at the origin, the floor y = -1.5 receiving only), on uv spheres from
//       8x4 to 256x128 and an ellipsoid (bench/smooth_silhouette_bench.cpp's shapes, lights
//       and floor), under the point light (1.2, 4, 0.8) and the sun towards (0.3, 1, 0.2).
//       The volume is pipeline/silhouette_volumes.h's (what `render` and `diff` draw: the scene
//       in the eye's frame, rounded to float, cut caps behind the surface by the depth band).
//       Counters: recv_dis, recv_agree, recv_amb (floor pixels), self_dis, self_agree, self_band,
//       self_amb (the caster's own pixels, against the interpolated-normal terminator), build_ms
//       (the volume, CPU, one build), vol_tris. Time: GL ms per frame (manual time, wall
//       clock, glFinish; the first frame, with its readback, is untimed).
//   offset/METHOD/OFFSET/SHAPE/LIGHT   accurate and smooth(0.01) with the cut caps on the surface
//       (0), behind it by the depth band (band, what GL draws), and by the paper's 0.15: the
//       same counters.
//   mesh/NAME   discrete, accurate and smooth(0.01) in one `diff` comparison
//       (pipeline/scene_comparison.h) of the mesh over a floor, framed as the SharedMeshDiff
//       tests frame it. Counters: METHOD_dis (pixels where the method's lit mask disagrees
//       with the polyhedral exact image: its hard errors), METHOD_agree, ambiguous, METHOD_ms
//       (GL ms per frame), qualified (1: the mesh is cast by the methods; 0: it falls back to
//       the robust chain, the label says why), tris. Skipped when the file is absent.
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "contour/smooth_caster.h"
#include "contour/smooth_volume.h"
#include "core/eye_frame.h"
#include "core/float_rounding.h"
#include "core/near_plane.h"
#include "core/vector3.h"
#include "exact/light_orientation.h"
#include "gpu/depth_precision.h"
#include "gpu/egl_context.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method_renderer.h"
#include "io/soup_file.h"
#include "pipeline/analytic_comparison.h"
#include "pipeline/mesh_palette.h"
#include "pipeline/method_inputs.h"
#include "pipeline/scene_comparison.h"
#include "pipeline/silhouette_volumes.h"
#include "scene/framed_scene.h"
#include "scene/merged_soup.h"

#include "gl_bench_main.h"

namespace {

using namespace shadowcert;
using Clock = std::chrono::steady_clock;

// The analytic scenes' lights (scene/framed_scene.h).
const Light kPointLight = kAnalyticPointLight;
const Light kSun = kAnalyticSun;
// The paper's offset of the caps along -n (Mattausch et al. 2012, §5), for a caster of unit size.
constexpr double kPaperCapOffset = 0.15;
// GL frames timed per benchmark after the untimed compared one.
constexpr benchmark::IterationCount kFrames = 5;

struct Settings {
  std::uint32_t width = 1024, height = 768;            // pixels/ and offset/
  std::uint32_t mesh_width = 512, mesh_height = 384;  // mesh/
};
Settings g_settings;

// The casters of the analytic error (scene/framed_scene.h): uv spheres 8x4 to 256x128 and the
// ellipsoid, the shapes of bench/smooth_silhouette_bench.cpp.
using Shape = AnalyticShape;

// One shape under one light: the scene, as GL gets it, and the analytic truth. One at a time.
struct Case {
  std::string key;
  Scene scene;  // world space
  Scene drawn;  // the eye's frame (core/eye_frame.h)
  std::vector<gpu::ShadedSoupPart> parts;
  MethodInputs inputs;
  AnalyticShadowImage truth;
};

// The shape over the floor y = -1.5 (receiving only), seen so that the shadow and the caster's
// terminator side are in view (scene/framed_scene.h's analytic_shape_scene).
Scene shape_scene(const Shape& shape, const Light& light) {
  return analytic_shape_scene(shape, light, g_settings.width, g_settings.height);
}

Case& case_for(const Shape& shape, std::string_view light_name, const Light& light) {
  static std::unique_ptr<Case> current;
  const std::string key = shape.name + "/" + std::string(light_name);
  if (current && current->key == key) return *current;
  current.reset();
  auto c = std::make_unique<Case>();
  c->key = key;
  c->scene = shape_scene(shape, light);
  c->drawn = eye_relative_scene(c->scene);
  c->parts = shaded_parts(c->drawn);
  const std::array methods{gpu::ShadowMethod::smooth};
  c->inputs = prepare_method_inputs(merged_casters(c->drawn), c->drawn.lights, methods);
  c->truth = analytic_reference(c->scene);
  current = std::move(c);
  return *current;
}

// The caster's volume as silhouette_volumes builds it, but with the cut caps `offset` behind
// the surface (a negative offset: the depth band, as silhouette_volumes sets it).
HomogeneousMesh volume_with_offset(const Case& c, SilhouetteMethod method, double epsilon, double offset) {
  const SceneMesh& mesh = c.drawn.meshes[1];
  const SmoothCasterResult caster = smooth_caster(float_rounded(mesh.soup));
  if (!caster.caster) throw std::runtime_error(mesh.name + ": " + caster.qualification.summary());
  if (offset < 0.0) {
    double farthest = 0.0;
    for (const Vec3& v : caster.caster->vertices) farthest = std::max(farthest, std::sqrt(dot(v, v)));
    offset = gpu::depth_band(farthest, c.drawn.camera.near_plane);
  }
  return smooth_shadow_volume(*caster.caster, float_rounded(c.drawn.lights[0]), {method, epsilon, offset}).mesh;
}

// Renders `volume` for the case's light, compares the first frame with the truth and times
// kFrames more.
void measure(benchmark::State& state, Case& c, gpu::ShadowMethod method, const HomogeneousMesh& volume,
             double build_ms) {
  gpu::ShadowMethodOptions options;
  options.light_stencil.assign(1, gpu::StencilMethod::zfail);  // as compare_scene draws these
  gpu::ShadowMethodRenderer renderer(method, light_scene(c.inputs, c.parts, c.drawn.lights, 0, &volume), options);
  const gpu::OffscreenTarget target(c.drawn.camera.width, c.drawn.camera.height);
  const AnalyticCounts a = compare_analytic(c.truth, 0, renderer.render(target, c.drawn.camera));
  for (auto _ : state) state.SetIterationTime(renderer.render_frames(target, c.drawn.camera, 1).front() / 1000.0);
  state.counters["recv_dis"] = static_cast<double>(a.receiver_disagree);
  state.counters["recv_agree"] = static_cast<double>(a.receiver_agree);
  state.counters["recv_amb"] = static_cast<double>(a.receiver_ambiguous);
  state.counters["self_dis"] = static_cast<double>(a.caster_disagree);
  state.counters["self_agree"] = static_cast<double>(a.caster_agree);
  state.counters["self_band"] = static_cast<double>(a.caster_band);
  state.counters["self_amb"] = static_cast<double>(a.caster_ambiguous);
  state.counters["build_ms"] = build_ms;
  state.counters["vol_tris"] = static_cast<double>(volume.triangles.size());
}

void run_pixels(benchmark::State& state, const Shape& shape, std::string_view light_name, const Light& light,
                gpu::ShadowMethod method, double epsilon) {
  Case& c = case_for(shape, light_name, light);
  SilhouetteOptions options;
  options.epsilon = epsilon;
  options.near_plane = c.drawn.camera.near_plane;
  const auto start = Clock::now();
  const SilhouetteVolumes volumes = silhouette_volumes(c.drawn.meshes, c.drawn.lights, method, options);
  const double build_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  measure(state, c, method, volumes.per_light[0], build_ms);
  state.counters["truth_s"] = c.truth.seconds;
}

void run_offset(benchmark::State& state, const Shape& shape, std::string_view light_name, const Light& light,
                gpu::ShadowMethod method, double offset) {
  Case& c = case_for(shape, light_name, light);
  const SilhouetteMethod kind = method == gpu::ShadowMethod::accurate ? SilhouetteMethod::accurate : SilhouetteMethod::smooth;
  const auto start = Clock::now();
  const HomogeneousMesh volume = volume_with_offset(c, kind, kDefaultContourEpsilon, offset);
  measure(state, c, method, volume, std::chrono::duration<double, std::milli>(Clock::now() - start).count());
}

// A shared mesh framed over a floor that only receives (scene/framed_scene.h's rule, which the
// SharedMeshDiff tests and `shadowcert bench --suite real` use).
Scene shared_mesh_scene(const Soup& mesh, const std::string& name) {
  FramedMeshOptions options;
  options.width = g_settings.mesh_width;
  options.height = g_settings.mesh_height;
  return framed_mesh_scene(mesh, name, options);
}

void run_mesh(benchmark::State& state, const std::string& relative) {
  const std::filesystem::path file = std::filesystem::path(SHADOWCERT_SHARED_DATA) / relative;
  if (!std::filesystem::exists(file)) {
    state.SkipWithError((file.string() + " is not here (../shared/data/ is a dev checkout's)").c_str());
    return;
  }
  const Scene scene = shared_mesh_scene(read_soup(file), relative);
  SceneComparisonOptions options;
  options.timed_frames = kFrames;
  const std::vector<gpu::ShadowMethod> methods{gpu::ShadowMethod::discrete, gpu::ShadowMethod::accurate,
                                               gpu::ShadowMethod::smooth};
  std::optional<SceneComparison> c;
  for (auto _ : state) c = compare_scene(scene, methods, options);
  for (const MethodRun& run : c->runs) {
    const std::string name(gpu::shadow_method_name(run.method));
    state.counters[name + "_dis"] = static_cast<double>(run.sum(&PixelComparison::hard_errors));
    state.counters[name + "_agree"] = static_cast<double>(run.sum(&PixelComparison::agree));
    state.counters[name + "_ms"] = run.gl_ms();
    state.counters["ambiguous"] = static_cast<double>(run.sum(&PixelComparison::ambiguous));
  }
  const SilhouetteCaster& caster = c->silhouettes.front().casters.front();
  state.counters["qualified"] = caster.cast_by ? 1.0 : 0.0;
  state.counters["tris"] = static_cast<double>(caster.triangles);
  state.SetLabel(caster.cast_by ? "qualifies" : caster.qualification);
}

void register_benchmarks() {
  struct Method {
    std::string name;
    gpu::ShadowMethod method;
    double epsilon;
  };
  const std::vector<Method> methods{{"discrete", gpu::ShadowMethod::discrete, kDefaultContourEpsilon},
                                    {"accurate", gpu::ShadowMethod::accurate, kDefaultContourEpsilon},
                                    {"smooth0.1", gpu::ShadowMethod::smooth, 0.1},
                                    {"smooth0.03", gpu::ShadowMethod::smooth, 0.03},
                                    {"smooth0.01", gpu::ShadowMethod::smooth, 0.01},
                                    {"smooth0.003", gpu::ShadowMethod::smooth, 0.003}};
  const std::vector<Shape> all = analytic_shapes();
  // Light-major, then shape: one analytic image per (light, shape).
  for (const auto& [light_name, light] : {std::pair{"point", kPointLight}, {"sun", kSun}})
    for (const Shape& shape : all)
      for (const Method& m : methods)
        benchmark::RegisterBenchmark(("pixels/" + m.name + "/" + shape.name + "/" + light_name).c_str(), run_pixels,
                                     shape, std::string_view(light_name), light, m.method, m.epsilon)
            ->Iterations(kFrames)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
  const std::vector<std::pair<std::string, double>> offsets{{"0", 0.0}, {"band", -1.0}, {"0.15", kPaperCapOffset}};
  for (const auto& [light_name, light] : {std::pair{"point", kPointLight}, {"sun", kSun}})
    for (const Shape& shape : all) {
      if (shape.name != "sphere12x6" && shape.name != "sphere32x16" && shape.name != "sphere128x64" &&
          shape.name != "ellipsoid32x16")
        continue;
      for (gpu::ShadowMethod method : {gpu::ShadowMethod::accurate, gpu::ShadowMethod::smooth})
        for (const auto& [offset_name, offset] : offsets)
          benchmark::RegisterBenchmark(("offset/" + std::string(gpu::shadow_method_name(method)) + "/" + offset_name +
                                        "/" + shape.name + "/" + light_name)
                                           .c_str(),
                                       run_offset, shape, std::string_view(light_name), light, method, offset)
              ->Iterations(kFrames)
              ->UseManualTime()
              ->Unit(benchmark::kMillisecond);
    }
  for (const std::string mesh : {"closed_manifold/spot.obj", "closed_manifold/nefertiti.obj", "soups/stanford-bunny.obj",
                                 "soups/trimesh_bunny.ply", "closed_manifold/thingi10k_65004.stl",
                                 "edge_cases/trimesh_featuretype.STL"}) {
    const std::string short_name = std::filesystem::path(mesh).stem().string();
    benchmark::RegisterBenchmark(("mesh/" + short_name).c_str(), run_mesh, mesh)
        ->Iterations(1)
        ->Unit(benchmark::kSecond);
  }
}

// Parses and removes this program's own flags (Google Benchmark rejects flags it does not know).
void take_settings(int& argc, char** argv) {
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (const auto size = bench::flag_value(arg, "--resolution=")) {
      const auto [width, height] = bench::image_size(*size, "--resolution");
      g_settings.width = width;
      g_settings.height = height;
    } else if (const auto mesh_size = bench::flag_value(arg, "--mesh-resolution=")) {
      const auto [width, height] = bench::image_size(*mesh_size, "--mesh-resolution");
      g_settings.mesh_width = width;
      g_settings.mesh_height = height;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
}

}  // namespace

int main(int argc, char** argv) {
  if (!bench::take_command_line("analytic_shadow_bench", argc, argv, take_settings)) return 2;
  const std::optional<gpu::EglContext> context = bench::open_bench_context("analytic_shadow_bench");
  if (!context) return 2;
  benchmark::AddCustomContext("renderer", context->renderer());
  benchmark::AddCustomContext("resolution", fmt::format("{}x{}", g_settings.width, g_settings.height));
  benchmark::AddCustomContext("mesh_resolution", fmt::format("{}x{}", g_settings.mesh_width, g_settings.mesh_height));
  register_benchmarks();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
