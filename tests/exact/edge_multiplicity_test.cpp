// Multiplicities of the four methods (exact/edge_multiplicity.h) against an independent
// brute force: exact integer determinants (tests/exact/brute_force_orientation.h) summed per edge in a
// std::map, with the sign convention of docs/definitions.md#counts, m(u, v) = - sum sign D(u, v, o, L).
#include "exact/edge_multiplicity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <utility>

#include "brute_force_orientation.h"
#include "core/light_side_formula.h"
#include "scene/edge_table.h"
#include "scene/canonical_soup.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

Light point_light(const Vec3& p) { return Light{{p[0], p[1], p[2], 1.0}}; }
Light directional_light(const Vec3& d) { return Light{{d[0], d[1], d[2], 0.0}}; }

struct Variant {
  MultiplicityMethod method;
  Precision precision;
};
const std::vector<Variant> kAllVariants = {
    {MultiplicityMethod::exact, Precision::float64},   {MultiplicityMethod::kim, Precision::float64},
    {MultiplicityMethod::kim, Precision::float32},     {MultiplicityMethod::peciva, Precision::float64},
    {MultiplicityMethod::peciva, Precision::float32},  {MultiplicityMethod::refedge, Precision::float64},
    {MultiplicityMethod::refedge, Precision::float32}};
const std::vector<Variant> kDoubleVariants = {{MultiplicityMethod::exact, Precision::float64},
                                              {MultiplicityMethod::kim, Precision::float64},
                                              {MultiplicityMethod::peciva, Precision::float64},
                                              {MultiplicityMethod::refedge, Precision::float64}};

std::string describe(const Variant& v) {
  return std::string(method_name(v.method)) + (v.precision == Precision::float32 ? "/float" : "/double");
}

struct Prepared {
  Soup soup;  // canonical
  EdgeTable table;
};

Prepared prepare(const Soup& input) {
  Prepared p{canonical_soup(input).soup, {}};
  p.table = build_edge_table(p.soup);
  return p;
}

bool distinct(const Triangle& t) { return t[0] != t[1] && t[1] != t[2] && t[0] != t[2]; }

// ---- brute force, independent of exact/ ---------------------------------------------------

int brute_d(const Soup& s, std::uint32_t a, std::uint32_t b, std::uint32_t c, const Light& light) {
  return brute::light_orientation(s.vertices[a], s.vertices[b], s.vertices[c], light.position);
}

std::vector<int> brute_caps(const Soup& s, const Light& light) {
  std::vector<int> caps;
  for (const Triangle& t : s.triangles) caps.push_back(distinct(t) ? brute_d(s, t[0], t[1], t[2], light) : 0);
  return caps;
}

using EdgeKey = std::pair<std::uint32_t, std::uint32_t>;

std::map<EdgeKey, int> brute_multiplicities(const Soup& s, const Light& light) {
  std::map<EdgeKey, int> m;
  for (const Triangle& t : s.triangles) {
    if (!distinct(t)) continue;
    const bool casts = brute_d(s, t[0], t[1], t[2], light) != 0;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = std::min(t[k], t[(k + 1) % 3]), v = std::max(t[k], t[(k + 1) % 3]);
      const std::uint32_t o = t[(k + 2) % 3];
      m[{u, v}] -= casts ? brute_d(s, u, v, o, light) : 0;  // docs/definitions.md#counts
    }
  }
  return m;
}

std::map<EdgeKey, int> as_map(const EdgeTable& table, const std::vector<std::int32_t>& m) {
  std::map<EdgeKey, int> out;
  for (std::size_t e = 0; e < table.size(); ++e) out[{table.edges[e][0], table.edges[e][1]}] = m[e];
  return out;
}

std::vector<int> as_ints(const std::vector<Sign>& signs) {
  std::vector<int> out;
  for (Sign s : signs) out.push_back(to_int(s));
  return out;
}

// +1 when (x, y, z) is an even permutation of (t0, t1, t2), -1 when odd (indices distinct).
int permutation_parity(const Triangle& t, std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  auto position = [&t](std::uint32_t v) { return static_cast<int>(std::find(t.begin(), t.end(), v) - t.begin()); };
  const int p[3] = {position(x), position(y), position(z)};
  const int inversions = (p[0] > p[1]) + (p[0] > p[2]) + (p[1] > p[2]);
  return inversions % 2 == 0 ? 1 : -1;
}

