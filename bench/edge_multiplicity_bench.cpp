// Speed of the exact multiplicities and of the float methods on the same table (docs/definitions.md#counts,
// docs/multiplicities.md). Targets, one core: canonical_soup + edge table + exact on
// sphere_grid(1M) well under 1 s, and exact within 1.5x of refedge in double.
//
//   cmake --build build --target edge_multiplicity_bench
//   taskset -c 0 ./build/bench/edge_multiplicity_bench --benchmark_repetitions=10
//       --benchmark_report_aggregates_only=true    (one command line; read the _min rows)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "exact/edge_multiplicity.h"
#include "scene/edge_table.h"
#include "io/soup_file.h"
#include "scene/canonical_soup.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

struct Input {
  Soup raw;
  Soup canonical;
  EdgeTable table;
  Light light;
};

// A point light above and beside the scene, well outside its bounding box.
Light light_for(const Soup& soup) {
  Vec3 lo = soup.vertices.front(), hi = lo;
  for (const Vec3& p : soup.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  return Light{{hi[0] + 0.3 * size, hi[1] + 1.1 * size, (lo[2] + hi[2]) / 2 + 0.2 * size, 1.0}};
}

Input make_input(Soup raw) {
  Input in;
  in.raw = std::move(raw);
  in.canonical = canonical_soup(in.raw).soup;
  in.table = build_edge_table(in.canonical);
  in.light = light_for(in.canonical);
  return in;
}

// The worst case of the exact predicate (docs/definitions.md#hard-cases, a floor lit at grazing angle): a
// 1000 x 500-cell grid (1M triangles) on the tilted plane z = x + 2y, light in that plane.
// With step 1 every determinant is exactly zero (the semi-static stage cannot tell, the
// intervals can); with step 0.1 the vertices are rounded off the plane, every determinant is
// tiny and of either sign, and many reach the exact stage.
Input grazing_grid(double step) {
  Soup s;
  constexpr std::uint32_t kW = 1000, kH = 500;
  for (std::uint32_t i = 0; i <= kW; ++i)
    for (std::uint32_t j = 0; j <= kH; ++j) {
      const double x = i * step, y = j * step;
      s.vertices.push_back({x, y, x + 2 * y});
    }
  auto id = [](std::uint32_t i, std::uint32_t j) { return i * (kH + 1) + j; };
  for (std::uint32_t i = 0; i < kW; ++i)
    for (std::uint32_t j = 0; j < kH; ++j) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  Input in = make_input(std::move(s));
  const double x = -300 * step, y = 700 * step;
  in.light = Light{{x, y, x + 2 * y, 1.0}};
  return in;
}

// Inputs are built once, on first use, so that a filtered run builds only what it needs.
const Input& input(const std::string& name) {
  static std::map<std::string, Input> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  if (name == "grazing_exact") return cache.emplace(name, grazing_grid(1.0)).first->second;
  if (name == "grazing_rounded") return cache.emplace(name, grazing_grid(0.1)).first->second;
  const std::filesystem::path data = SHADOWCERT_SHARED_DATA;
  Soup raw = name == "sphere_grid_1M" ? sphere_grid(1'000'000)
             : name == "ogre"         ? read_soup(data / "soups/ogre.obj")
                                      : read_soup(data / "closed_manifold/nefertiti.obj");
  return cache.emplace(name, make_input(std::move(raw))).first->second;
}

void set_counters(benchmark::State& state, const Input& in) {
  state.counters["triangles"] = static_cast<double>(in.raw.triangles.size());
  state.counters["ns_per_tri"] = benchmark::Counter(
      static_cast<double>(in.raw.triangles.size()), benchmark::Counter::kIsIterationInvariantRate |
                                                        benchmark::Counter::kInvert);
}

void canonical_bench(benchmark::State& state, const std::string& name) {
  const Input& in = input(name);
  for (auto _ : state) benchmark::DoNotOptimize(canonical_soup(in.raw));
  set_counters(state, in);
}

void table_bench(benchmark::State& state, const std::string& name) {
  const Input& in = input(name);
  for (auto _ : state) benchmark::DoNotOptimize(build_edge_table(in.canonical));
  set_counters(state, in);
  state.counters["edges"] = static_cast<double>(in.table.size());
}

void method_bench(benchmark::State& state, const std::string& name, MultiplicityMethod method,
                  Precision precision) {
  const Input& in = input(name);
  EdgeMultiplicities m;
  for (auto _ : state) benchmark::DoNotOptimize(m = edge_multiplicities(method, in.canonical, in.table, in.light, precision));
  set_counters(state, in);
  std::int64_t silhouette = 0;
  for (std::int32_t x : m.multiplicity) silhouette += x != 0;
  state.counters["silhouette_edges"] = static_cast<double>(silhouette);
}

// The whole exact path of one soup and light, as the certificate runs it (closure excluded).
void pipeline_bench(benchmark::State& state, const std::string& name) {
  const Input& in = input(name);
  for (auto _ : state) {
    const Soup canonical = canonical_soup(in.raw).soup;
    const EdgeTable table = build_edge_table(canonical);
    benchmark::DoNotOptimize(exact_multiplicities(canonical, table, in.light));
  }
  set_counters(state, in);
}

bool available(const std::string& name) {
  const std::filesystem::path data = SHADOWCERT_SHARED_DATA;
  if (name == "ogre") return std::filesystem::exists(data / "soups/ogre.obj");
  if (name == "nefertiti") return std::filesystem::exists(data / "closed_manifold/nefertiti.obj");
  return true;
}

int register_all() {
  struct Variant {
    const char* label;
    MultiplicityMethod method;
    Precision precision;
  };
  const Variant variants[] = {{"exact", MultiplicityMethod::exact, Precision::float64},
                              {"refedge_double", MultiplicityMethod::refedge, Precision::float64},
                              {"refedge_float", MultiplicityMethod::refedge, Precision::float32},
                              {"kim_double", MultiplicityMethod::kim, Precision::float64},
                              {"kim_float", MultiplicityMethod::kim, Precision::float32},
                              {"peciva_double", MultiplicityMethod::peciva, Precision::float64},
                              {"peciva_float", MultiplicityMethod::peciva, Precision::float32}};
  for (const std::string name : {"sphere_grid_1M", "ogre", "nefertiti"}) {
    if (!available(name)) continue;  // the shared meshes are optional (docs/development.md)
    auto add = [](const std::string& label, auto&& f) {
      // The minimum over repetitions is the figure to read on a shared machine: other jobs
      // only ever add time (run with --benchmark_repetitions=N).
      benchmark::RegisterBenchmark(label.c_str(), f)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->ComputeStatistics("min", [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); });
    };
    add("CanonicalSoup/" + name, [name](benchmark::State& s) { canonical_bench(s, name); });
    add("EdgeTable/" + name, [name](benchmark::State& s) { table_bench(s, name); });
    for (const Variant& v : variants)
      add(std::string("Multiplicities/") + v.label + "/" + name,
          [name, v](benchmark::State& s) { method_bench(s, name, v.method, v.precision); });
    add("ExactPipeline/" + name, [name](benchmark::State& s) { pipeline_bench(s, name); });
  }
  for (const std::string name : {"grazing_exact", "grazing_rounded"})
    for (const Variant& v : {variants[0], variants[1]})
      benchmark::RegisterBenchmark((std::string("Multiplicities/") + v.label + "/" + name).c_str(),
                                   [name, v](benchmark::State& s) { method_bench(s, name, v.method, v.precision); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime()
          ->ComputeStatistics("min", [](const std::vector<double>& x) { return *std::min_element(x.begin(), x.end()); });
  return 0;
}

const int registered = register_all();

}  // namespace

BENCHMARK_MAIN();
