#include "pipeline/contour_error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "contour/smooth_volume.h"
#include "core/vector3.h"
#include "exact/light_orientation.h"
#include "gpu/smooth_silhouette_volume.h"
#include "pipeline/smooth_caster_arrays.h"

namespace shadowcert {
namespace {

void check_epsilon(const char* function, double epsilon) {
  if (!(epsilon > 0.0) || !std::isfinite(epsilon))
    throw std::invalid_argument(std::string(function) + ": epsilon must be finite and > 0");
}

// The meshes every contour error measures: they cast, know their ellipsoid and qualify as
// smooth casters.
template <typename Visit>
void for_each_analytic_caster(const Scene& scene, double crease_angle_degrees, Visit visit) {
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const SceneMesh& mesh = scene.meshes[m];
    if (!mesh.casts || !mesh.ellipsoid) continue;
    SmoothCasterOptions caster_options;
    caster_options.crease_angle_degrees = crease_angle_degrees;
    const SmoothCasterResult caster = smooth_caster(mesh.soup, caster_options);
    if (caster.caster) visit(m, *caster.caster);
  }
}

using Point4 = std::array<float, 4>;

Vec3 finite_point(const Point4& p) { return {p[0] / p[3], p[1] / p[3], p[2] / p[3]}; }

// X's boundary in `volume`: the finite edge of every side triangle (two finite vertices, one at
// infinity), oriented as the triangle runs it, with opposite segments cancelled and each segment
// left once.
std::vector<std::pair<Point4, Point4>> front_cap_boundary(const HomogeneousMesh& volume) {
  std::map<std::pair<Point4, Point4>, int> net;  // (lower, higher) -> runs lower -> higher minus the reverse
  for (const auto& t : volume.triangles) {
    std::array<bool, 3> finite{};
    for (std::size_t k = 0; k < 3; ++k) {
      if (t[k] >= volume.vertices.size()) throw std::invalid_argument("volume_contour_error: a vertex index out of range");
      finite[k] = volume.vertices[t[k]][3] != 0.0f;
    }
    if (finite[0] + finite[1] + finite[2] != 2) continue;
    const std::size_t k = !finite[0] ? 1 : !finite[1] ? 2 : 0;  // the finite edge runs k -> k + 1
    const Point4& a = volume.vertices[t[k]];
    const Point4& b = volume.vertices[t[(k + 1) % 3]];
    if (a < b) {
      ++net[{a, b}];
    } else {
      --net[{b, a}];
    }
  }
  std::vector<std::pair<Point4, Point4>> out;
  for (const auto& [segment, count] : net)
    if (count != 0) out.push_back(segment);
  return out;
}

void add_mesh(ContourError& e, double& weighted, const BoundaryDistance& d, std::size_t points) {
  e.max = std::max(e.max, d.max);
  weighted += d.mean * static_cast<double>(points);
  e.points += points;
}

}  // namespace

std::optional<ContourError> contour_error(const Scene& scene, std::size_t light, gpu::ShadowMethod method,
                                          double epsilon, const Plane& plane, double crease_angle_degrees) {
  if (!gpu::is_silhouette_method(method))
    throw std::invalid_argument("contour_error: " + std::string(gpu::shadow_method_name(method)) +
                                " is not a smooth-silhouette method");
  // smooth-gpu was once measured here as smooth (the CPU's contour): its own figure is its GPU's.
  if (method == gpu::ShadowMethod::smooth_gpu)
    throw std::invalid_argument(
        "contour_error: smooth-gpu's contour is built on the GPU: measure its volumes "
        "(smooth_gpu_caster_volumes, volume_contour_error)");
  if (light >= scene.lights.size()) throw std::invalid_argument("contour_error: light out of range");
  check_epsilon("contour_error", epsilon);
  const Light& l = scene.lights[light];
  const SilhouetteMethod kind = method == gpu::ShadowMethod::discrete   ? SilhouetteMethod::discrete
                                : method == gpu::ShadowMethod::accurate ? SilhouetteMethod::accurate
                                                                        : SilhouetteMethod::smooth;
  std::optional<ContourError> out;
  double weighted = 0.0;
  for_each_analytic_caster(scene, crease_angle_degrees, [&](std::size_t m, const SmoothCaster& c) {
    const SceneMesh& mesh = scene.meshes[m];
    std::vector<Sign> sides;
    if (kind == SilhouetteMethod::discrete)
      for (const Triangle& t : c.triangles)
        sides.push_back(light_orientation(c.vertices[t[0]], c.vertices[t[1]], c.vertices[t[2]], l));
    const double eps = mesh.epsilon.value_or(epsilon);
    const SmoothVolume volume = smooth_shadow_volume(c, l, {kind, eps, 0.0}, sides);
    const std::vector<Vec3> truth = ellipsoid_shadow_boundary(*mesh.ellipsoid, l, plane, kContourTruthSamples);
    ContourError& e = out ? *out : out.emplace();
    ++e.casters;
    for (std::size_t k = 0; k < volume.loops.size(); ++k) {
      std::vector<Vec3> boundary;
      if (kind == SilhouetteMethod::smooth) {
        for (const ContourPoint& p : volume.contours[k].points) boundary.push_back(shadow_on_plane(p.position, l, plane));
      } else {
        for (const SilhouettePoint& p : volume.loops[k].points) boundary.push_back(shadow_on_plane(p.position, l, plane));
      }
      if (boundary.size() < 2) continue;
      add_mesh(e, weighted, boundary_distance(boundary, volume.loops[k].closed, truth), boundary.size());
    }
  });
  if (out && out->points > 0) out->mean = weighted / static_cast<double>(out->points);
  return out;
}