void expect_matches_brute_force(const Prepared& p, const Light& light, const std::vector<Variant>& variants) {
  const std::map<EdgeKey, int> expected = brute_multiplicities(p.soup, light);
  const std::vector<int> expected_caps = brute_caps(p.soup, light);
  for (const Variant& v : variants) {
    const EdgeMultiplicities got = edge_multiplicities(v.method, p.soup, p.table, light, v.precision);
    EXPECT_EQ(as_map(p.table, got.multiplicity), expected) << describe(v);
    EXPECT_EQ(as_ints(got.triangle_sign), expected_caps) << describe(v);
  }
}

// Every entry's sign equals the triangle's cap sign times the permutation parity: the
// consistency that makes the chain closed (docs/definitions.md#counts).
std::size_t count_inconsistent_entries(const Prepared& p, const Light& light, const Variant& v) {
  const EdgeMultiplicities m = edge_multiplicities(v.method, p.soup, p.table, light, v.precision);
  const std::vector<Sign> entries = edge_entry_signs(v.method, p.soup, p.table, light, v.precision);
  std::size_t inconsistent = 0;
  for (std::size_t e = 0; e < p.table.size(); ++e) {
    const auto [u, w] = p.table.edges[e];
    int sum = 0;
    for (std::uint32_t i = p.table.first_opposite[e]; i < p.table.first_opposite[e + 1]; ++i) {
      const std::uint32_t t = p.table.opposite_triangle[i];
      const int expected = to_int(m.triangle_sign[t]) * permutation_parity(p.soup.triangles[t], u, w,
                                                                             p.table.opposite_vertex[i]);
      inconsistent += to_int(entries[i]) != expected;
      sum += to_int(entries[i]);
    }
    EXPECT_EQ(m.multiplicity[e], -sum) << describe(v) << ": the sums and the entries disagree";
  }
  return inconsistent;
}

// ---- soups ---------------------------------------------------------------------------------

// k triangles on the edge (0,0,0)-(0,1,0), all ordered (0, 1, apex), apexes at angles in
// (0, pi/2) around the edge: a light at x > 0, z < 0 sees every blade from the same side.
Soup same_side_fan(std::uint32_t k) {
  Soup s;
  s.vertices = {{0, 0, 0}, {0, 1, 0}};
  for (std::uint32_t i = 0; i < k; ++i) {
    const double angle = (i + 1.0) / (k + 1.0) * std::acos(0.0);
    s.vertices.push_back({std::cos(angle), 0.5, std::sin(angle)});
    s.triangles.push_back({0, 1, i + 2});
  }
  return s;
}

// Random triangles over a shared pool of vertices (so edges carry 0..many triangles), with
// coordinates from `coordinate`.
template <typename Coordinate>
Soup pooled_soup(std::mt19937_64& engine, std::uint32_t vertices, std::uint32_t triangles, Coordinate coordinate) {
  Soup s;
  for (std::uint32_t i = 0; i < vertices; ++i) s.vertices.push_back({coordinate(), coordinate(), coordinate()});
  for (std::uint32_t t = 0; t < triangles; ++t)
    s.triangles.push_back({static_cast<std::uint32_t>(engine() % vertices),
                           static_cast<std::uint32_t>(engine() % vertices),
                           static_cast<std::uint32_t>(engine() % vertices)});
  return s;
}

