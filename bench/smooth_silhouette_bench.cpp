// Smooth silhouettes (docs/smooth-silhouettes.md): each method's shadow boundary against the
// analytic one, and the time to build it.
//
//   error/METHOD/SHAPE/LIGHT   discrete, accurate and smooth at eps in {0.1, 0.03, 0.01, 0.003}
//                              (caster radius 1), on uv spheres from 8x4 to 256x128 and an
//                              ellipsoid, under a point and a directional light. Counters:
//                              max_err, mean_err (world units on the floor y = -1.5, against
//                              reference/ellipsoid_shadow.h's conic), points (boundary points),
//                              volume_tris; Time: loops + contour + the whole closed volume.
//   extract/100k               silhouette extraction and smooth subdivision at eps = 0.01 on a
//                              100K-triangle uv sphere of unit radius, one core (the paper: about
//                              4.3 ms for its 100K dragon in 2011).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "contour/smooth_volume.h"
#include "core/vector3.h"
#include "reference/ellipsoid_shadow.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

const Plane kFloor{{0.0, -1.5, 0.0}, {0.0, 1.0, 0.0}};
const Light kPointLight{{1.2, 4.0, 0.8, 1.0}};
const Light kSun{{0.3, 1.0, 0.2, 0.0}};

struct Shape {
  std::string name;
  Soup soup;
  Ellipsoid truth;
};

// x -> A x for the ellipsoid (the uv sphere's vertices and normals: normals by A^-T).
Shape ellipsoid_shape() {
  const Ellipsoid e{{0, 0, 0}, {{{1.4, 0.0, 0.2}, {0.0, 0.8, 0.0}, {-0.3, 0.0, 1.0}}}};
  Soup s = uv_sphere({0, 0, 0}, 1.0, 32, 16);
  s.normals.clear();  // computed from the transformed mesh
  for (Vec3& v : s.vertices) {
    const Vec3 u = v;
    for (std::size_t k = 0; k < 3; ++k) v[k] = e.axes[0][k] * u[0] + e.axes[1][k] * u[1] + e.axes[2][k] * u[2];
  }
  return {"ellipsoid32x16", s, e};
}

std::vector<Vec3> projected(const std::vector<Vec3>& points, const Light& light) {
  std::vector<Vec3> out;
  out.reserve(points.size());
  for (const Vec3& p : points) out.push_back(shadow_on_plane(p, light, kFloor));
  return out;
}

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

void run_error(benchmark::State& state, Shape shape, Light light, SilhouetteMethod method, double epsilon) {
  const SmoothCasterResult r = smooth_caster(shape.soup);
  if (!r.caster) {
    state.SkipWithError(r.qualification.summary().c_str());
    return;
  }
  const SmoothCaster& caster = *r.caster;
  const std::vector<Sign> lit = face_sides(caster, light);
  const SmoothVolumeOptions options{method, epsilon};
  SmoothVolume volume;
  for (auto _ : state) {
    volume = smooth_shadow_volume(caster, light, options, lit);
    benchmark::DoNotOptimize(volume.mesh.triangles.data());
  }
  const std::vector<Vec3> truth = ellipsoid_shadow_boundary(shape.truth, light, kFloor, 4096);
  double max = 0.0, weighted = 0.0, points = 0.0;
  // The boundary of the shadow: the outer loop (the caster's silhouette seen from the light).
  for (std::size_t l = 0; l < volume.loops.size(); ++l) {
    std::vector<Vec3> boundary;
    bool closed = volume.loops[l].closed;
    if (method == SilhouetteMethod::smooth) {
      for (const ContourPoint& p : volume.contours[l].points) boundary.push_back(p.position);
    } else {
      for (const SilhouettePoint& p : volume.loops[l].points) boundary.push_back(p.position);
    }
    if (boundary.size() < 2) continue;
    const BoundaryDistance d = boundary_distance(projected(boundary, light), closed, truth);
    max = std::max(max, d.max);
    weighted += d.mean * static_cast<double>(boundary.size());
    points += static_cast<double>(boundary.size());
  }
  state.counters["max_err"] = max;
  state.counters["mean_err"] = points > 0 ? weighted / points : 0.0;
  state.counters["points"] = points;
  state.counters["loops"] = static_cast<double>(volume.loops.size());
  state.counters["volume_tris"] = static_cast<double>(volume.mesh.triangles.size());
}

void register_error_benchmarks() {
  std::vector<Shape> shapes;
  for (const auto& [slices, stacks] : {std::pair{8u, 4u}, {12u, 6u}, {16u, 8u}, {32u, 16u}, {64u, 32u}, {128u, 64u},
                                       {256u, 128u}})
    shapes.push_back({"sphere" + std::to_string(slices) + "x" + std::to_string(stacks),
                      uv_sphere({0, 0, 0}, 1.0, slices, stacks), Ellipsoid{}});
  shapes.push_back(ellipsoid_shape());
  struct Method {
    std::string name;
    SilhouetteMethod method;
    double epsilon;
  };
  const std::vector<Method> methods{{"discrete", SilhouetteMethod::discrete, 0.01},
                                    {"accurate", SilhouetteMethod::accurate, 0.01},
                                    {"smooth0.1", SilhouetteMethod::smooth, 0.1},
                                    {"smooth0.03", SilhouetteMethod::smooth, 0.03},
                                    {"smooth0.01", SilhouetteMethod::smooth, 0.01},
                                    {"smooth0.003", SilhouetteMethod::smooth, 0.003}};
  for (const auto& [light_name, light] : {std::pair{"point", kPointLight}, {"sun", kSun}})
    for (const Shape& shape : shapes)
      for (const Method& m : methods)
        benchmark::RegisterBenchmark(("error/" + m.name + "/" + shape.name + "/" + light_name).c_str(), run_error, shape,
                                     light, m.method, m.epsilon)
            ->Unit(benchmark::kMillisecond)
            ->Iterations(shape.soup.triangles.size() > 20000 ? 3 : 10);
}

void BM_Extract100k(benchmark::State& state) {
  const SmoothCaster caster = *smooth_caster(uv_sphere({0, 0, 0}, 1.0, 224, 224)).caster;
  std::size_t points = 0;
  for (auto _ : state) {
    const auto loops = accurate_silhouette(caster, kPointLight);
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
