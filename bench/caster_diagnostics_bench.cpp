// Speed of the caster diagnostics (docs/definitions.md#caster-diagnostics): the whole diagnose_caster call on a
// 1M-triangle sphere grid (target: under 3 s on 2 cores), its stages one by one, a
// moderately self-intersecting random soup, and the largest shared mesh when present.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "exact/caster_diagnostics.h"
#include "exact/degenerate_triangles.h"
#include "io/soup_file.h"
#include "exact/triangle_soup_self_intersections.h"
#include "exact/triangle_soup_topology.h"
#include "scene/procedural_mesh.h"
#include "scene/welded_soup.h"

namespace {

using namespace shadowcert;

const Soup& sphere_grid_1m() {
  static const Soup soup = sphere_grid(1'000'000);
  return soup;
}

// 100k random triangles of edge ~1/50 of the box: a few thousand crossings, the regime of
// a scanned or badly modelled caster rather than of a worst case.
const Soup& moderate_random_soup() {
  static const Soup soup = [] {
    Soup s = random_soup(7, 100'000, 1.0);
    // Shrink every triangle towards its first corner so that intersections stay sparse.
    for (Triangle& t : s.triangles) {
      const Vec3 a = s.vertices[t[0]];
      for (int k = 1; k < 3; ++k) {
        Vec3& p = s.vertices[t[k]];
        for (int d = 0; d < 3; ++d) p[d] = a[d] + (p[d] - a[d]) / 64.0;
      }
    }
    return s;
  }();
  return soup;
}

void set_counters(benchmark::State& state, const Soup& soup) {
  state.counters["triangles"] = static_cast<double>(soup.triangles.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * soup.triangles.size()));
}

void BM_DiagnoseCaster_SphereGrid1M(benchmark::State& state) {
  const Soup& soup = sphere_grid_1m();
  CasterDiagnostics d;
  for (auto _ : state) benchmark::DoNotOptimize(d = diagnose_caster(soup));
  set_counters(state, soup);
  state.counters["si_pairs"] = static_cast<double>(d.self_intersecting_pairs);
}
BENCHMARK(BM_DiagnoseCaster_SphereGrid1M)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Weld_SphereGrid1M(benchmark::State& state) {
  const Soup& soup = sphere_grid_1m();
  for (auto _ : state) benchmark::DoNotOptimize(weld_soup(soup));
  set_counters(state, soup);
}
BENCHMARK(BM_Weld_SphereGrid1M)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_TriangleShapes_SphereGrid1M(benchmark::State& state) {
  const Soup welded = weld_soup(sphere_grid_1m()).soup;
  for (auto _ : state) benchmark::DoNotOptimize(classify_triangle_shapes(welded));
  set_counters(state, welded);
}
BENCHMARK(BM_TriangleShapes_SphereGrid1M)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Topology_SphereGrid1M(benchmark::State& state) {
  const Soup welded = weld_soup(sphere_grid_1m()).soup;
  for (auto _ : state) benchmark::DoNotOptimize(analyze_topology(welded));
  set_counters(state, welded);
}
BENCHMARK(BM_Topology_SphereGrid1M)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SelfIntersections_SphereGrid1M(benchmark::State& state) {
  const Soup welded = weld_soup(sphere_grid_1m()).soup;
  const auto shapes = classify_triangle_shapes(welded);
  for (auto _ : state) benchmark::DoNotOptimize(find_self_intersecting_pairs(welded, shapes));
  set_counters(state, welded);
}
BENCHMARK(BM_SelfIntersections_SphereGrid1M)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DiagnoseCaster_ModerateRandomSoup100k(benchmark::State& state) {
  const Soup& soup = moderate_random_soup();
  CasterDiagnostics d;
  for (auto _ : state) benchmark::DoNotOptimize(d = diagnose_caster(soup));
  set_counters(state, soup);
  state.counters["si_pairs"] = static_cast<double>(d.self_intersecting_pairs);
}
BENCHMARK(BM_DiagnoseCaster_ModerateRandomSoup100k)->Unit(benchmark::kMillisecond)->UseRealTime();

// The largest shared mesh (README: soups/ogre.obj, 124,008 triangles, 9,142 SI pairs).
void BM_DiagnoseCaster_Ogre(benchmark::State& state) {
  const std::filesystem::path file = std::filesystem::path(SHADOWCERT_SHARED_DATA) / "soups/ogre.obj";
  if (!std::filesystem::exists(file)) {
    state.SkipWithError(("missing " + file.string()).c_str());
    return;
  }
  const Soup soup = read_soup(file);
  CasterDiagnostics d;
  for (auto _ : state) benchmark::DoNotOptimize(d = diagnose_caster(soup));
  set_counters(state, soup);
  state.counters["si_pairs"] = static_cast<double>(d.self_intersecting_pairs);
}
BENCHMARK(BM_DiagnoseCaster_Ogre)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
