// Speed of the volume library without GL (volume/volume_workspace.h) on Milet 2014's sphere
// grid (scene/procedural_mesh.h) of 100K and 1M triangles, CPU only:
//   set_soup (once per soup: weld, edge table, the build's arrays reserved),
//   generate (the hot path, per light and frame: exact multiplicities, chain, homogeneous mesh,
//   written into the caller's buffers, box), point and directional light,
//   build alone (the same without the copy into the caller's buffers).
// Wall time (the build runs on TBB's threads: both cores of the measuring machine).
// docs/engine-integration.md#volume-library-no-gl records the figures.
//
//   flock /tmp/team/build.lock cmake --build build -j2 --target volume_workspace_bench
//   ./build/bench/volume_workspace_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdint>
#include <span>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "scene/procedural_mesh.h"
#include "volume/volume_workspace.h"

namespace {

using namespace shadowcert;

// certificate_bench's lights: above the grid and off-axis, and a sun.
const Light kPointLight{{5.3, 20.0, 3.7, 1.0}};
const Light kDirectionalLight{{0.3, 1.0, 0.2, 0.0}};

// The caller's arrays: float xyz positions and uint32 indices, as an engine holds them.
struct CallerSoup {
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
};

const CallerSoup& grid(std::int64_t triangles) {
  static const auto make = [](std::int64_t t) {
    const Soup soup = sphere_grid(static_cast<std::uint64_t>(t));
    CallerSoup s;
    for (const Vec3& v : soup.vertices)
      for (const double x : v) s.positions.push_back(static_cast<float>(x));
    for (const Triangle& tri : soup.triangles) s.indices.insert(s.indices.end(), tri.begin(), tri.end());
    return s;
  };
  static const CallerSoup small = make(100'000), large = make(1'000'000);
  return triangles == 100'000 ? small : large;
}

void BM_VolumeSetSoup(benchmark::State& state) {
  const CallerSoup& soup = grid(state.range(0));
  for (auto _ : state) {
    VolumeWorkspace ws;
    ws.set_soup(std::span<const float>(soup.positions), soup.indices);
    benchmark::DoNotOptimize(ws.input_vertex_ids().data());
  }
  state.counters["triangles"] = static_cast<double>(soup.indices.size() / 3);
}

// The hot path as an engine runs it: the workspace and the buffers exist already.
void BM_VolumeGenerate(benchmark::State& state) {
  const CallerSoup& soup = grid(state.range(0));
  const Light& light = state.range(1) != 0 ? kDirectionalLight : kPointLight;
  VolumeWorkspace ws;
  ws.set_soup(std::span<const float>(soup.positions), soup.indices);
  const VolumeSizes sizes = ws.build(light);
  std::vector<float> positions(sizes.position_floats());
  std::vector<std::uint32_t> indices(sizes.index_count());
  for (auto _ : state) {
    const VolumeInfo info = ws.generate(light, positions, indices);
    benchmark::DoNotOptimize(info.written.triangles);
  }
  state.counters["volume_triangles"] = static_cast<double>(sizes.triangles);
  state.SetLabel(state.range(1) != 0 ? "directional" : "point");
}

void BM_VolumeBuild(benchmark::State& state) {
  const CallerSoup& soup = grid(state.range(0));
  const Light& light = state.range(1) != 0 ? kDirectionalLight : kPointLight;
  VolumeWorkspace ws;
  ws.set_soup(std::span<const float>(soup.positions), soup.indices);
  for (auto _ : state) benchmark::DoNotOptimize(ws.build(light).triangles);
  state.SetLabel(state.range(1) != 0 ? "directional" : "point");
}

BENCHMARK(BM_VolumeSetSoup)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_VolumeGenerate)
    ->ArgsProduct({{100'000, 1'000'000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_VolumeBuild)
    ->ArgsProduct({{100'000, 1'000'000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
