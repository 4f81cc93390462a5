#pragma once
// The hard cases of docs/definitions.md#hard-cases: the soups tests/exact/hard_cases_test.cpp certifies (one builder
// each, the only copy), and the same configurations as named (soup, light) scenes for tests
// that run every method over all of them (tests/campaign/float_method_hard_cases_test.cpp).
// Header-only, test code only.
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "support/certificate_test_support.h"
#include "scene/hard_soups.h"
#include "scene/procedural_mesh.h"

namespace shadowcert::test_support {

struct HardCaseScene {
  std::string name;
  Soup soup;
  Light light;
};

inline Soup translated(Soup s, const Vec3& by) {
  for (Vec3& v : s.vertices)
    for (int i = 0; i < 3; ++i) v[i] += by[i];
  return s;
}

inline Soup scaled(Soup s, double factor) {
  for (Vec3& v : s.vertices)
    for (double& x : v) x *= factor;
  return s;
}

// A cube standing on a floor: the floor's triangles are exactly coplanar with y = 0.
inline Soup cube_on_floor() {
  Soup s = floor_quad(3.0);
  append(s, box({-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}));
  return s;
}

// The hard cases' small soups, one copy (scene/hard_soups.h): half_fan(k) (|m| = k with the
// light in the plane z = 0), slivers().
using ::shadowcert::half_fan;
using ::shadowcert::slivers;

// A unit cube plus faces with repeated indices, and one naming a bitwise copy of a vertex.
inline Soup repeated_indices() {
  Soup s = unit_cube();
  s.triangles.push_back({0, 0, 7});
  s.triangles.push_back({3, 3, 3});
  s.triangles.push_back({1, 5, 1});
  s.vertices.push_back(s.vertices[6]);  // a bitwise duplicate vertex, welded to 6
  s.triangles.push_back({6, 8, 2});
  return s;
}

// Every face of a unit cube twice, every third one a third time reversed.
inline Soup duplicated_triangles() {
  Soup s = unit_cube();
  const std::size_t n = s.triangles.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Triangle t = s.triangles[i];
    s.triangles.push_back(t);
    if (i % 3 == 0) s.triangles.push_back({t[0], t[2], t[1]});
  }
  return s;
}

// Three overlapping squares in y = 0 and a coplanar pair in y = 1.
inline Soup coplanar_overlaps() {
  Soup s = floor_quad(1.0);
  append(s, translated(floor_quad(1.0), {0.5, 0.0, 0.25}));
  append(s, translated(floor_quad(0.5), {0.0, 0.0, 0.0}));
  append(s, translated(floor_quad(1.0), {0.0, 1.0, 0.0}));  // and a coplanar pair above
  append(s, translated(floor_quad(0.75), {0.25, 1.0, 0.0}));
  return s;
}

// Coordinates offset by kFarOffset with 1e-3 features: a small sphere and a small cube.
inline constexpr Vec3 kFarOffset{1e6, 1e6, -1e6};
inline Soup offset_1e6_features() {
  Soup s = translated(scaled(uv_sphere({0, 0, 0}, 1.0, 10, 5), 1e-3), kFarOffset);
  append(s, translated(scaled(unit_cube(), 1e-3), {kFarOffset[0] + 2e-3, kFarOffset[1], kFarOffset[2]}));
  return s;
}

// A unit cube and a sphere beside it, scaled about the origin.
inline Soup cube_and_sphere_scaled(double scale) {
  Soup s = scaled(unit_cube(), scale);
  append(s, scaled(uv_sphere({2.0, 0.5, 0.5}, 0.6, 12, 6), scale));
  return s;
}

// scene/hard_soups.h: a T-junction and a 0.001 crack; two tetrahedra and two triangles sharing
// only a vertex.
using ::shadowcert::bow_ties;
using ::shadowcert::t_junctions_and_cracks;

// Soups snapped to the grid {-2, ..., 2}^3: 20 vertices, 40 triangles each (repeated indices
// and collinear triples included), each with a point light at y = 3 and a directional light,
// all drawn from one std::mt19937_64(seed) in that order.
struct GridSoup {
  Soup soup;
  Light point;
  Light directional;
};
inline std::vector<GridSoup> integer_grid_soups(std::uint64_t seed, int rounds) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> grid(-2, 2);
  std::vector<GridSoup> soups;
  for (int round = 0; round < rounds; ++round) {
    Soup s;
    for (int i = 0; i < 20; ++i) s.vertices.push_back({double(grid(rng)), double(grid(rng)), double(grid(rng))});
    std::uniform_int_distribution<std::uint32_t> pick(0, 19);
    for (int i = 0; i < 40; ++i) s.triangles.push_back({pick(rng), pick(rng), pick(rng)});
    const Light point = point_light(grid(rng), 3.0, grid(rng));
    const Light directional = directional_light(grid(rng), 1.0, grid(rng));
    soups.push_back({std::move(s), point, directional});
  }
  return soups;
}

