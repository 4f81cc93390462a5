// Smooth silhouettes (docs/smooth-silhouettes.md): each method's shadow boundary against the
// analytic one, and the time to build it.
//
//   error/METHOD/SHAPE/LIGHT   discrete, accurate and smooth at eps in {0.1, 0.03, 0.01, 0.003}
//                              (caster radius 1), on uv spheres from 8x4 to 256x128 and an
//                              ellipsoid, under a point and a directional light. Counters:
//                              max_err, mean_err (world units on the floor y = -1.5, against
//                              reference/ellipsoid_shadow.h's conic, measured by
//                              pipeline/contour_error.h as `shadowcert bench --suite analytic`
//                              does, on the same scenes), points (boundary points), loops,
//                              volume_tris; Time: loops + contour + the whole closed volume.
//   extract/100k               silhouette extraction and smooth subdivision at eps = 0.01 on a
//                              100K-triangle uv sphere of unit radius, one core (the paper: about
//                              4.3 ms for its 100K dragon in 2011).
#include <benchmark/benchmark.h>

#include <optional>
#include <string>
#include <vector>

#include "contour/smooth_volume.h"
#include "core/vector3.h"
#include "pipeline/contour_error.h"
#include "scene/framed_scene.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

const Plane kFloor{{0.0, kAnalyticFloorHeight, 0.0}, {0.0, 1.0, 0.0}};

std::vector<Sign> face_sides(const SmoothCaster& c, const Light& light) {
  std::vector<Sign> lit(c.triangles.size());
  const auto& l = light.position;
  for (std::size_t t = 0; t < lit.size(); ++t) {
    const Vec3& a = c.vertices[c.triangles[t][0]];
    const Vec3 n = cross(difference(c.vertices[c.triangles[t][1]], a), difference(c.vertices[c.triangles[t][2]], a));
    lit[t] = sign_of(dot(n, Vec3{l[0] - l[3] * a[0], l[1] - l[3] * a[1], l[2] - l[3] * a[2]}));
  }
  return lit;
}

struct Method {
  std::string name;
  SilhouetteMethod kind;
  gpu::ShadowMethod method;
  double epsilon;
};

// Times the closed volume's build; then the error, measured as `shadowcert bench` measures it
// (pipeline/contour_error.h, on the same analytic scene: scene/framed_scene.h).
void run_error(benchmark::State& state, const AnalyticShape& shape, Light light, const Method& m) {
  const SmoothCasterResult r = smooth_caster(shape.soup);
  if (!r.caster) {
    state.SkipWithError(r.qualification.summary().c_str());
    return;
  }
  const SmoothCaster& caster = *r.caster;
  const std::vector<Sign> lit = face_sides(caster, light);
  const SmoothVolumeOptions options{m.kind, m.epsilon};
  SmoothVolume volume;
  for (auto _ : state) {
    volume = smooth_shadow_volume(caster, light, options, lit);
    benchmark::DoNotOptimize(volume.mesh.triangles.data());
  }
  const std::optional<ContourError> e =
      contour_error(analytic_shape_scene(shape, light, 64, 48), 0, m.method, m.epsilon, kFloor);
  if (!e) {
    state.SkipWithError("contour_error: the shape is no analytic caster");
    return;
  }
  state.counters["max_err"] = e->max;
  state.counters["mean_err"] = e->mean;
  state.counters["points"] = static_cast<double>(e->points);
  state.counters["loops"] = static_cast<double>(volume.loops.size());
  state.counters["volume_tris"] = static_cast<double>(volume.mesh.triangles.size());
}

void register_error_benchmarks() {
  const std::vector<Method> methods{{"discrete", SilhouetteMethod::discrete, gpu::ShadowMethod::discrete, 0.01},
                                    {"accurate", SilhouetteMethod::accurate, gpu::ShadowMethod::accurate, 0.01},
                                    {"smooth0.1", SilhouetteMethod::smooth, gpu::ShadowMethod::smooth, 0.1},
                                    {"smooth0.03", SilhouetteMethod::smooth, gpu::ShadowMethod::smooth, 0.03},
                                    {"smooth0.01", SilhouetteMethod::smooth, gpu::ShadowMethod::smooth, 0.01},
                                    {"smooth0.003", SilhouetteMethod::smooth, gpu::ShadowMethod::smooth, 0.003}};
  for (const auto& [light_name, light] : {std::pair{"point", kAnalyticPointLight}, {"sun", kAnalyticSun}})
    for (const AnalyticShape& shape : analytic_shapes())
      for (const Method& m : methods)
        benchmark::RegisterBenchmark(("error/" + m.name + "/" + shape.name + "/" + light_name).c_str(), run_error, shape,
                                     light, m)
            ->Unit(benchmark::kMillisecond)
            ->Iterations(shape.soup.triangles.size() > 20000 ? 3 : 10);
}

void BM_Extract100k(benchmark::State& state) {
  const SmoothCaster caster = *smooth_caster(uv_sphere({0, 0, 0}, 1.0, 224, 224)).caster;
  std::size_t points = 0;
  for (auto _ : state) {
    const auto loops = accurate_silhouette(caster, kAnalyticPointLight);
    const auto contours = smooth_contour(caster, loops, 0.01);
    points = 0;
    for (const auto& c : contours) points += c.points.size();
    benchmark::DoNotOptimize(points);
  }
  state.counters["tris"] = static_cast<double>(caster.triangles.size());
  state.counters["contour_points"] = static_cast<double>(points);
}
BENCHMARK(BM_Extract100k)->Name("extract/100k")->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  register_error_benchmarks();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