std::optional<ContourError> volume_contour_error(const Scene& scene, std::size_t light,
                                                 std::span<const CasterVolume> volumes, const Plane& plane) {
  if (light >= scene.lights.size()) throw std::invalid_argument("volume_contour_error: light out of range");
  const Light& l = scene.lights[light];
  std::optional<ContourError> out;
  double weighted = 0.0;
  for (const CasterVolume& v : volumes) {
    if (v.mesh >= scene.meshes.size()) throw std::invalid_argument("volume_contour_error: mesh out of range");
    const SceneMesh& mesh = scene.meshes[v.mesh];
    if (!mesh.ellipsoid)
      throw std::invalid_argument("volume_contour_error: mesh " + mesh.name + " records no ellipsoid");
    const std::vector<std::pair<Point4, Point4>> segments = front_cap_boundary(v.volume);
    if (segments.empty()) continue;
    const std::vector<Vec3> truth = ellipsoid_shadow_boundary(*mesh.ellipsoid, l, plane, kContourTruthSamples);
    // boundary_distance on each segment alone: its 8 samples, ends included, as on a loop.
    BoundaryDistance d;
    double length = 0.0, along = 0.0;
    std::set<Point4> ends;
    for (const auto& [a, b] : segments) {
      const std::array<Vec3, 2> s{shadow_on_plane(finite_point(a), l, plane), shadow_on_plane(finite_point(b), l, plane)};
      const BoundaryDistance one = boundary_distance(s, false, truth);
      const Vec3 ab = difference(s[1], s[0]);
      const double seg = std::sqrt(dot(ab, ab));
      d.max = std::max(d.max, one.max);
      along += seg * one.mean;
      length += seg;
      ends.insert(a);
      ends.insert(b);
    }
    d.mean = length > 0.0 ? along / length : d.max;
    ContourError& e = out ? *out : out.emplace();
    ++e.casters;
    add_mesh(e, weighted, d, ends.size());
  }
  if (out && out->points > 0) out->mean = weighted / static_cast<double>(out->points);
  return out;
}

std::vector<CasterVolume> smooth_gpu_caster_volumes(const Scene& scene, std::size_t light, double epsilon,
                                                    double crease_angle_degrees) {
  if (light >= scene.lights.size()) throw std::invalid_argument("smooth_gpu_caster_volumes: light out of range");
  check_epsilon("smooth_gpu_caster_volumes", epsilon);
  std::vector<CasterVolume> out;
  for_each_analytic_caster(scene, crease_angle_degrees, [&](std::size_t m, const SmoothCaster& c) {
    gpu::SmoothCasterArrays arrays;
    append_smooth_caster(arrays, c, scene.meshes[m].epsilon.value_or(epsilon), 0.0);
    const gpu::SmoothCasterBuffers buffers(arrays);
    gpu::SmoothSilhouetteVolume volume(buffers);
    volume.build(scene.lights[light]);
    if (volume.read_requested_vertices() > volume.capacity_vertices())
      throw gpu::VolumeCapacityError("the smooth-gpu volume needs more vertices than one GL storage buffer holds (" +
                                     std::to_string(volume.capacity_vertices()) + ")");
    CasterVolume& v = out.emplace_back();
    v.mesh = m;
    for (const gpu::VolumeTriangle& t : volume.read_triangles()) {
      const auto first = static_cast<std::uint32_t>(v.volume.vertices.size());
      v.volume.vertices.insert(v.volume.vertices.end(), t.begin(), t.end());
      v.volume.triangles.push_back({first, first + 1, first + 2});
    }
  });
  return out;
}

}  // namespace shadowcert
