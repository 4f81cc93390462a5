#include "pipeline/contour_error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "contour/smooth_volume.h"
#include "exact/light_orientation.h"

namespace shadowcert {

std::optional<ContourError> contour_error(const Scene& scene, std::size_t light, gpu::ShadowMethod method,
                                          double epsilon, const Plane& plane, double crease_angle_degrees) {
  if (!gpu::is_silhouette_method(method))
    throw std::invalid_argument("contour_error: " + std::string(gpu::shadow_method_name(method)) +
                                " is not a smooth-silhouette method");
  if (light >= scene.lights.size()) throw std::invalid_argument("contour_error: light out of range");
  if (!(epsilon > 0.0) || !std::isfinite(epsilon))
    throw std::invalid_argument("contour_error: epsilon must be finite and > 0");
  const Light& l = scene.lights[light];
  const SilhouetteMethod kind = method == gpu::ShadowMethod::discrete   ? SilhouetteMethod::discrete
                                : method == gpu::ShadowMethod::accurate ? SilhouetteMethod::accurate
                                                                        : SilhouetteMethod::smooth;
  std::optional<ContourError> out;
  double weighted = 0.0;
  for (const SceneMesh& mesh : scene.meshes) {
    if (!mesh.casts || !mesh.ellipsoid) continue;
    SmoothCasterOptions caster_options;
    caster_options.crease_angle_degrees = crease_angle_degrees;
    const SmoothCasterResult caster = smooth_caster(mesh.soup, caster_options);
    if (!caster.caster) continue;
    const SmoothCaster& c = *caster.caster;
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
      const BoundaryDistance d = boundary_distance(boundary, volume.loops[k].closed, truth);
      e.max = std::max(e.max, d.max);
      weighted += d.mean * static_cast<double>(boundary.size());
      e.points += boundary.size();
    }
  }
  if (out && out->points > 0) out->mean = weighted / static_cast<double>(out->points);
  return out;
}

}  // namespace shadowcert
