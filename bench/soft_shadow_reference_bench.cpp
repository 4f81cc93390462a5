// Cost of the exact soft reference (reference/soft_shadow_image.h, docs/smoothies.md#the-exact-soft-reference):
// seconds per image with K = 64 disk samples at 256x192 and 1024x768, on two scenes over a floor:
//   - one uv sphere (64 x 32, 4K triangles), disk radius 1 at 5 above (the tests' shape, larger);
//   - sphere_grid(100'000) with exact_image_bench's camera and light, disk radius 1.
// Counters split the time like exact_image_bench's (summed over the exact images: one per batch
// of samples, SoftShadowOptions::batch_bytes), and count the pixels by region.
// Run one with --benchmark_filter, e.g. 'SphereGrid100k/w:1024'; K with the third argument.
#include <benchmark/benchmark.h>

#include <vector>

#include "reference/soft_shadow_image.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

struct BenchScene {
  Soup soup;
  Light light;
  double radius = 1.0;
  Camera camera;
};

const BenchScene& sphere_scene() {
  static const BenchScene scene = [] {
    BenchScene s;
    s.soup = floor_quad(8.0);
    s.soup.normals.clear();
    append_soup(s.soup, uv_sphere({0.0, 1.5, 0.0}, 1.0, 64, 32));
    s.light = Light{{1.0, 6.5, 0.5, 1.0}};
    s.camera.eye = {0.0, 7.0, 8.0};
    s.camera.target = {0.0, 0.5, 0.0};
    return s;
  }();
  return scene;
}

const BenchScene& sphere_grid_scene() {
  static const BenchScene scene = [] {
    BenchScene s;
    s.soup = floor_quad(16.0);
    s.soup.normals.clear();
    append_soup(s.soup, sphere_grid(100'000));
    s.light = Light{{4.0, 30.0, 8.0, 1.0}};
    s.camera.eye = {0.0, 24.0, 32.0};
    s.camera.target = {0.0, 0.0, 0.0};
    return s;
  }();
  return scene;
}

void run(benchmark::State& state, const BenchScene& scene) {
  Camera camera = scene.camera;
  camera.width = static_cast<std::uint32_t>(state.range(0));
  camera.height = static_cast<std::uint32_t>(state.range(1));
  const DiskLightSampling sampling{scene.radius, static_cast<std::uint32_t>(state.range(2)), kDefaultDiskSeed};
  SoftShadowStats stats;
  std::uint64_t umbra = 0, penumbra = 0, lit = 0;
  for (auto _ : state) {
    const SoftShadowImage image = disk_light_shadow_image(scene.soup, scene.light, sampling, camera);
    stats = image.stats;
    umbra = penumbra = lit = 0;
    for (std::size_t p = 0; p < image.pixels(); ++p) {
      const SoftRegion r = image.region(p);
      umbra += r == SoftRegion::umbra;
      penumbra += r == SoftRegion::penumbra;
      lit += r == SoftRegion::lit;
    }
  }
  state.counters["triangles"] = static_cast<double>(scene.soup.triangles.size());
  state.counters["exact_images"] = static_cast<double>(stats.exact_images);
  state.counters["tree_s"] = stats.tree_seconds;
  state.counters["hits_s"] = stats.hit_seconds;
  state.counters["counts_s"] = stats.count_seconds;
  state.counters["umbra_px"] = static_cast<double>(umbra);
  state.counters["penumbra_px"] = static_cast<double>(penumbra);
  state.counters["lit_px"] = static_cast<double>(lit);
}

void BM_SoftReference_SphereOverFloor(benchmark::State& state) { run(state, sphere_scene()); }
BENCHMARK(BM_SoftReference_SphereOverFloor)
    ->Args({256, 192, 64})
    ->Args({1024, 768, 64})
    ->ArgNames({"w", "h", "K"})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_SoftReference_SphereGrid100k(benchmark::State& state) { run(state, sphere_grid_scene()); }
BENCHMARK(BM_SoftReference_SphereGrid100k)
    ->Args({256, 192, 64})
    ->Args({1024, 768, 64})
    ->ArgNames({"w", "h", "K"})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
