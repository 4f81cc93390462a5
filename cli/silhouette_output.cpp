#include "cli/silhouette_output.h"

#include <fmt/core.h>

#include <string>

namespace shadowcert::cli {

void add_silhouette_options(CLI::App& command, SilhouetteOptions& options) {
  command.add_option("--epsilon", options.epsilon,
                     "smooth: how far the smooth contour may stay from the surface the normals describe, world units")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command.add_option("--crease-angle", options.crease_angle_degrees,
                     "discrete, accurate, smooth: dihedral angle in degrees above which an edge keeps each side's "
                     "normals (computed normals only)")
      ->check(CLI::Range(0.0, 180.0))
      ->capture_default_str();
}

nlohmann::json silhouette_casters_json(const SilhouetteVolumes& volumes) {
  nlohmann::json out = nlohmann::json::array();
  for (const SilhouetteCaster& c : volumes.casters)
    out.push_back({{"mesh", c.mesh},
                   {"triangles", c.triangles},
                   {"cast_by", c.smooth ? std::string(gpu::shadow_method_name(volumes.method)) : "robust chain"},
                   {"qualification", c.qualification},
                   {"loops", c.loops}});
  return out;
}

void print_silhouette_casters(const SilhouetteVolumes& volumes) {
  const std::string_view method = gpu::shadow_method_name(volumes.method);
  for (const SilhouetteCaster& c : volumes.casters) {
    if (c.smooth)
      fmt::print("  {}: {} ({} triangles) cast by {}, {} loop{}\n", method, c.mesh, c.triangles, method, c.loops,
                 c.loops == 1 ? "" : "s");
    else
      fmt::print("  {}: {} ({} triangles) cast by the robust chain: {}\n", method, c.mesh, c.triangles, c.qualification);
  }
}

}  // namespace shadowcert::cli