// The pinned soup of tests/exact/closure_certificate_test.cpp: two triangles on a tilted plane
// through the light, up to the rounding of every coordinate to float.
inline HardCaseScene pinned_tilted_plane() {
  return {"pinned tilted plane through the light",
          soup_of({{-0x1.2e5834p+1, 0x1.69abdap+1, -0x1.5f31ap+1},
                   {-0x1.3d9ae6p+0, 0x1.cbdd66p+1, -0x1.12dd5p+1},
                   {-0x1.de841cp+1, 0x1.e98b84p+1, -0x1.01dcbap+2},
                   {-0x1.e9ad6cp+1, 0x1.d2b9e6p+1, -0x1.02aa1p+2}},
                  {{0, 1, 2}, {1, 3, 2}}),
          Light{{-0x1.b79118p-2, -0x1.0e081p-1, -0x1.878fbp-2, 1.0}}};
}

inline std::vector<HardCaseScene> hard_case_scenes() {
  std::vector<HardCaseScene> scenes;
  auto add = [&scenes](std::string name, Soup soup, Light light) {
    scenes.push_back({std::move(name), std::move(soup), light});
  };
  add("light on the floor's plane", cube_on_floor(), point_light(5.0, 0.0, 0.75));
  const Soup raised = translated(cube_on_floor(), {0.0, 1.0, 0.0});
  add("light one ulp above the floor's plane", raised, point_light(5.0, std::nextafter(1.0, 2.0), 0.75));
  add("light one ulp below the floor's plane", raised, point_light(5.0, std::nextafter(1.0, 0.0), 0.75));
  add("light on a cube edge's line", unit_cube(), point_light(3.0, 0.0, 0.0));
  add("light on a sphere's pole axis", uv_sphere({0, 0, 0}, 1.0, 12, 6), point_light(0.0, 5.0, 0.0));
  add("light at a cube vertex", unit_cube(), point_light(1.0, 1.0, 1.0));
  Soup two_boxes = unit_cube();
  append(two_boxes, box({2.0, 0.0, 0.0}, {3.0, 1.0, 1.0}));
  add("light at a vertex between two boxes", two_boxes, point_light(2.0, 1.0, 0.0));
  add("grazing, sliver and zero-area triangles, light above", slivers(), point_light(0.7, 5.0, 1e-9));
  add("grazing, sliver and zero-area triangles, light grazing", slivers(), point_light(9.0, 1e-12, 0.0));
  add("repeated indices", repeated_indices(), point_light(0.3, 3.0, 0.4));
  const Soup duplicated = duplicated_triangles();
  add("duplicate and flipped duplicate triangles, point light", duplicated, point_light(0.3, 3.0, 0.4));
  add("duplicate and flipped duplicate triangles, directional light", duplicated, directional_light(0.2, 1.0, -0.3));
  add("coplanar overlaps", coplanar_overlaps(), point_light(0.2, 4.0, 0.3));
  for (std::uint32_t k : {1u, 2u, 33u, 256u})
    add("half fan of " + std::to_string(k) + " on one edge", half_fan(k), point_light(-3.0, 0.5, 0.0));
  add("non-manifold fan of 256", nonmanifold_fan(256), point_light(0.3, 0.45, 2.0));
  const Vec3& offset = kFarOffset;
  const Soup far = offset_1e6_features();
  add("offset 1e6 with 1e-3 features, point light", far,
      point_light(offset[0] + 1e-3, offset[1] + 5e-3, offset[2] + 2e-4));
  add("offset 1e6 with 1e-3 features, directional light", far, directional_light(0.1, 1.0, 0.2));
  for (const double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
    const Soup s = cube_and_sphere_scaled(scale);
    char name[64];
    std::snprintf(name, sizeof name, "cube and sphere at scale %g", scale);
    add(name, s, point_light(1.1 * scale, 4.0 * scale, 0.3 * scale));
  }
  const Soup cracks = t_junctions_and_cracks();
  add("T-junctions and cracks", cracks, point_light(1.2, 3.0, 0.4));
  add("T-junctions and cracks, light above the T vertex", cracks, point_light(1.0, 3.0, 0.5));
  const Soup bow_tie_soup = bow_ties();
  add("bow-tie vertices", bow_tie_soup, point_light(0.2, 3.0, 0.1));
  add("bow-tie vertices, light on the axis through the shared vertex", bow_tie_soup, point_light(0.0, 0.0, 4.0));
  add("directional light parallel to cube faces (x)", unit_cube(), directional_light(1.0, 0.0, 0.0));
  add("directional light parallel to cube faces (z)", unit_cube(), directional_light(1.0, 1.0, 0.0));
  add("directional light parallel to the floor", cube_on_floor(), directional_light(0.0, 0.0, -1.0));
  add("light above a cube on a floor (camera inside a volume)", cube_on_floor(), point_light(0.1, 4.0, 0.2));
  add("light inside a closed sphere", uv_sphere({0, 0, 0}, 1.0, 16, 8), point_light(0.1, 0.2, -0.05));
  add("light inside a closed cube", unit_cube(), point_light(0.5, 0.5, 0.5));
  // Soups snapped to the grid {-2, ..., 2}^3, as in tests/exact/hard_cases_test.cpp (seed 128).
  int round = 0;
  for (const GridSoup& g : integer_grid_soups(128, 4)) {
    add("integer grid soup " + std::to_string(round) + ", point light", g.soup, g.point);
    add("integer grid soup " + std::to_string(round) + ", directional light", g.soup, g.directional);
    ++round;
  }
  scenes.push_back(pinned_tilted_plane());
  return scenes;
}

}  // namespace shadowcert::test_support
