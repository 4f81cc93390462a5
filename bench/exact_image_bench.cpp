// Speed of the exact image (reference/exact_image.h, docs/definitions.md#pixel-protocol), alone and against Embree
// (issue 24: the exact image within 3x of Embree on the same scene, rays and threads). Two scenes,
// each over a floor with one point light:
//   - sphere_grid(100'000) (Milet 2014's 10 x 10 spheres), camera and light of
//     data/scenes/sphere_grid_1m.json;
//   - the largest mesh of ../shared/data (soups/ogre.obj, 124K triangles), framed by its box;
//     ExactVsEmbree also frames the other two of at least 50K (the Stanford bunny, Nefertiti).
// Counters split the time: tree (casting signs and box tree), hits (first hit of every centre
// and corner ray), footprints (eye pyramids), counts (n(P) where it matters, and the ambiguity).
// Run one size with --benchmark_filter, e.g. 'SphereGrid100k/w:1024'.
//
// ExactVsEmbree runs, in one process on the same scene, rays and threads (TBB's default: every
// core), rounds of Embree's robust build and trace (raytrace/ray_traced_image.h: the centre
// rays, the corner rays and one shadow ray per hit, BVH build included) and then the exact
// image, and reports the median times and the median of the rounds' exact_s / embree_s as
// `ratio` (also printed, with the rounds' range and the first round's):
//   build/bench/exact_image_bench --benchmark_filter=ExactVsEmbree
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include <cstdio>

#include "bench/cpu_vector_isa.h"
#include "bench/peak_memory.h"
#include "io/soup_file.h"
#include "raytrace/ray_traced_image.h"
#include "reference/exact_image.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

struct BenchScene {
  Soup soup;
  std::vector<Light> lights;
  Camera camera;
};

// Milet's sphere grid of about `triangles` triangles over the floor, lit from above.
BenchScene sphere_grid_over_floor(std::uint64_t triangles) {
  BenchScene s;
  s.soup = floor_quad(16.0);  // the grid spans x, z in [-12.25, 12.25], resting on y = 0
  s.soup.normals.clear();
  append_soup(s.soup, sphere_grid(triangles));
  s.lights = {Light{{4.0, 30.0, 8.0, 1.0}}};
  s.camera.eye = {0.0, 24.0, 32.0};
  s.camera.target = {0.0, 0.0, 0.0};
  return s;
}

const BenchScene& sphere_grid_scene() {
  static const BenchScene scene = sphere_grid_over_floor(100'000);
  return scene;
}

// Embree's robust mode with the corner rays, on every thread of the arena: the peer the exact
// image is measured against (same rays, same threads).
raytrace::RayTracedImageOptions robust_rt_options() {
  raytrace::RayTracedImageOptions options;
  options.mode = raytrace::BuildMode::robust;
  options.corner_rays = true;
  options.threads = static_cast<unsigned>(tbb::this_task_arena::max_concurrency());
  return options;
}

// A mesh of the shared data (`relative` to ../shared/data) over a floor just below it, seen from
// the front and above, lit from above; nullptr where the file is missing. One scene kept at a
// time (the last asked for).
const BenchScene* shared_mesh_scene(const char* relative = "soups/ogre.obj") {
  static std::string loaded;
  static BenchScene scene;
  if (loaded == relative) return scene.soup.triangles.empty() ? nullptr : &scene;
  loaded = relative;
  const std::filesystem::path file = std::filesystem::path(SHADOWCERT_SHARED_DATA) / relative;
  scene = [&] {
    BenchScene s;
    if (!std::filesystem::exists(file)) return s;
    const Soup mesh = read_soup(file);
    Vec3 lo = mesh.vertices.front(), hi = lo;
    for (const Vec3& v : mesh.vertices)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], v[k]);
        hi[k] = std::max(hi[k], v[k]);
      }
    const Vec3 c{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    s.soup = floor_quad(1.5 * size);
    s.soup.normals.clear();
    for (Vec3& v : s.soup.vertices) v = {v[0] + c[0], lo[1] - 0.01 * size, v[2] + c[2]};
    append_soup(s.soup, mesh);
    s.lights = {Light{{c[0] + 0.4 * size, c[1] + 2.0 * size, c[2] + 0.6 * size, 1.0}}};
    s.camera.eye = {c[0], c[1] + 0.8 * size, c[2] + 1.6 * size};
    s.camera.target = c;
    return s;
  }();
  return scene.soup.triangles.empty() ? nullptr : &scene;
}

