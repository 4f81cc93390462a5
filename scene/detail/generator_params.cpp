#include "scene/detail/generator_params.h"

#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/procedural_mesh.h"
#include "scene/sphere_grid_layout.h"

namespace shadowcert {
namespace {

constexpr std::uint64_t kU32 = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint64_t kU64 = std::numeric_limits<std::uint64_t>::max();

std::uint32_t u32_or(const JsonField& p, std::string_view key, std::uint32_t fallback) {
  return static_cast<std::uint32_t>(unsigned_or(p, key, kU32, fallback));
}

// Defaults: unit-sized shapes at the origin, resolutions fine enough for smooth shading.
GeneratedMesh floor_from(const JsonField& p) {
  p.require_keys_within({"half_size"});
  return {floor_quad(number_or(p, "half_size", 10.0)), std::nullopt};
}

GeneratedMesh box_from(const JsonField& p) {
  p.require_keys_within({"min", "max"});
  return {box(vec3_or(p, "min", {-0.5, -0.5, -0.5}), vec3_or(p, "max", {0.5, 0.5, 0.5})), std::nullopt};
}

// The sphere of centre `centre` and radius `radius` as an ellipsoid: axes r e_x, r e_y, r e_z.
Ellipsoid sphere_ellipsoid(const Vec3& centre, double radius) {
  return {centre, {{{radius, 0, 0}, {0, radius, 0}, {0, 0, radius}}}};
}

// The spheres record the surface they approximate (their vertices lie on it).
GeneratedMesh uv_sphere_from(const JsonField& p) {
  p.require_keys_within({"center", "radius", "slices", "stacks"});
  const Vec3 centre = vec3_or(p, "center", {0, 0, 0});
  const double radius = number_or(p, "radius", 1.0);
  Soup soup = uv_sphere(centre, radius, u32_or(p, "slices", 32), u32_or(p, "stacks", 16));
  return {std::move(soup), sphere_ellipsoid(centre, radius)};
}

GeneratedMesh icosphere_from(const JsonField& p) {
  p.require_keys_within({"center", "radius", "subdivisions"});
  const Vec3 centre = vec3_or(p, "center", {0, 0, 0});
  const double radius = number_or(p, "radius", 1.0);
  Soup soup = icosphere(centre, radius, u32_or(p, "subdivisions", 3));
  return {std::move(soup), sphere_ellipsoid(centre, radius)};
}

GeneratedMesh torus_from(const JsonField& p) {
  p.require_keys_within({"center", "major_radius", "minor_radius", "major_segments", "minor_segments"});
  return {torus(vec3_or(p, "center", {0, 0, 0}), number_or(p, "major_radius", 1.0), number_or(p, "minor_radius", 0.25),
                u32_or(p, "major_segments", 48), u32_or(p, "minor_segments", 24)), std::nullopt};
}

GeneratedMesh torus_knot_from(const JsonField& p) {
  p.require_keys_within({"center", "p", "q", "major_radius", "knot_radius", "tube_radius", "segments", "tube_segments"});
  return {torus_knot(vec3_or(p, "center", {0, 0, 0}), u32_or(p, "p", 2), u32_or(p, "q", 3), number_or(p, "major_radius", 1.0),
                     number_or(p, "knot_radius", 0.4), number_or(p, "tube_radius", 0.12), u32_or(p, "segments", 128),
                     u32_or(p, "tube_segments", 12)), std::nullopt};
}

GeneratedMesh sphere_grid_from(const JsonField& p) {
  p.require_keys_within({"triangles"});
  return {sphere_grid(unsigned_or(p, "triangles", kSphereGridMaxTriangles, 1'000'000)), std::nullopt};
}

GeneratedMesh random_soup_from(const JsonField& p) {
  p.require_keys_within({"seed", "triangles", "extent"});
  return {random_soup(unsigned_or(p, "seed", kU64, 1), unsigned_or(p, "triangles", kU32 / 3, 100),
                      number_or(p, "extent", 1.0)), std::nullopt};
}

GeneratedMesh nonmanifold_fan_from(const JsonField& p) {
  p.require_keys_within({"k"});
  return {nonmanifold_fan(u32_or(p, "k", 8)), std::nullopt};
}

GeneratedMesh open_box_with_fins_from(const JsonField& p) {
  p.require_keys_within({});
  return {open_box_with_fins(), std::nullopt};
}

struct Generator {
  std::string_view name;
  GeneratedMesh (*make)(const JsonField& params);
};

constexpr std::array<Generator, 10> kGenerators{{{"floor", floor_from},
                                                {"box", box_from},
                                                {"uv_sphere", uv_sphere_from},
                                                {"icosphere", icosphere_from},
                                                {"torus", torus_from},
                                                {"torus_knot", torus_knot_from},
                                                {"sphere_grid", sphere_grid_from},
                                                {"random_soup", random_soup_from},
                                                {"nonmanifold_fan", nonmanifold_fan_from},
                                                {"open_box_with_fins", open_box_with_fins_from}}};

[[noreturn]] void fail_unknown(const JsonField& name_field, const std::string& name) {
  std::string message = "unknown generator '" + name + "'";
  std::vector<std::string_view> names;
  for (const Generator& g : kGenerators) names.push_back(g.name);
  const std::string hint = closest_name(name, names);
  if (!hint.empty()) {
    message += " (did you mean '" + hint + "'?)";
  } else {
    message += " (known:";
    for (const Generator& g : kGenerators) message.append(" ").append(g.name);
    message += ")";
  }
  name_field.fail(message);
}

}  // namespace

GeneratedMesh run_generator(const JsonField& name_field, const std::optional<JsonField>& params) {
  const std::string name = name_field.string();
  for (const Generator& g : kGenerators) {
    if (g.name != name) continue;
    // An absent "params" reads as {}: every parameter takes its default.
    const nlohmann::json empty = nlohmann::json::object();
    const JsonField& p = params ? *params : JsonField(empty, name_field.file_name());
    try {
      return g.make(p);
    } catch (const std::invalid_argument& e) {
      // The generator's own range check ("uv_sphere: slices must be >= 3, got 2").
      (params ? *params : name_field).fail(e.what());
    }
  }
  fail_unknown(name_field, name);
}

}  // namespace shadowcert
