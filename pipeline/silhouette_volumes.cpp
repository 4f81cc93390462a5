#include "pipeline/silhouette_volumes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/float_rounding.h"
#include "core/vector3.h"
#include "exact/cpu_volume.h"
#include "gpu/depth_precision.h"
#include "exact/light_orientation.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"

namespace shadowcert {
namespace {

SilhouetteMethod contour_method(gpu::ShadowMethod method) {
  switch (method) {
    case gpu::ShadowMethod::discrete: return SilhouetteMethod::discrete;
    case gpu::ShadowMethod::accurate: return SilhouetteMethod::accurate;
    case gpu::ShadowMethod::smooth: return SilhouetteMethod::smooth;
    default: break;
  }
  throw std::invalid_argument("silhouette_volumes: " + std::string(gpu::shadow_method_name(method)) +
                              " is not a smooth-silhouette method");
}

// `into` += `part`, its indices moved past `into`'s vertices.
void append(HomogeneousMesh& into, const HomogeneousMesh& part) {
  const auto offset = static_cast<std::uint32_t>(into.vertices.size());
  into.vertices.insert(into.vertices.end(), part.vertices.begin(), part.vertices.end());
  for (const auto& t : part.triangles) into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

// Soup `part` appended to `into` (indices moved past its vertices).
void append(Soup& into, const Soup& part) {
  const auto offset = static_cast<std::uint32_t>(into.vertices.size());
  into.vertices.insert(into.vertices.end(), part.vertices.begin(), part.vertices.end());
  for (const Triangle& t : part.triangles) into.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

}  // namespace

SilhouetteVolumes silhouette_volumes(std::span<const SceneMesh> meshes, std::span<const Light> lights,
                                     gpu::ShadowMethod method, const SilhouetteOptions& options) {
  const SilhouetteMethod kind = contour_method(method);
  if (kind == SilhouetteMethod::smooth && !(options.epsilon > 0.0 && std::isfinite(options.epsilon)))
    throw std::invalid_argument("silhouette_volumes: epsilon must be finite and > 0");
  SilhouetteVolumes out;
  out.method = method;
  out.per_light.resize(lights.size());
  std::vector<Light> rounded_lights;
  for (const Light& light : lights) rounded_lights.push_back(float_rounded(light));

  Soup robust;  // the meshes that do not qualify
  for (const SceneMesh& mesh : meshes) {
    const Soup soup = float_rounded(mesh.soup);
    SilhouetteCaster report{mesh.name, soup.triangles.size(), false, {}, 0};
    SmoothCasterOptions caster_options;
    caster_options.crease_angle_degrees = options.crease_angle_degrees;
    const SmoothCasterResult caster = smooth_caster(soup, caster_options);
    report.qualification = caster.qualification.summary();
    if (!caster.caster) {
      append(robust, soup);
      out.casters.push_back(std::move(report));
      continue;
    }
    report.smooth = true;
    const SmoothCaster& c = *caster.caster;
    double cap_offset = 0.0;
    if (options.near_plane > 0.0 && kind != SilhouetteMethod::discrete) {
      double farthest = 0.0;
      for (const Vec3& v : c.vertices) farthest = std::max(farthest, std::sqrt(dot(v, v)));
      cap_offset = gpu::depth_band(farthest, options.near_plane);
    }
    for (std::size_t k = 0; k < lights.size(); ++k) {
      std::vector<Sign> sides;
      if (kind == SilhouetteMethod::discrete)
        for (const Triangle& tri : c.triangles)
          sides.push_back(light_orientation(c.vertices[tri[0]], c.vertices[tri[1]], c.vertices[tri[2]], rounded_lights[k]));
      const SmoothVolume volume = smooth_shadow_volume(c, rounded_lights[k], {kind, options.epsilon, cap_offset}, sides);
      if (k == 0) report.loops = volume.loops.size();
      append(out.per_light[k], volume.mesh);
    }
    out.casters.push_back(std::move(report));
  }
  if (!robust.triangles.empty()) {
    const CanonicalSoup canonical = canonical_soup(robust);
    const EdgeTable table = build_edge_table(canonical.soup);
    for (std::size_t k = 0; k < lights.size(); ++k) append(out.per_light[k], cpu_volume_mesh(canonical.soup, table, lights[k]));
  }
  return out;
}

}  // namespace shadowcert
