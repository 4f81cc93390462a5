// Silhouette tracking against the full search, per frame (Chen and Tsai, §2.1 and §5;
// docs/smoothies.md, "Silhouette tracking"): contour/silhouette_tracker.h on uv spheres, tori,
// (2, 3) torus knots and the sphere grid, 1K to 1M triangles, the light orbiting the mesh one
// degree per frame.
//
//   track/SHAPE/TRIANGLES/VARIANT   one frame per iteration (the orbit's next light), after a
//                                   first full frame. VARIANT: full, one-way, continue,
//                                   periodic:10. Counters: checked (edges tested per frame),
//                                   faces (face sides computed per frame), found (silhouette
//                                   edges per frame), edges (the mesh's).
//
// The paper: tracking wins above about 10,000 faces. Where it wins here: docs/smoothies.md.
// One core: taskset -c 1 ./build/bench/silhouette_tracking_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "contour/silhouette_edge_graph.h"
#include "contour/silhouette_tracker.h"
#include "contour/smooth_caster.h"
#include "scene/light_orbit.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

// One degree per frame.
constexpr std::size_t kOrbitFrames = 360;

enum class Shape { sphere, torus, knot, sphere_grid };

const char* shape_name(Shape s) {
  switch (s) {
    case Shape::sphere: return "sphere";
    case Shape::torus: return "torus";
    case Shape::knot: return "knot";
    case Shape::sphere_grid: return "sphere_grid";
  }
  return "?";
}

// About `triangles` triangles, in a mesh of unit size around the origin (the grid: 25 x 25).
Soup mesh(Shape shape, std::uint64_t triangles) {
  switch (shape) {
    case Shape::sphere: {  // 2 s (k - 1) triangles with s = 2 k
      const auto k = static_cast<std::uint32_t>(std::lround(std::sqrt(static_cast<double>(triangles) / 4.0))) + 1;
      return uv_sphere({0, 0, 0}, 1.0, 2 * k, k);
    }
    case Shape::torus: {  // 2 M m triangles with M = 2 m
      const auto m = static_cast<std::uint32_t>(std::lround(std::sqrt(static_cast<double>(triangles) / 4.0)));
      return torus({0, 0, 0}, 1.0, 0.35, 2 * m, m);
    }
    case Shape::knot: {  // 2 S T triangles with S = 8 T
      const auto t = static_cast<std::uint32_t>(std::lround(std::sqrt(static_cast<double>(triangles) / 16.0)));
      return torus_knot({0, 0, 0}, 2, 3, 1.0, 0.4, 0.12, 8 * t, t);
    }
    case Shape::sphere_grid: return sphere_grid(std::max<std::uint64_t>(triangles, 600));
  }
  return {};
}

struct Fixture {
  SilhouetteEdgeGraph graph;
  std::vector<Light> lights;
};

const Fixture& fixture(Shape shape, std::uint64_t triangles) {
  static std::map<std::pair<Shape, std::uint64_t>, std::unique_ptr<Fixture>> cache;
  auto& slot = cache[{shape, triangles}];
  if (!slot) {
    const Soup soup = mesh(shape, triangles);
    SmoothCasterOptions options;
    options.use_file_normals = true;  // normals play no part: skip computing them
    const SmoothCasterResult caster = smooth_caster(soup, options);
    slot = std::make_unique<Fixture>();
    slot->graph = silhouette_edge_graph(*caster.caster);
    LightOrbit orbit = default_light_orbit(used_vertex_box(soup));
    slot->lights = orbit_lights(orbit, kOrbitFrames);
  }
  return *slot;
}

void run_track(benchmark::State& state, Shape shape, std::uint64_t triangles, TrackingVariant variant) {
  const Fixture& f = fixture(shape, triangles);
  SilhouetteTracker tracker(f.graph, variant);
  (void)tracker.track(f.lights[0]);  // the first frame is a full search for every variant
  std::size_t frame = 1;
  double checked = 0.0, faces = 0.0, found = 0.0;
  for (auto _ : state) {
    const TrackedFrame& t = tracker.track(f.lights[frame++ % f.lights.size()]);
    checked += static_cast<double>(t.edges_checked);
    faces += static_cast<double>(t.faces_evaluated);
    found += static_cast<double>(t.edges.size());
    benchmark::DoNotOptimize(t.edges.data());
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["checked"] = checked / n;
  state.counters["faces"] = faces / n;
  state.counters["found"] = found / n;
  state.counters["edges"] = static_cast<double>(f.graph.edge_count());
  state.counters["triangles"] = static_cast<double>(f.graph.face_count());
}

const bool registered = [] {
  const std::vector<TrackingVariant> variants{{TrackingSearch::full, 0},
                                              {TrackingSearch::one_way, 0},
                                              {TrackingSearch::continue_search, 0},
                                              {TrackingSearch::periodic, 10}};
  for (const Shape shape : {Shape::sphere, Shape::torus, Shape::knot, Shape::sphere_grid})
    for (const std::uint64_t triangles : {1'000ULL, 10'000ULL, 100'000ULL, 1'000'000ULL}) {
      if (shape == Shape::sphere_grid && triangles < 10'000) continue;
      for (const TrackingVariant& v : variants)
        benchmark::RegisterBenchmark(("track/" + std::string(shape_name(shape)) + "/" + std::to_string(triangles) + "/" +
                                      tracking_variant_name(v))
                                         .c_str(),
                                     run_track, shape, triangles, v)
            ->Unit(benchmark::kMicrosecond);
    }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