void run(benchmark::State& state, const BenchScene& scene) {
  Camera camera = scene.camera;
  camera.width = static_cast<std::uint32_t>(state.range(0));
  camera.height = static_cast<std::uint32_t>(state.range(1));
  ExactImageStats stats;
  std::uint64_t ambiguous = 0, shadowed = 0;
  for (auto _ : state) {
    const ExactImage image = exact_image(scene.soup, scene.lights, camera);
    stats = image.stats;
    ambiguous = shadowed = 0;
    for (std::size_t p = 0; p < image.hit_triangles.size(); ++p) {
      ambiguous += image.lights[0].ambiguity[p] != 0;
      shadowed += image.lights[0].counts[p] != kNoHit && image.lights[0].counts[p] != 0;
    }
  }
  state.counters["triangles"] = static_cast<double>(scene.soup.triangles.size());
  state.counters["rays"] = static_cast<double>(stats.rays);
  state.counters["counts"] = static_cast<double>(stats.counts);
  state.counters["tree_s"] = stats.tree_seconds;
  state.counters["hits_s"] = stats.hit_seconds;
  state.counters["footprints_s"] = stats.footprint_seconds;
  state.counters["counts_s"] = stats.count_seconds;
  state.counters["ambiguous_px"] = static_cast<double>(ambiguous);
  state.counters["shadowed_px"] = static_cast<double>(shadowed);
}

void BM_ExactImage_SphereGrid100k(benchmark::State& state) { run(state, sphere_grid_scene()); }
BENCHMARK(BM_ExactImage_SphereGrid100k)
    ->Args({256, 192})
    ->Args({1024, 768})
    ->ArgNames({"w", "h"})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_ExactImage_OgreOverFloor(benchmark::State& state) {
  const BenchScene* scene = shared_mesh_scene();
  if (scene == nullptr) {
    state.SkipWithError("../shared/data/soups/ogre.obj not found");
    return;
  }
  run(state, *scene);
}
BENCHMARK(BM_ExactImage_OgreOverFloor)
    ->Args({256, 192})
    ->Args({1024, 768})
    ->ArgNames({"w", "h"})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// Rounds of Embree (robust, corner rays on) then the exact image, same scene and threads, in
// one process. A single run on the 2-core virtual machine we measure on spreads by about 15%
// either way (the host's handling of fresh memory, docs/diff.md "The kernel's share varies"), so
// the figure is the median of kPeerRounds rounds, each round's two times taken back to back:
// its ratio is the median of the rounds' ratios, its times the medians of each time. The first
// round (fresh memory, as a one-shot run of a user's) is printed beside it.
inline constexpr std::size_t kPeerRounds = 5;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 == 1 ? v[v.size() / 2] : (v[v.size() / 2 - 1] + v[v.size() / 2]) / 2;
}

void exact_vs_embree(benchmark::State& state, const BenchScene& scene, const char* name) {
  Camera camera = scene.camera;
  camera.width = static_cast<std::uint32_t>(state.range(0));
  camera.height = static_cast<std::uint32_t>(state.range(1));
  const raytrace::RayTracedImageOptions rt_options = robust_rt_options();
  const unsigned threads = rt_options.threads;
  // Per round: Embree, exact, its four stages, and the ratio.
  std::array<std::vector<double>, 7> rounds;
  enum Column : std::size_t { kEmbree, kExact, kTree, kHits, kFootprints, kCounts, kRatio };
  for (auto _ : state) {
    for (auto& column : rounds) column.clear();
    for (std::size_t round = 0; round < kPeerRounds; ++round) {
      const double embree = raytrace::ray_traced_image(scene.soup, scene.lights, camera, rt_options).stats.seconds;
      const ExactImageStats stats = exact_image(scene.soup, scene.lights, camera).stats;
      const std::array<double, 7> row{embree,
                                      stats.seconds,
                                      stats.tree_seconds,
                                      stats.hit_seconds,
                                      stats.footprint_seconds,
                                      stats.count_seconds,
                                      stats.seconds / embree};
      for (std::size_t c = 0; c < row.size(); ++c) rounds[c].push_back(row[c]);
    }
  }
  if (rounds[kRatio].empty()) return;  // the benchmark's loop never ran
  std::array<double, 7> m{};
  for (std::size_t c = 0; c < m.size(); ++c) m[c] = median(rounds[c]);
  const auto [least, most] = std::minmax_element(rounds[kRatio].begin(), rounds[kRatio].end());
  state.counters["threads"] = threads;
  state.counters["triangles"] = static_cast<double>(scene.soup.triangles.size());
  state.counters["rounds"] = static_cast<double>(kPeerRounds);
  state.counters["embree_s"] = m[kEmbree];
  state.counters["exact_s"] = m[kExact];
  state.counters["tree_s"] = m[kTree];
  state.counters["hits_s"] = m[kHits];
  state.counters["footprints_s"] = m[kFootprints];
  state.counters["counts_s"] = m[kCounts];
  state.counters["ratio"] = m[kRatio];
  state.counters["first_ratio"] = rounds[kRatio].front();
  std::printf("%s %ux%u, %u threads: exact %.3f s (tree %.3f, hits %.3f, footprints %.3f, counts %.3f), "
              "Embree robust %.3f s, exact/Embree %.2f "
              "(median of %zu rounds: %.2f-%.2f, first %.2f; cpu %s, code %s)\n",
              name, camera.width, camera.height, threads, m[kExact], m[kTree], m[kHits], m[kFootprints], m[kCounts],
              m[kEmbree], m[kRatio], kPeerRounds, *least, *most, rounds[kRatio].front(), bench::cpu_vector_isa(),
              bench::code_level());
}