// An n x n grid on the tilted plane z = 0.1 x + 0.37 y (rounded per vertex, so only nearly
// coplanar), two triangles per cell with alternating diagonals.
Soup tilted_grid(std::uint32_t n, double h) {
  Soup s;
  for (std::uint32_t i = 0; i <= n; ++i)
    for (std::uint32_t j = 0; j <= n; ++j) s.vertices.push_back({i * h, j * h, 0.1 * i * h + 0.37 * j * h});
  auto id = [n](std::uint32_t i, std::uint32_t j) { return i * (n + 1) + j; };
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = 0; j < n; ++j) {
      if ((i + j) % 2 == 0) {
        s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        s.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        s.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return s;
}

// A point of the grid's plane, as computed in doubles, moved by `ulps` on each coordinate.
Vec3 in_tilted_plane(double x, double y, int ulps) {
  Vec3 p{x, y, 0.1 * x + 0.37 * y};
  for (double& c : p)
    for (int u = ulps; u != 0; u += (u > 0 ? -1 : 1)) c = std::nextafter(c, u > 0 ? 1e300 : -1e300);
  return p;
}

// A strip of slivers: points nearly on the line y = 0, z = x, each triangle (i, i+1, i+2).
Soup sliver_strip(std::uint32_t n) {
  Soup s;
  for (std::uint32_t i = 0; i < n; ++i) {
    const double x = i / 7.0;
    double y = 0.0;
    for (std::uint32_t u = 0; u < i % 3; ++u) y = std::nextafter(y, 1.0) * 1e290;  // 0 or tiny
    s.vertices.push_back({x, y, x});
  }
  for (std::uint32_t i = 0; i + 2 < n; ++i) s.triangles.push_back({i, i + 1, i + 2});
  return s;
}

// ---- tests ---------------------------------------------------------------------------------

TEST(EdgeMultiplicities, LoneTriangleFacingLight_SignConventionOfDesign) {
  // docs/definitions.md#counts: with s = +1 the front cap is t = (0, 1, 2) itself and each directed edge
  // (x, y) of it gives the side quad (y, x, x_inf, y_inf); the chain holds m copies of
  // (u, v, v_inf, u_inf). Directed edges (0, 1) and (1, 2) therefore give m = -1, and (2, 0),
  // whose quad is (0, 2, 2_inf, 0_inf), gives m = +1 (Milet 2014 would report the opposite).
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};  // already in canonical order
  s.triangles = {{0, 1, 2}};
  const Prepared p = prepare(s);
  for (const Light& light : {point_light({0.5, 0.25, 3}), directional_light({0.1, 0.2, 1})}) {
    for (const Variant& v : kAllVariants) {
      const EdgeMultiplicities m = edge_multiplicities(v.method, p.soup, p.table, light, v.precision);
      ASSERT_EQ(m.triangle_sign, std::vector<Sign>{Sign::positive}) << describe(v);
      EXPECT_EQ(as_map(p.table, m.multiplicity), (std::map<EdgeKey, int>{{{0, 1}, -1}, {{1, 2}, -1}, {{0, 2}, 1}}))
          << describe(v);
    }
  }
}

TEST(EdgeMultiplicities, ClosedCubePointLightOutside_AllInMinusTwoZeroTwo) {
  const Prepared cube = prepare(box({0, 0, 0}, {1, 1, 1}));
  const Light light = point_light({3, 5, 2});
  const EdgeMultiplicities m = exact_multiplicities(cube.soup, cube.table, light);
  int silhouette = 0;
  for (std::int32_t x : m.multiplicity) {
    EXPECT_TRUE(x == -2 || x == 0 || x == 2) << x;
    silhouette += x != 0;
  }
  EXPECT_EQ(silhouette, 6);  // a cube seen from a generic outside point: a hexagon
  expect_matches_brute_force(cube, light, kAllVariants);
}

TEST(EdgeMultiplicities, UvSpherePointAndDirectionalLights_AllInMinusTwoZeroTwo) {
  const Prepared sphere = prepare(uv_sphere({0.5, -0.25, 1}, 2, 48, 24));
  for (const Light& light : {point_light({3, 5, 2}), directional_light({1, 2, 0.5}), point_light({0, 100, 0})}) {
    const EdgeMultiplicities m = exact_multiplicities(sphere.soup, sphere.table, light);
    int silhouette = 0;
    for (std::int32_t x : m.multiplicity) {
      EXPECT_TRUE(x == -2 || x == 0 || x == 2) << x;
      silhouette += x != 0;
    }
    EXPECT_GT(silhouette, 0);
    expect_matches_brute_force(sphere, light, kDoubleVariants);
  }
}

TEST(EdgeMultiplicities, SameSideFanOfOneTo256_AbsMultiplicityK) {
  for (std::uint32_t k = 1; k <= 256; ++k) {
    const Prepared fan = prepare(same_side_fan(k));
    const Light light = point_light({1, 0.5, -1});
    const EdgeMultiplicities m = exact_multiplicities(fan.soup, fan.table, light);
    // The shared edge is the one between the two lowest vertices (0,0,0) < (0,1,0).
    ASSERT_EQ(fan.table.edges[0], (std::array<std::uint32_t, 2>{0, 1}));
    EXPECT_EQ(std::abs(m.multiplicity[0]), static_cast<std::int32_t>(k)) << "k=" << k;  // > 32 from k = 33 on
    expect_matches_brute_force(fan, light, kDoubleVariants);
  }
}

