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

namespace {

// "discrete", "accurate", "smooth", "smooth-gpu", "robust chain" or "nothing" (the JSON's "cast_by").
std::string cast_by_name(const SilhouetteCaster& c) {
  if (c.cast_by) return std::string(gpu::shadow_method_name(*c.cast_by));
  return c.casts ? "robust chain" : "nothing";
}

}  // namespace

nlohmann::json silhouette_casters_json(const SilhouetteVolumes& volumes) {
  nlohmann::json out = nlohmann::json::array();
  for (const SilhouetteCaster& c : volumes.casters)
    out.push_back({{"mesh", c.mesh},
                   {"triangles", c.triangles},
                   {"cast_by", cast_by_name(c)},
                   {"epsilon", c.cast_by == gpu::ShadowMethod::smooth || c.cast_by == gpu::ShadowMethod::smooth_gpu
                                   ? nlohmann::json(c.epsilon)
                                   : nlohmann::json()},
                   {"qualification", c.qualification},
                   {"loops", c.loops}});
  return out;
}

void print_silhouette_casters(const SilhouetteVolumes& volumes) {
  const std::string_view method = gpu::shadow_method_name(volumes.method);
  for (const SilhouetteCaster& c : volumes.casters) {
    if (!c.cast_by)
      fmt::print("  {}: {} ({} triangles) {}: {}\n", method, c.mesh, c.triangles,
                 c.casts ? "cast by the robust chain" : "casts nothing", c.qualification);
    else if (c.cast_by == gpu::ShadowMethod::smooth_gpu)
      fmt::print("  {}: {} ({} triangles) cast by smooth-gpu (epsilon {}), built on the GPU per triangle\n", method,
                 c.mesh, c.triangles, c.epsilon);
    else if (c.cast_by == gpu::ShadowMethod::smooth)
      fmt::print("  {}: {} ({} triangles) cast by smooth (epsilon {}), {} loop{}\n", method, c.mesh, c.triangles,
                 c.epsilon, c.loops, c.loops == 1 ? "" : "s");
    else
      fmt::print("  {}: {} ({} triangles) cast by {}, {} loop{}\n", method, c.mesh, c.triangles,
                 gpu::shadow_method_name(*c.cast_by), c.loops, c.loops == 1 ? "" : "s");
  }
}

}  // namespace shadowcert::cli
