#pragma once
// `shadowcert bench` (docs/bench.md): every GL method, at each value of its swept
// parameter, on the scenes of a suite, each run's time and its error by the measure that fits it.
// The work per scene is compare_scene's (pipeline/scene_comparison.h): one exact image, the
// analytic truth when a smooth-silhouette run meets an ellipsoid caster, the exact soft
// reference when a shadow-map run is asked for, and per run and light the same frame and
// compare_light that `diff` uses; but each run gets its own method options (sign, map size,
// kernel, epsilon, smoothie width), its CPU build is timed, and its frames are timed by
// gpu/shadow_method_renderer.h's time_frames (stage medians, min and max over warm frames).
//
//   const std::vector<BenchVariant> variants = bench_variants();          // the whole matrix
//   for (const BenchSceneSpec& spec : bench_suite("default", paths))     // the scenes
//     BenchSceneResult r = bench_scene(load_bench_scene(spec, 160, 120), spec, variants, options);
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contour/smoothie.h"
#include "core/scene.h"
#include "gpu/edge_map.h"
#include "gpu/frame_timing.h"
#include "gpu/image.h"
#include "gpu/shadow_method_renderer.h"
#include "gpu/sign_mode.h"
#include "pipeline/contour_error.h"
#include "pipeline/edge_map_comparison.h"
#include "pipeline/scene_comparison.h"
#include "reference/ellipsoid_shadow.h"