TEST(EdgeMultiplicities, AlternatingFanOfOneTo256_MatchesBruteForce) {
  // Blades all around the edge: whatever their winding, those on either side of the light's
  // half-plane cancel, so |m| <= 1 here (the winding plays no part in D(u, v, o)).
  for (std::uint32_t k = 1; k <= 256; ++k) {
    const Prepared fan = prepare(nonmanifold_fan(k));
    const Light light = point_light({0.3, 0.7, 0.45});
    const EdgeMultiplicities m = exact_multiplicities(fan.soup, fan.table, light);
    EXPECT_LE(std::abs(m.multiplicity[0]), 1) << "k=" << k;
    expect_matches_brute_force(fan, light, kDoubleVariants);
  }
}

TEST(EdgeMultiplicities, FloorWithLightInItsPlane_AllZero) {
  const Prepared floor = prepare(floor_quad(10));
  for (const Light& light : {point_light({3, 0, -2}), directional_light({1, 0, 2}), point_light({0, 0, 0})}) {
    for (const Variant& v : kAllVariants) {
      const EdgeMultiplicities m = edge_multiplicities(v.method, floor.soup, floor.table, light, v.precision);
      for (Sign s : m.triangle_sign) EXPECT_EQ(s, Sign::zero) << describe(v);
      for (std::int32_t x : m.multiplicity) EXPECT_EQ(x, 0) << describe(v);
    }
  }
}

TEST(EdgeMultiplicities, DirectionalLights_MatchBruteForce) {
  const Prepared cube = prepare(box({-1, -1, -1}, {1, 2, 3}));
  const Prepared fins = prepare(open_box_with_fins());
  for (const Vec3& d : {Vec3{0, 1, 0}, Vec3{1, 1, 1}, Vec3{-0.3, 0.2, 0.9}, Vec3{1, 0, 0}}) {
    expect_matches_brute_force(cube, directional_light(d), kAllVariants);
    expect_matches_brute_force(fins, directional_light(d), kAllVariants);
  }
}

TEST(EdgeMultiplicities, DuplicateAndFlippedDuplicate_ContributionsAddCapsFollowWinding) {
  // D(u, v, o) depends on the vertex set, not on the winding: a triangle and its flipped copy
  // have the same shadow volume, both count as occluders (n(P), docs/definitions.md#counts), so their edge
  // contributions add up; only the cap signs differ, and the front caps t' coincide.
  Soup one;
  one.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  one.triangles = {{0, 1, 2}};
  Soup twice = one, flipped = one;
  twice.triangles.push_back({0, 1, 2});
  flipped.triangles.push_back({2, 1, 0});
  const Light light = point_light({0.2, 0.3, 4});
  const Prepared p1 = prepare(one), p2 = prepare(twice), pf = prepare(flipped);
  for (const Variant& v : kAllVariants) {
    const EdgeMultiplicities m1 = edge_multiplicities(v.method, p1.soup, p1.table, light, v.precision);
    const EdgeMultiplicities m2 = edge_multiplicities(v.method, p2.soup, p2.table, light, v.precision);
    const EdgeMultiplicities mf = edge_multiplicities(v.method, pf.soup, pf.table, light, v.precision);
    for (std::size_t e = 0; e < p1.table.size(); ++e) {
      EXPECT_NE(m1.multiplicity[e], 0) << describe(v);  // a lone triangle: every edge on the silhouette
      EXPECT_EQ(m2.multiplicity[e], 2 * m1.multiplicity[e]) << describe(v);
      EXPECT_EQ(mf.multiplicity[e], 2 * m1.multiplicity[e]) << describe(v);
    }
    EXPECT_EQ(m2.triangle_sign[1], m2.triangle_sign[0]) << describe(v);
    EXPECT_EQ(mf.triangle_sign[1], -mf.triangle_sign[0]) << describe(v);
    EXPECT_NE(mf.triangle_sign[0], Sign::zero) << describe(v);
  }
}