// The peer runs of a real mesh of the shared data (`relative` to it); an error naming the file
// where it is missing.
void exact_vs_embree_on_mesh(benchmark::State& state, const char* relative, const char* name) {
  const BenchScene* scene = shared_mesh_scene(relative);
  if (scene == nullptr) {
    state.SkipWithError((std::string("../shared/data/") + relative + " not found").c_str());
    return;
  }
  exact_vs_embree(state, *scene, name);
}

// Every ExactVsEmbree benchmark: 1024x768, one iteration (its rounds run inside), in seconds.
void peer_runs(benchmark::internal::Benchmark* b) {
  b->Args({1024, 768})->ArgNames({"w", "h"})->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
}

void BM_ExactVsEmbree_OgreOverFloor(benchmark::State& state) {
  exact_vs_embree_on_mesh(state, "soups/ogre.obj", "ogre over floor");
}
BENCHMARK(BM_ExactVsEmbree_OgreOverFloor)->Apply(peer_runs);

// The other real meshes of the shared data with at least 50K triangles (issue 24's bar), so
// the ratio is seen not to be ogre's alone: the Stanford bunny (69K) and Nefertiti (100K).
void BM_ExactVsEmbree_RealMesh(benchmark::State& state, const char* relative, const char* name) {
  exact_vs_embree_on_mesh(state, relative, name);
}
BENCHMARK_CAPTURE(BM_ExactVsEmbree_RealMesh, Bunny, "soups/stanford-bunny.obj", "stanford bunny over floor")
    ->Apply(peer_runs);
BENCHMARK_CAPTURE(BM_ExactVsEmbree_RealMesh, Nefertiti, "closed_manifold/nefertiti.obj", "nefertiti over floor")
    ->Apply(peer_runs);

void BM_ExactVsEmbree_SphereGrid100k(benchmark::State& state) {
  exact_vs_embree(state, sphere_grid_scene(), "sphere grid 100K");
}
BENCHMARK(BM_ExactVsEmbree_SphereGrid100k)->Apply(peer_runs);

// Issue 24's scaling table (docs/diff.md#scaling): Milet's sphere grid of 100K, 1M and 4M
// triangles over the floor, at 1024x768 and 1920x1080, Embree (robust, corner rays) then the
// exact image, one run each on the same scene, rays and threads, each stage's time and the peak
// of the resident set it added (reset before each: bench/peak_memory.h).
const BenchScene& sphere_grid_scene_of(std::int64_t triangles) {
  static std::map<std::int64_t, BenchScene> scenes;
  auto it = scenes.find(triangles);
  if (it != scenes.end()) return it->second;
  scenes.clear();  // one grid at a time: the 4M soup alone is 300 MB
  return scenes.emplace(triangles, sphere_grid_over_floor(static_cast<std::uint64_t>(triangles))).first->second;
}

void BM_ExactVsEmbree_Scaling(benchmark::State& state) {
  const BenchScene& scene = sphere_grid_scene_of(state.range(0));
  Camera camera = scene.camera;
  camera.width = static_cast<std::uint32_t>(state.range(1));
  camera.height = static_cast<std::uint32_t>(state.range(2));
  const raytrace::RayTracedImageOptions rt_options = robust_rt_options();
  const unsigned threads = rt_options.threads;
  double embree = 0.0, exact = 0.0, embree_peak = 0.0, exact_peak = 0.0;
  for (auto _ : state) {
    bench::reset_peak_rss();
    double before = bench::rss_line_mib("VmRSS:");
    {
      const raytrace::RayTracedImage rt = raytrace::ray_traced_image(scene.soup, scene.lights, camera, rt_options);
      embree = rt.stats.seconds;
      embree_peak = bench::rss_line_mib("VmHWM:") - before;
    }
    bench::reset_peak_rss();
    before = bench::rss_line_mib("VmRSS:");
    const ExactImage image = exact_image(scene.soup, scene.lights, camera);
    exact = image.stats.seconds;
    exact_peak = bench::rss_line_mib("VmHWM:") - before;
  }
  state.counters["threads"] = threads;
  state.counters["triangles"] = static_cast<double>(scene.soup.triangles.size());
  state.counters["embree_s"] = embree;
  state.counters["exact_s"] = exact;
  state.counters["ratio"] = exact / embree;
  state.counters["embree_peak_MiB"] = embree_peak;
  state.counters["exact_peak_MiB"] = exact_peak;
  std::printf("scaling: sphere grid %zu triangles %ux%u, %u threads: exact %.3f s, %.0f MiB; Embree robust %.3f s, "
              "%.0f MiB; exact/Embree %.2f (cpu %s, code %s)\n",
              scene.soup.triangles.size(), camera.width, camera.height, threads, exact, exact_peak, embree, embree_peak,
              exact / embree, bench::cpu_vector_isa(), bench::code_level());
}
BENCHMARK(BM_ExactVsEmbree_Scaling)
    ->Args({100'000, 1024, 768})
    ->Args({100'000, 1920, 1080})
    ->Args({1'000'000, 1024, 768})
    ->Args({1'000'000, 1920, 1080})
    ->Args({4'000'000, 1024, 768})
    ->Args({4'000'000, 1920, 1080})
    ->ArgNames({"triangles", "w", "h"})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