namespace shadowcert {

// How a run's error is measured (docs/bench.md): stencil (cpu, cs, gs, ts, pertri: hard and
// ambiguous pixels, closure), silhouette (discrete, accurate, smooth, smooth-gpu: also against
// the analytic shadow and the conic), shadow_map (shadowmap, pcf, pcss, smoothie: also against
// the exact soft reference), edges (the edge-map filters of issue 14: precision and recall;
// no run yet, see bench_variants), ray_traced (rt, rt-robust: Embree on the CPU, hard and
// ambiguous pixels and the soft error, never a failure; docs/ray-tracing.md).
enum class BenchFamily { stencil, silhouette, shadow_map, edges, ray_traced };
[[nodiscard]] std::string_view bench_family_name(BenchFamily family);

// One method at one value of its swept parameter.
struct BenchVariant {
  std::string id;  // unique: "cpu", "cs/float", "shadowmap/1024", "pcf/5", "smooth/0.01", "smoothie/R/4"
  gpu::ShadowMethod method = gpu::ShadowMethod::cpu;
  BenchFamily family = BenchFamily::stencil;
  gpu::SignMode sign = gpu::SignMode::exact;                 // cs, gs, ts, pertri
  std::uint32_t shadow_map_size = gpu::kDefaultShadowMapSize;  // the shadow-map family
  std::uint32_t pcf_kernel = gpu::kDefaultPcfKernel;           // pcf
  double epsilon = kDefaultContourEpsilon;                     // smooth, smooth-gpu
  double smoothie_width_in_r = 0.0;                            // smoothie: D as a fraction of the light radius R
  SmoothieSpace smoothie_space = SmoothieSpace::world;         // smoothie
  gpu::EdgeFilter edge_filter = gpu::EdgeFilter::diagonal;     // edges (family edges; `method` unused)
  RayTracedMethod ray_traced = RayTracedMethod::rt;            // family ray_traced (`method` unused)
  // Held to the robust rule (diff's): the robust methods with exact signs; the float-sign runs
  // are the float baseline (wrong where the light is within rounding of a plane).
  [[nodiscard]] bool robust() const;
};

// The whole matrix, in this order: cpu; cs, gs, ts, pertri each with exact then float signs;
// shadowmap at 512, 1024, 2048, 4096; pcf 3, 5, 9 and pcss at 2048 (pcss's light radius R: the
// soft reference's); smoothie at 2048 with D = R/4, R/2, R (world space); discrete, accurate,
// smooth at eps 0.1, 0.03, 0.01, 0.003, smooth-gpu at 0.01; the edge-map filters (issue 14,
// gpu/edge_map.h) edges/diagonal, edges/c1, edges/sobel; the ray-traced methods rt, rt-robust.
[[nodiscard]] std::vector<BenchVariant> bench_variants();
// The method name --methods selects a variant by: render's --method name (rt, rt-robust for the
// ray-traced ones), "edges" for edge maps.
[[nodiscard]] std::string method_of(const BenchVariant& variant);

// The variants `list` names, comma-separated: a method name (every variant of it: "cs", "smooth")
// ("edges" for the edge-map filters) or a variant id ("cs/float"), in the matrix's order, each once; "all" or an empty list: every
// variant. Throws std::invalid_argument naming an unknown entry, with the names.
[[nodiscard]] std::vector<BenchVariant> select_bench_variants(std::string_view list);

// Where a suite's files are: the source tree (data/scenes/) and the shared meshes (../shared/data).
struct BenchPaths {
  std::filesystem::path source_dir;   // holds data/scenes/ and data/meshes/ (the bundled real meshes)
  std::filesystem::path shared_data;  // the developer meshes: closed_manifold/, soups/, ... (may be absent)
};

// One scene of a suite.
struct BenchSceneSpec {
  std::string suite;  // default, hard, real, analytic, scenes
  std::string name;   // unique in the whole list: the file stem, or e.g. "sphere8x4-point"
  std::string input;  // the path as shown (relative to the source tree where it lies there), or "generated: ..."
  std::filesystem::path file;  // the scene (.json) or mesh file to read; empty for a generated scene
  bool framed = false;  // a mesh framed over a floor (scene/framed_scene.h's rule)
  std::optional<std::size_t> analytic_shape;  // analytic: index into analytic_shapes()
  bool sun = false;                           // analytic: the sun, else the point light
  std::optional<Plane> receiver_plane;        // where the contour error is measured (analytic)
  std::string missing;  // non-empty: why the scene cannot run (a mesh not here)
};

// The suites (docs/bench.md#the-suites), each in a fixed order:
//   default   data/scenes/*.json but sphere_grid_1m.json, by name
//   hard      data/scenes/hard/*.json, by name
//   real      the meshes of kRealMeshes under paths.shared_data, framed (missing ones are listed,
//             with `missing` set)
//   analytic  analytic_shapes() under the point light, then under the sun, floor y = -1.5
//   all       default, hard, real, analytic
// Throws std::invalid_argument for another name.
[[nodiscard]] std::vector<BenchSceneSpec> bench_suite(std::string_view suite, const BenchPaths& paths);
// The real suite's meshes, relative to the shared data folder: the smooth-silhouette table's.
[[nodiscard]] std::vector<std::string> real_meshes();
// Scenes given by path: a .json scene as it is, any other file a mesh framed over a floor
// (suite "scenes"; with real = true, suite "real"). Names are the file stems, made unique by a
// numeric suffix.
[[nodiscard]] std::vector<BenchSceneSpec> bench_scene_files(const std::vector<std::string>& paths, bool real);

// The scene of `spec` at width x height (0 x 0: a file's own camera size; a framed or generated
// scene gets 256 x 192 then). Throws InputError for a file that cannot be read (a missing
// spec, `spec.missing` set, too), as io/ does.
[[nodiscard]] Scene load_bench_scene(const BenchSceneSpec& spec, std::uint32_t width, std::uint32_t height);

struct BenchOptions {
  std::size_t warm_up_frames = 2;
  std::size_t frames = 10;
  gpu::StageSync sync = gpu::StageSync::none;  // finish on a software renderer (gpu/gpu_stage_timer.h)
  double crease_angle_degrees = kDefaultCreaseAngleDegrees;
  std::uint32_t soft_samples = 64;  // the exact soft reference's samples, a perfect square
  // The area light's radius R (world units) of the soft reference, pcss and the smoothie widths;
  // 0: gpu::default_light_radius of the scene's bounds (1% of the diagonal, as diff --soft).
  double light_radius = 0.0;
  // A directional light's angular radius in degrees, of the soft reference and pcss, in
  // [0, 90); 0: gpu::kDefaultLightAngleDegrees (whatever the scene's scale, as diff --soft).
  double light_angle_degrees = 0.0;
  bool images = true;               // keep each run's overlay (and soft error image)
  // Called with a line per run (for a progress display); may be empty.
  std::function<void(std::string_view)> progress;
};

// An edge-map run against the exact edges (pipeline/edge_map_comparison.h): the map at the
// filter's default thresholds (profile: a depth step of gpu::kDefaultEdgeDepthStep of the depth
// range; inner: creases above gpu::kDefaultEdgeCreaseAngleDegrees), one-pixel tolerance.
struct BenchEdgeScores {
  double profile_threshold = 0.0;
  double inner_threshold = 0.0;
  EdgeMatchCounts profile;
  EdgeMatchCounts inner;
  [[nodiscard]] EdgeMatchCounts pooled() const {
    EdgeMatchCounts c = profile;
    c += inner;
    return c;
  }
};

// One variant on one scene.
struct BenchRun {
  BenchVariant variant;
  // compare_scene's MethodRun for it (per light: comparison, closure, volume triangles, capacity
  // error, analytic and soft figures); the frames are dropped once the images below are made.
  // A ray-traced run's: its lights' comparisons and soft errors (`run.method` unused).
  MethodRun run;
  gpu::FrameTiming timing;  // every light's time_frames, summed (each light rendered alone); a
                            // ray-traced run: its images' rays (every light at once), CPU wall
  double build_ms = 0.0;    // the CPU work before the frames, summed over lights; ray-traced: the
                            // median of its images' BVH builds
  double smoothie_width = 0.0;  // smoothie: D in world units
  double light_radius = 0.0;    // pcss: R in world units
  std::optional<SoftShadowErrors> soft;  // the lights' soft errors together
  std::optional<ContourError> contour;   // silhouette runs on a scene with a receiver plane
  std::optional<BenchEdgeScores> edges;  // edges runs (their `run` has no light: no pixel comparison)
  gpu::RgbaImage overlay;     // the first light's frame with hard errors and ambiguous pixels
                              // (edges: the profile verdicts, reference/edge_scores.h's colours)
  gpu::RgbaImage soft_error;  // the first light's light against its soft reference, when there is one
  // A ray-traced run never fails (its `run` has no volume and is not held robust).
  [[nodiscard]] bool failed() const { return variant.family != BenchFamily::ray_traced && run.failed(); }
};

struct BenchSceneResult {
  std::size_t triangles = 0;
  std::size_t lights = 0;
  std::uint32_t width = 0, height = 0;
  double exact_seconds = 0.0;  // the exact image and its float-rounded twin
  double exact_image_seconds = 0.0;  // the exact image alone (what a ray tracer's time compares with)
  std::optional<double> soft_radius;  // with a soft reference
  double soft_angle_degrees = 0.0;    // its directional lights' angular radius
  double soft_seconds = 0.0;
  std::vector<std::string> analytic_casters;  // with an analytic image
  double analytic_seconds = 0.0;
  double edge_truth_seconds = 0.0;  // the exact edges, with an edges run
  double seconds = 0.0;
  std::vector<BenchRun> runs;  // in the variants' order; a variant that does not apply is absent
  // The first light's exact pictures: lit mask (gray), counts in viridis (comparison_pictures.h)
  // up to count_scale, ambiguous pixels (gray).
  gpu::GrayImage exact_mask;
  gpu::RgbaImage exact_counts;
  std::uint32_t count_scale = 0;
  gpu::GrayImage exact_ambiguous;
  // bench_scene_into: the id of the run under way (empty before the first and after the last),
  // so that when it throws, the run that threw.
  std::string running;
};

// Every variant of `variants` that applies to `scene` (the smooth-silhouette ones only when some
// casting mesh qualifies as a smooth caster and is cast by them; the others always), with the
// scene's references (the exact edges too when an edges run is asked for). A GL context must be current. Throws what compare_scene throws.
[[nodiscard]] BenchSceneResult bench_scene(const Scene& scene, const BenchSceneSpec& spec,
                                           const std::vector<BenchVariant>& variants, const BenchOptions& options);
// The same, filling `result` as it goes (it is reset first), so that when a run throws the
// caller keeps what finished (`shadowcert bench` records the failure and goes on,
// docs/bench.md): the runs done, in order, and in `result.running` the id of the run that threw
// (empty: the scene's checks or references threw, before any run).
void bench_scene_into(BenchSceneResult& result, const Scene& scene, const BenchSceneSpec& spec,
                      const std::vector<BenchVariant>& variants, const BenchOptions& options);

// Whether scene number `index` (0-based, in the whole suite's order) belongs to shard K of N
// (1 <= K <= N): index % N == K - 1.
[[nodiscard]] constexpr bool in_shard(std::size_t index, std::size_t k, std::size_t n) {
  return n != 0 && index % n == k - 1;
}

}  // namespace shadowcert