TEST(EdgeMultiplicities, IntegerGridSoups_AllMethodsBothPrecisionsMatchBruteForce) {
  // Integer coordinates in [-16, 16] and lights in [-40, 40]: every operation of the shared
  // formula is exact even in float (|value| < 2^24), so every method must give the exact
  // answer, exact zeros (coplanarities, grid snapping) included.
  constexpr std::uint64_t kSeed = 1234;
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 engine(kSeed);
  auto small = [&engine](int r) { return static_cast<double>(static_cast<int>(engine() % (2 * r + 1)) - r); };
  for (int round = 0; round < 60; ++round) {
    const Prepared p = prepare(pooled_soup(engine, 12, 80, [&] { return small(16); }));
    const Vec3 l{small(40), small(40), small(40)};
    expect_matches_brute_force(p, point_light(l), kAllVariants);
    if (l != Vec3{0, 0, 0}) expect_matches_brute_force(p, directional_light(l), kAllVariants);
  }
}

TEST(EdgeMultiplicities, WellConditionedRandomSoups_AllMethodsMatchBruteForce) {
  // Float-exact coordinates, and only triangles whose determinant is far from zero relative to
  // the magnitudes involved (> 1e-3), so that neither float nor double rounding can flip a
  // sign: then every method must agree with the exact one, caps included.
  constexpr std::uint64_t kSeed = 4321;
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 engine(kSeed);
  auto unit = [&engine] {
    return static_cast<double>(static_cast<float>(static_cast<double>(engine() >> 11) * 0x1.0p-53 * 2 - 1));
  };
  for (int round = 0; round < 40; ++round) {
    Soup s = pooled_soup(engine, 20, 200, unit);
    const Light light = round % 2 == 0 ? point_light({3 * unit(), 3 * unit(), 3 + unit()})
                                       : directional_light({unit(), unit(), 1 + unit()});
    const auto& l = light.position;
    std::erase_if(s.triangles, [&](const Triangle& t) {
      if (!distinct(t)) return false;  // kept: must give zero everywhere
      const Vec3 &a = s.vertices[t[0]], &b = s.vertices[t[1]], &c = s.vertices[t[2]];
      const double x[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, y[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double z[3] = {l[0] - l[3] * a[0], l[1] - l[3] * a[1], l[2] - l[3] * a[2]};
      const double det = x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0]) +
                         x[2] * (y[0] * z[1] - y[1] * z[0]);
      // Largest magnitudes any vertex order of the formula can meet: edges up to 2 sqrt 3,
      // light vectors up to |l| + sqrt 3.
      const double scale = 12.0 * (std::hypot(l[0], l[1], l[2]) + 2.0);
      return std::fabs(det) < 1e-3 * scale;
    });
    expect_matches_brute_force(prepare(s), light, kAllVariants);
  }
}

TEST(EdgeMultiplicities, VertexRelabelling_ExactMultiplicitiesInvariant) {
  constexpr std::uint64_t kSeed = 99;
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 engine(kSeed);
  auto coordinate = [&engine] { return static_cast<double>(engine() % 9) / 4.0 - 1.0; };  // grid: degeneracies
  for (int round = 0; round < 30; ++round) {
    const Soup s = pooled_soup(engine, 25, 150, coordinate);
    const Light light = round % 2 ? point_light({0.5, 1.25, -0.75}) : directional_light({0.25, 1, 0.5});
    // Relabel: permute the vertices, and give every vertex a second, unwelded copy.
    std::vector<std::uint32_t> perm(2 * s.vertices.size());
    std::iota(perm.begin(), perm.end(), 0u);
    std::shuffle(perm.begin(), perm.end(), engine);
    Soup r;
    r.vertices.resize(perm.size());
    for (std::uint32_t i = 0; i < perm.size(); ++i) r.vertices[perm[i]] = s.vertices[i % s.vertices.size()];
    for (const Triangle& t : s.triangles) {
      const std::uint32_t copy = static_cast<std::uint32_t>(engine() % 2) * static_cast<std::uint32_t>(s.vertices.size());
      r.triangles.push_back({perm[t[0] + copy], perm[t[1]], perm[t[2] + copy]});
    }
    auto by_positions = [&light](const Soup& input) {
      const Prepared p = prepare(input);
      const EdgeMultiplicities m = exact_multiplicities(p.soup, p.table, light);
      std::map<std::pair<Vec3, Vec3>, int> out;
      for (std::size_t e = 0; e < p.table.size(); ++e)
        out[{p.soup.vertices[p.table.edges[e][0]], p.soup.vertices[p.table.edges[e][1]]}] = m.multiplicity[e];
      return std::make_pair(out, as_ints(m.triangle_sign));
    };
    EXPECT_EQ(by_positions(s), by_positions(r)) << "round " << round;
  }
}

