#include "pipeline/silhouette_volumes.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/float_rounding.h"
#include "core/vector3.h"
#include "exact/cpu_volume.h"
#include "gpu/depth_precision.h"
#include "pipeline/smooth_caster_arrays.h"
#include "exact/light_orientation.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"

namespace shadowcert {
namespace {

SilhouetteMethod contour_method(gpu::ShadowMethod method) {
  switch (method) {
    case gpu::ShadowMethod::discrete: return SilhouetteMethod::discrete;
    case gpu::ShadowMethod::accurate: return SilhouetteMethod::accurate;
    case gpu::ShadowMethod::smooth:
    case gpu::ShadowMethod::smooth_gpu: return SilhouetteMethod::smooth;
    default: break;
  }
  throw std::invalid_argument("silhouette_volumes: " + std::string(gpu::shadow_method_name(method)) +
                              " is not a smooth-silhouette method");
}

gpu::ShadowMethod shadow_method(SilhouetteMethod kind) {
  switch (kind) {
    case SilhouetteMethod::discrete: return gpu::ShadowMethod::discrete;
    case SilhouetteMethod::accurate: return gpu::ShadowMethod::accurate;
    case SilhouetteMethod::smooth: break;
  }
  return gpu::ShadowMethod::smooth;
}

// The method `mesh` asks to be cast by, the command's `kind` unless it says otherwise; nullopt:
// the robust chain.
std::optional<SilhouetteMethod> mesh_method(const SceneMesh& mesh, SilhouetteMethod kind) {
  if (!mesh.silhouette) return kind;
  switch (*mesh.silhouette) {
    case MeshSilhouette::chain: return std::nullopt;
    case MeshSilhouette::discrete: return SilhouetteMethod::discrete;
    case MeshSilhouette::accurate: return SilhouetteMethod::accurate;
    case MeshSilhouette::smooth: break;
  }
  return SilhouetteMethod::smooth;
}

bool valid_epsilon(double epsilon) { return epsilon > 0.0 && std::isfinite(epsilon); }

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
  if (kind == SilhouetteMethod::smooth && !valid_epsilon(options.epsilon))
    throw std::invalid_argument("silhouette_volumes: epsilon must be finite and > 0");
  SilhouetteVolumes out;
  out.method = method;
  out.per_light.resize(lights.size());
  std::vector<Light> rounded_lights;
  for (const Light& light : lights) rounded_lights.push_back(float_rounded(light));

  Soup robust;  // the casting meshes that ask for the chain or do not qualify
  for (const SceneMesh& mesh : meshes) {
    SilhouetteCaster report{mesh.name, mesh.soup.triangles.size(), mesh.casts, std::nullopt, 0.0, {}, 0};
    if (mesh.epsilon && !valid_epsilon(*mesh.epsilon))
      throw std::invalid_argument("silhouette_volumes: mesh " + mesh.name + ": epsilon must be finite and > 0");
    if (!mesh.casts) {
      report.qualification = "the scene says it casts nothing";
      out.casters.push_back(std::move(report));
      continue;
    }
    const Soup soup = float_rounded(mesh.soup);
    const std::optional<SilhouetteMethod> asked = mesh_method(mesh, kind);
    if (!asked) {
      report.qualification = "the scene asks for the chain";
      append(robust, soup);
      out.casters.push_back(std::move(report));
      continue;
    }
    SmoothCasterOptions caster_options;
    caster_options.crease_angle_degrees = options.crease_angle_degrees;
    const SmoothCasterResult caster = smooth_caster(soup, caster_options);
    report.qualification = caster.qualification.summary();
    if (!caster.caster) {
      append(robust, soup);
      out.casters.push_back(std::move(report));
      continue;
    }
    const SilhouetteMethod method_here = *asked;
    const bool on_gpu = method == gpu::ShadowMethod::smooth_gpu && method_here == SilhouetteMethod::smooth;
    report.cast_by = on_gpu ? gpu::ShadowMethod::smooth_gpu : shadow_method(method_here);
    if (method_here == SilhouetteMethod::smooth) {
      report.epsilon = mesh.epsilon.value_or(options.epsilon);
      if (!valid_epsilon(report.epsilon))
        throw std::invalid_argument("silhouette_volumes: epsilon must be finite and > 0");
    }
    const SmoothCaster& c = *caster.caster;
    double cap_offset = 0.0;
    if (options.near_plane > 0.0 && method_here != SilhouetteMethod::discrete) {
      double farthest = 0.0;
      for (const Vec3& v : c.vertices) farthest = std::max(farthest, std::sqrt(dot(v, v)));
      cap_offset = gpu::depth_band(farthest, options.near_plane);
    }
    if (on_gpu) {
      append_smooth_caster(out.gpu_casters, c, report.epsilon, cap_offset);
      out.casters.push_back(std::move(report));
      continue;
    }
    for (std::size_t k = 0; k < lights.size(); ++k) {
      std::vector<Sign> sides;
      if (method_here == SilhouetteMethod::discrete)
        for (const Triangle& tri : c.triangles)
          sides.push_back(light_orientation(c.vertices[tri[0]], c.vertices[tri[1]], c.vertices[tri[2]], rounded_lights[k]));
      // report.epsilon is 0 unless smooth, the one method that reads it.
      const SmoothVolume volume =
          smooth_shadow_volume(c, rounded_lights[k], {method_here, report.epsilon, cap_offset}, sides);
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

void capture_gpu_volumes(SilhouetteVolumes& volumes, std::span<const Light> lights) {
  if (lights.size() != volumes.per_light.size())
    throw std::invalid_argument("capture_gpu_volumes: " + std::to_string(lights.size()) + " lights for " +
                                std::to_string(volumes.per_light.size()) + " volumes");
  if (volumes.gpu_casters.triangles.empty()) return;
  const gpu::SmoothCasterBuffers buffers(volumes.gpu_casters);
  gpu::SmoothSilhouetteVolume volume(buffers);
  for (std::size_t k = 0; k < lights.size(); ++k) {
    volume.build(lights[k]);
    if (volume.read_requested_vertices() > volume.capacity_vertices())
      throw gpu::VolumeCapacityError("the smooth-gpu volume needs more vertices than one GL storage buffer holds (" +
                                     std::to_string(volume.capacity_vertices()) + ")");
    HomogeneousMesh& mesh = volumes.per_light[k];
    for (const gpu::VolumeTriangle& t : volume.read_triangles()) {
      const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
      mesh.vertices.insert(mesh.vertices.end(), t.begin(), t.end());
      mesh.triangles.push_back({first, first + 1, first + 2});
    }
  }
}

}  // namespace shadowcert