TEST(EdgeMultiplicities, FaceReversal_MultiplicitiesUnchangedCapsNegated) {
  const Prepared sphere = prepare(uv_sphere({0, 0, 0}, 1, 24, 12));
  Prepared reversed = sphere;
  for (std::size_t t = 0; t < reversed.soup.triangles.size(); t += 3)
    std::swap(reversed.soup.triangles[t][1], reversed.soup.triangles[t][2]);
  reversed.table = build_edge_table(reversed.soup);
  const Light light = point_light({2, 3, 1});
  for (const Variant& v : kAllVariants) {
    const EdgeMultiplicities a = edge_multiplicities(v.method, sphere.soup, sphere.table, light, v.precision);
    const EdgeMultiplicities b = edge_multiplicities(v.method, reversed.soup, reversed.table, light, v.precision);
    EXPECT_EQ(a.multiplicity, b.multiplicity) << describe(v);
    for (std::size_t t = 0; t < a.triangle_sign.size(); ++t)
      EXPECT_EQ(b.triangle_sign[t], t % 3 == 0 ? -a.triangle_sign[t] : a.triangle_sign[t]) << describe(v);
  }
}

TEST(EdgeMultiplicities, TranslationByTwoToTheTwenty_ExactMultiplicitiesInvariant) {
  // Coordinates are multiples of 2^-20 in [-4, 4]: adding 2^20 is exact in double (43 bits),
  // and keeps the lexicographic order, so tables and answers must be identical.
  constexpr std::uint64_t kSeed = 2020;
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 engine(kSeed);
  auto coordinate = [&engine] { return std::ldexp(static_cast<double>(engine() % (1u << 23)), -20) - 4.0; };
  const double shift = std::ldexp(1.0, 20);
  for (int round = 0; round < 20; ++round) {
    const Soup s = pooled_soup(engine, 30, 200, coordinate);
    Soup moved = s;
    for (Vec3& p : moved.vertices)
      for (double& c : p) c += shift;
    const Vec3 l{coordinate(), coordinate(), coordinate()};
    const Prepared a = prepare(s), b = prepare(moved);
    ASSERT_EQ(a.table.edges, b.table.edges);
    ASSERT_EQ(a.table.opposite_vertex, b.table.opposite_vertex);
    for (const auto& [la, lb] : {std::pair{point_light(l), point_light({l[0] + shift, l[1] + shift, l[2] + shift})},
                                 std::pair{directional_light(l), directional_light(l)}}) {
      const EdgeMultiplicities ma = exact_multiplicities(a.soup, a.table, la);
      const EdgeMultiplicities mb = exact_multiplicities(b.soup, b.table, lb);
      EXPECT_EQ(ma.multiplicity, mb.multiplicity) << "round " << round;
      EXPECT_EQ(ma.triangle_sign, mb.triangle_sign) << "round " << round;
    }
  }
}

TEST(EdgeMultiplicities, NearDegenerateSoups_ExactMatchesBruteForceAndConsistentMethodsStayConsistent) {
  // Light in (as computed) or a few ulps off the plane of a nearly planar grid, and slivers:
  // the configurations where float methods lose closure (docs/definitions.md#hard-cases). Exact must still match
  // the brute force; exact, peciva and refedge must keep every entry equal to the cap sign times
  // the permutation parity, in float and double (refedge: its per-entry Algorithm 3 evaluation
  // equals the per-triangle one bit for bit).
  const Prepared grid = prepare(tilted_grid(12, 0.1));
  const Prepared slivers = prepare(sliver_strip(40));
  std::vector<std::pair<const Prepared*, Light>> cases;
  for (int ulps = -3; ulps <= 3; ++ulps) {
    cases.push_back({&grid, point_light(in_tilted_plane(7.3, -2.9, ulps))});
    cases.push_back({&grid, point_light(in_tilted_plane(0.55, 0.65, ulps))});
    cases.push_back({&grid, directional_light(in_tilted_plane(1.0, 3.0, ulps))});
    cases.push_back({&slivers, point_light({3.0 + ulps * 1e-15, 1e-300 * ulps, 3.0})});
    cases.push_back({&slivers, directional_light({1.0, ulps * 1e-320, 1.0})});
  }
  std::size_t kim_float_inconsistent = 0;
  for (const auto& [p, light] : cases) {
    expect_matches_brute_force(*p, light, {{MultiplicityMethod::exact, Precision::float64}});
    for (const Variant& v : kAllVariants) {
      const std::size_t bad = count_inconsistent_entries(*p, light, v);
      if (v.method == MultiplicityMethod::kim) {
        if (v.precision == Precision::float32) kim_float_inconsistent += bad;
      } else {
        EXPECT_EQ(bad, 0u) << describe(v);
      }
    }
  }
  // The failure the consistent methods cure does occur on these soups.
  EXPECT_GT(kim_float_inconsistent, 0u);
}

TEST(EdgeMultiplicities, RepeatedIndexTriangles_CastNothingInEveryMethod) {
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.triangles = {{0, 1, 1}, {2, 2, 0}, {0, 1, 2}, {1, 0, 1}};
  const Prepared p = prepare(s);
  for (const Variant& v : kAllVariants) {
    const EdgeMultiplicities m = edge_multiplicities(v.method, p.soup, p.table, point_light({0.1, 0.2, 1}), v.precision);
    EXPECT_EQ(as_ints(m.triangle_sign), (std::vector<int>{0, 0, 1, 0})) << describe(v);
  }
}

TEST(EdgeMultiplicities, NamedFunctions_EqualDispatch) {
  const Prepared p = prepare(open_box_with_fins());
  const Light light = point_light({0.3, 2.5, -0.7});
  for (Precision precision : {Precision::float32, Precision::float64}) {
    auto same = [](const EdgeMultiplicities& a, const EdgeMultiplicities& b) {
      return a.multiplicity == b.multiplicity && a.triangle_sign == b.triangle_sign;
    };
    EXPECT_TRUE(same(kim_multiplicities(p.soup, p.table, light, precision),
                     edge_multiplicities(MultiplicityMethod::kim, p.soup, p.table, light, precision)));
    EXPECT_TRUE(same(peciva_multiplicities(p.soup, p.table, light, precision),
                     edge_multiplicities(MultiplicityMethod::peciva, p.soup, p.table, light, precision)));
    EXPECT_TRUE(same(refedge_multiplicities(p.soup, p.table, light, precision),
                     edge_multiplicities(MultiplicityMethod::refedge, p.soup, p.table, light, precision)));
    EXPECT_TRUE(same(exact_multiplicities(p.soup, p.table, light),
                     edge_multiplicities(MultiplicityMethod::exact, p.soup, p.table, light, precision)));
  }
}

TEST(EdgeMultiplicities, InvalidLightOrForeignTable_Throws) {
  const Prepared p = prepare(box({0, 0, 0}, {1, 1, 1}));
  EXPECT_THROW((void)exact_multiplicities(p.soup, p.table, Light{{0, 1, 0, 0.5}}), std::invalid_argument);
  EXPECT_THROW((void)refedge_multiplicities(p.soup, p.table, Light{{0, 0, 0, 0}}, Precision::float32),
               std::invalid_argument);
  EXPECT_THROW((void)kim_multiplicities(p.soup, p.table, Light{{std::nan(""), 0, 0, 1}}, Precision::float64),
               std::invalid_argument);
  EdgeTable broken = p.table;
  broken.first_opposite.pop_back();
  EXPECT_THROW((void)peciva_multiplicities(p.soup, broken, point_light({3, 3, 3}), Precision::float64),
               std::invalid_argument);
}

TEST(MethodName, EveryMethod_RoundTrips) {
  for (MultiplicityMethod m :
       {MultiplicityMethod::exact, MultiplicityMethod::kim, MultiplicityMethod::peciva, MultiplicityMethod::refedge})
    EXPECT_EQ(parse_method(method_name(m)), m);
  EXPECT_EQ(method_name(MultiplicityMethod::refedge), "refedge");
  EXPECT_THROW((void)parse_method("milet"), std::invalid_argument);
  EXPECT_THROW((void)parse_method("Exact"), std::invalid_argument);
}

}  // namespace
