#include "core/vector3.h"
#include "scene/procedural_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "scene/sphere_grid_layout.h"
#include "scene/affine_transform.h"
#include "scene/hard_soups.h"
#include "scene/light_orbit.h"
#include "support/bit_digest.h"

using shadowcert::Soup;
using shadowcert::cross;
using shadowcert::difference;
using shadowcert::dot;
using shadowcert::Triangle;
using shadowcert::Vec3;

namespace {

using DirectedEdge = std::pair<std::uint32_t, std::uint32_t>;
using UndirectedEdge = std::pair<std::uint32_t, std::uint32_t>;

std::map<DirectedEdge, int> directed_edge_counts(const Soup& s) {
  std::map<DirectedEdge, int> count;
  for (const Triangle& t : s.triangles)
    for (int i = 0; i < 3; ++i) ++count[{t[i], t[(i + 1) % 3]}];
  return count;
}

std::map<UndirectedEdge, int> undirected_edge_counts(const Soup& s) {
  std::map<UndirectedEdge, int> count;
  for (const Triangle& t : s.triangles)
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  return count;
}

// Closed and consistently oriented: every directed edge once, and its reverse once.
::testing::AssertionResult ClosedAndConsistent(const Soup& s) {
  const auto count = directed_edge_counts(s);
  for (const auto& [edge, n] : count) {
    if (n != 1) return ::testing::AssertionFailure() << "edge " << edge.first << "->" << edge.second << " used " << n << " times";
    const auto reverse = count.find({edge.second, edge.first});
    if (reverse == count.end() || reverse->second != 1)
      return ::testing::AssertionFailure() << "edge " << edge.first << "->" << edge.second << " has no single reverse";
  }
  return ::testing::AssertionSuccess();
}

// Index sharing is real sharing: no two vertices at the same position (seams not duplicated).
::testing::AssertionResult NoDuplicatePositions(const Soup& s) {
  const std::set<Vec3> distinct(s.vertices.begin(), s.vertices.end());
  if (distinct.size() == s.vertices.size()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << s.vertices.size() - distinct.size() << " duplicated positions";
}

Vec3 sub(const Vec3& a, const Vec3& b) { return difference(a, b); }

// Divergence theorem about `origin`: positive iff the closed surface is oriented outwards.
double signed_volume(const Soup& s, const Vec3& origin) {
  double six_v = 0.0;
  for (const Triangle& t : s.triangles)
    six_v += dot(sub(s.vertices[t[0]], origin), cross(sub(s.vertices[t[1]], origin), sub(s.vertices[t[2]], origin)));
  return six_v / 6.0;
}

// Star-shaped about `center` (spheres): every triangle's (b-a)x(c-a) points away from it.
::testing::AssertionResult EveryTriangleFacesAwayFrom(const Soup& s, const Vec3& center) {
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const Triangle& t = s.triangles[i];
    const Vec3& a = s.vertices[t[0]];
    const Vec3 n = cross(sub(s.vertices[t[1]], a), sub(s.vertices[t[2]], a));
    if (!(dot(n, sub(a, center)) > 0.0)) return ::testing::AssertionFailure() << "triangle " << i << " faces inwards";
  }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult UnitNormalsPointingAwayFrom(const Soup& s, const Vec3& center) {
  if (s.normals.size() != s.vertices.size())
    return ::testing::AssertionFailure() << s.normals.size() << " normals for " << s.vertices.size() << " vertices";
  for (std::size_t i = 0; i < s.normals.size(); ++i) {
    const Vec3 n{s.normals[i][0], s.normals[i][1], s.normals[i][2]};
    if (std::abs(std::sqrt(dot(n, n)) - 1.0) > 1e-6) return ::testing::AssertionFailure() << "normal " << i << " not unit";
    if (!(dot(n, sub(s.vertices[i], center)) > 0.0))
      return ::testing::AssertionFailure() << "normal " << i << " points inwards";
  }
  return ::testing::AssertionSuccess();
}

template <typename F>
::testing::AssertionResult ThrowsNaming(F&& f, const std::string& function) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).rfind(function + ": ", 0) == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "message '" << e.what() << "' does not start with " << function;
  }
  return ::testing::AssertionFailure() << "no std::invalid_argument";
}

// Procedural meshes, rotations and light orbits are the same bits on every machine
// (core/portable_math.h, not libm, whose sin/cos differ by CPU), pinned; also run with glibc's
// FMA variants off.
TEST(ProceduralMesh, EveryGenerator_SameOnEveryMachine) {
  using namespace shadowcert;
  test::BitDigest digest;
  digest.add(uv_sphere({0.1, 0.2, 0.3}, 0.7, 33, 17));
  digest.add(icosphere({0.0, 1.0, 0.0}, 1.3, 3));
  digest.add(torus({0.0, 0.0, 0.0}, 1.0, 0.3, 40, 12));
  digest.add(torus_knot({0.0, 0.0, 0.0}, 2, 3, 1.0, 0.4, 0.1, 96, 8));
  digest.add(sphere_grid(20000));
  digest.add(random_soup(5, 300, 2.0));
  digest.add(half_fan(64));
  digest.add(transformed(box({-1, -1, -1}, {1, 2, 3}), compose_trs({1, 2, 3}, {1, 0.5, 2}, {30, 47, -71})));
  for (const Light& light : orbit_lights(LightOrbit{{0.5, 0.0, -0.5}, 3.0, 2.0, 1.25}, 37)) digest.add(light);
  EXPECT_EQ(digest.hex(), "5e7973b0d204a7d0");
}

}  // namespace

TEST(FloorQuad, TwoTriangles_FacePlusY) {
  const Soup s = shadowcert::floor_quad(3.0);
  ASSERT_EQ(s.triangles.size(), 2u);
  for (const Triangle& t : s.triangles) {
    const Vec3 n = cross(sub(s.vertices[t[1]], s.vertices[t[0]]), sub(s.vertices[t[2]], s.vertices[t[0]]));
    EXPECT_EQ(n[0], 0.0);
    EXPECT_GT(n[1], 0.0);
    EXPECT_EQ(n[2], 0.0);
  }
  for (const Vec3& p : s.vertices) {
    EXPECT_EQ(std::abs(p[0]), 3.0);
    EXPECT_EQ(p[1], 0.0);
    EXPECT_EQ(std::abs(p[2]), 3.0);
  }
  EXPECT_EQ(s.normals.size(), s.vertices.size());
}

TEST(Box, TwelveTriangles_ClosedOutward) {
  const Soup s = shadowcert::box({-1, 0, 2}, {1, 3, 5});
  EXPECT_EQ(s.triangles.size(), 12u);
  EXPECT_EQ(s.vertices.size(), 8u);
  EXPECT_TRUE(ClosedAndConsistent(s));
  EXPECT_DOUBLE_EQ(signed_volume(s, {0, 0, 0}), 2.0 * 3.0 * 3.0);
  EXPECT_TRUE(EveryTriangleFacesAwayFrom(s, {0, 1.5, 3.5}));
}

TEST(UvSphere, Counts_MatchFormula) {
  for (const auto& [slices, stacks] : {std::pair<std::uint32_t, std::uint32_t>{3, 2}, {4, 3}, {32, 16}, {7, 5}}) {
    const Soup s = shadowcert::uv_sphere({0, 0, 0}, 1.0, slices, stacks);
    EXPECT_EQ(s.triangles.size(), 2u * slices * (stacks - 1));
    EXPECT_EQ(s.vertices.size(), slices * (stacks - 1) + 2u);
  }
}

TEST(UvSphere, ClosedConsistentOutward_WithUnitNormals) {
  const Vec3 c{1.5, -2.0, 0.25};
  for (const auto& [slices, stacks] : {std::pair<std::uint32_t, std::uint32_t>{3, 2}, {5, 3}, {32, 16}, {33, 17}}) {
    const Soup s = shadowcert::uv_sphere(c, 2.0, slices, stacks);
    EXPECT_TRUE(ClosedAndConsistent(s)) << slices << "x" << stacks;
    EXPECT_TRUE(NoDuplicatePositions(s));
    EXPECT_GT(signed_volume(s, c), 0.0);
    EXPECT_TRUE(EveryTriangleFacesAwayFrom(s, c));
    EXPECT_TRUE(UnitNormalsPointingAwayFrom(s, c));
  }
}

TEST(UvSphere, PolesAndEquator_Exact) {
  const Soup s = shadowcert::uv_sphere({1, 2, 3}, 0.5, 8, 4);
  EXPECT_EQ(s.vertices.front(), (Vec3{1, 2.5, 3}));
  EXPECT_EQ(s.vertices.back(), (Vec3{1, 1.5, 3}));
  // Ring 2 of 3 is the equator: exactly in the centre's plane, with exact axis points.
  for (std::uint32_t j = 0; j < 8; ++j) EXPECT_EQ(s.vertices[1 + 8 + j][1], 2.0);
  EXPECT_EQ(s.vertices[1 + 8], (Vec3{1.5, 2, 3}));
}

TEST(UvSphere, Volume_ApproachesBall) {
  const Soup s = shadowcert::uv_sphere({0, 0, 0}, 1.0, 256, 128);
  // An inscribed polyhedron: a little below the ball's volume, never above.
  const double ball = 4.0 / 3.0 * 3.141592653589793;
  EXPECT_LT(signed_volume(s, {0, 0, 0}), ball);
  EXPECT_GT(signed_volume(s, {0, 0, 0}), 0.999 * ball);
}

TEST(Icosphere, Counts_MatchFormula) {
  for (std::uint32_t n = 0; n <= 4; ++n) {
    const Soup s = shadowcert::icosphere({0, 0, 0}, 1.0, n);
    const std::size_t faces = 20u << (2 * n);
    EXPECT_EQ(s.triangles.size(), faces);
    EXPECT_EQ(s.vertices.size(), faces / 2 + 2);  // Euler: V = F/2 + 2 for a closed sphere
  }
}

TEST(Icosphere, ClosedConsistentOutward_WithUnitNormals) {
  const Vec3 c{-3, 1, 7};
  for (std::uint32_t n = 0; n <= 3; ++n) {
    const Soup s = shadowcert::icosphere(c, 0.75, n);
    EXPECT_TRUE(ClosedAndConsistent(s)) << n;
    EXPECT_TRUE(NoDuplicatePositions(s));
    EXPECT_GT(signed_volume(s, c), 0.0);
    EXPECT_TRUE(EveryTriangleFacesAwayFrom(s, c));
    EXPECT_TRUE(UnitNormalsPointingAwayFrom(s, c));
  }
}

TEST(Torus, CountsClosedOutward_VolumeMatches) {
  const Vec3 c{0, 1, 0};
  const Soup s = shadowcert::torus(c, 2.0, 0.5, 64, 32);
  EXPECT_EQ(s.triangles.size(), 2u * 64 * 32);
  EXPECT_EQ(s.vertices.size(), 64u * 32);
  EXPECT_TRUE(ClosedAndConsistent(s));
  EXPECT_TRUE(NoDuplicatePositions(s));
  const double pi = 3.141592653589793;
  const double solid = 2 * pi * pi * 2.0 * 0.25;  // inscribed: slightly below
  EXPECT_LT(signed_volume(s, c), solid);
  EXPECT_GT(signed_volume(s, c), 0.99 * solid);
  ASSERT_EQ(s.normals.size(), s.vertices.size());
  for (std::size_t i = 0; i < s.vertices.size(); ++i) {
    // The normal points away from the tube's core circle.
    const Vec3& p = s.vertices[i];
    const double r = std::hypot(p[0], p[2]);
    const Vec3 core{2.0 * p[0] / r, 1.0, 2.0 * p[2] / r};
    const Vec3 n{s.normals[i][0], s.normals[i][1], s.normals[i][2]};
    EXPECT_NEAR(std::sqrt(dot(n, n)), 1.0, 1e-6);
    EXPECT_GT(dot(n, sub(p, core)), 0.0);
  }
}

TEST(Torus, SmallSegments_StillClosed) {
  EXPECT_TRUE(ClosedAndConsistent(shadowcert::torus({0, 0, 0}, 1.0, 0.5, 3, 3)));
}

// The (2, 3) knot of the defaults: closed, outward, its volume the tube's, and every vertex at
// the tube radius from the curve and from no other strand nearer (the tube does not cross itself).
TEST(TorusKnot, DefaultsClosedOutward_TubeClearOfOtherStrands) {
  const Vec3 c{0.5, -1, 2};
  const double tube = 0.12;
  const Soup s = shadowcert::torus_knot(c, 2, 3, 1.0, 0.4, tube, 128, 12);
  EXPECT_EQ(s.triangles.size(), 2u * 128 * 12);
  EXPECT_EQ(s.vertices.size(), 128u * 12);
  EXPECT_TRUE(ClosedAndConsistent(s));
  EXPECT_TRUE(NoDuplicatePositions(s));
  std::vector<Vec3> curve;
  double length = 0.0;
  const double pi = 3.141592653589793;
  for (int i = 0; i < 4096; ++i) {
    const double t = 2 * pi * i / 4096;
    const double rho = 1.0 + 0.4 * std::cos(3 * t);
    curve.push_back({c[0] + rho * std::cos(2 * t), c[1] + 0.4 * std::sin(3 * t), c[2] + rho * std::sin(2 * t)});
    if (i > 0) length += std::sqrt(dot(sub(curve[i], curve[i - 1]), sub(curve[i], curve[i - 1])));
  }
  const double solid = pi * tube * tube * length;  // inscribed polygons: a little below
  EXPECT_GT(signed_volume(s, c), 0.9 * solid);
  EXPECT_LT(signed_volume(s, c), 1.01 * solid);
  ASSERT_EQ(s.normals.size(), s.vertices.size());
  for (std::size_t i = 0; i < s.vertices.size(); ++i) {
    double nearest = 1e9;
    for (const Vec3& q : curve) nearest = std::min(nearest, std::sqrt(dot(sub(s.vertices[i], q), sub(s.vertices[i], q))));
    EXPECT_NEAR(nearest, tube, 2e-3) << "vertex " << i;
    const Vec3 n{s.normals[i][0], s.normals[i][1], s.normals[i][2]};
    EXPECT_NEAR(std::sqrt(dot(n, n)), 1.0, 1e-6);
  }
}

TEST(SphereGridLayout, RequestedSizes_WithinTwoPercent) {
  for (std::uint64_t requested : {32'000ULL, 32'768ULL, 128'000ULL, 131'072ULL, 512'000ULL, 524'288ULL, 1'000'000ULL,
                                  1'048'576ULL, 4'000'000ULL, 4'194'304ULL}) {
    const auto layout = shadowcert::sphere_grid_layout(requested);
    EXPECT_EQ(layout.total_triangles, 200ULL * layout.slices * (layout.stacks - 1));
    const double error = std::abs(static_cast<double>(layout.total_triangles) - static_cast<double>(requested)) /
                         static_cast<double>(requested);
    EXPECT_LT(error, 0.02) << requested;
    const auto band = std::max<std::int64_t>(2, layout.stacks / 4);
    EXPECT_LE(std::abs(static_cast<std::int64_t>(layout.slices) - 2 * static_cast<std::int64_t>(layout.stacks)), band);
  }
}

TEST(SphereGridLayout, KnownSizes_MatchDocumentation) {
  // docs/scene-format.md quotes these.
  auto check = [](std::uint64_t requested, std::uint32_t slices, std::uint32_t stacks, std::uint64_t total) {
    const auto layout = shadowcert::sphere_grid_layout(requested);
    EXPECT_EQ(layout.slices, slices) << requested;
    EXPECT_EQ(layout.stacks, stacks) << requested;
    EXPECT_EQ(layout.total_triangles, total) << requested;
  };
  check(32'000, 20, 9, 32'000);
  check(128'000, 38, 18, 129'200);
  check(512'000, 71, 37, 511'200);
  check(1'000'000, 100, 51, 1'000'000);
  check(4'000'000, 200, 101, 4'000'000);
  check(600, 3, 2, 600);
}

TEST(SphereGrid, TriangleCount_MatchesLayout) {
  for (std::uint64_t requested : {32'000ULL, 128'000ULL, 512'000ULL, 1'000'000ULL, 4'000'000ULL}) {
    const Soup s = shadowcert::sphere_grid(requested);
    EXPECT_EQ(s.triangles.size(), shadowcert::sphere_grid_layout(requested).total_triangles);
    EXPECT_EQ(s.normals.size(), s.vertices.size());
  }
}

TEST(SphereGrid, HundredClosedSpheres_RestingOnYZero) {
  const Soup s = shadowcert::sphere_grid(32'000);
  EXPECT_TRUE(ClosedAndConsistent(s));
  EXPECT_TRUE(NoDuplicatePositions(s));
  EXPECT_GT(signed_volume(s, {0, 1, 0}), 0.0);
  double lo = 1e300, hi = -1e300, xmax = 0;
  for (const Vec3& p : s.vertices) {
    lo = std::min(lo, p[1]);
    hi = std::max(hi, p[1]);
    xmax = std::max(xmax, std::abs(p[0]));
  }
  EXPECT_EQ(lo, 0.0);
  EXPECT_EQ(hi, 2.0);
  EXPECT_LE(xmax, 4.5 * 2.5 + 1.0);  // 10 columns, 2.5 apart, radius 1
  EXPECT_GT(xmax, 4.5 * 2.5 + 0.98);
  // 100 connected components of equal size: the vertex count is 100 spheres' worth.
  const auto layout = shadowcert::sphere_grid_layout(32'000);
  EXPECT_EQ(s.vertices.size(), 100u * (layout.slices * (layout.stacks - 1) + 2));
}

TEST(RandomSoup, SameSeed_SameSoup) {
  const Soup a = shadowcert::random_soup(42, 50, 2.0);
  const Soup b = shadowcert::random_soup(42, 50, 2.0);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST(RandomSoup, DifferentSeed_DifferentSoup) {
  EXPECT_NE(shadowcert::random_soup(42, 50, 2.0).vertices, shadowcert::random_soup(43, 50, 2.0).vertices);
}

TEST(RandomSoup, CountsAndRange_AsRequested) {
  const Soup s = shadowcert::random_soup(7, 1000, 3.0);
  EXPECT_EQ(s.triangles.size(), 1000u);
  EXPECT_EQ(s.vertices.size(), 3000u);
  for (const Vec3& p : s.vertices)
    for (double x : p) {
      EXPECT_GE(x, -3.0);
      EXPECT_LT(x, 3.0);
    }
  EXPECT_TRUE(shadowcert::random_soup(7, 0, 1.0).triangles.empty());
}

TEST(RandomSoup, FirstCoordinate_PinnedAcrossBuilds) {
  // Coordinates come from mt19937_64's bits directly (no std distribution): any standard
  // library must give this value; a change here breaks reproducibility of stored results.
  const Soup s = shadowcert::random_soup(1, 1, 1.0);
  EXPECT_EQ(s.vertices[0][0], -0x1.76e90a81125e6p-1);
}

TEST(NonmanifoldFan, KTriangles_OnOneEdge) {
  for (std::uint32_t k : {1u, 2u, 3u, 8u, 33u, 256u}) {
    const Soup s = shadowcert::nonmanifold_fan(k);
    EXPECT_EQ(s.triangles.size(), k);
    const auto undirected = undirected_edge_counts(s);
    EXPECT_EQ(undirected.at({0, 1}), static_cast<int>(k));
    for (const auto& [edge, n] : undirected) {
      if (edge != UndirectedEdge{0, 1}) {
        EXPECT_EQ(n, 1);
      }
    }
    const auto directed = directed_edge_counts(s);
    EXPECT_EQ(directed.count({0, 1}) ? directed.at({0, 1}) : 0, static_cast<int>((k + 1) / 2));
    EXPECT_EQ(directed.count({1, 0}) ? directed.at({1, 0}) : 0, static_cast<int>(k / 2));
    EXPECT_TRUE(NoDuplicatePositions(s));
  }
}

TEST(OpenBoxWithFins, BorderAndTripleEdges_AsDocumented) {
  const Soup s = shadowcert::open_box_with_fins();
  EXPECT_EQ(s.triangles.size(), 14u);
  EXPECT_TRUE(NoDuplicatePositions(s));
  std::map<int, int> edges_by_count;
  for (const auto& [edge, n] : undirected_edge_counts(s)) ++edges_by_count[n];
  EXPECT_EQ(edges_by_count[1], 9);  // one bare rim edge and two free edges per fin
  EXPECT_EQ(edges_by_count[3], 1);  // the rim edge with two fins
  EXPECT_EQ(edges_by_count.size(), 3u);
}

TEST(Generators, Deterministic_SameOutputTwice) {
  EXPECT_EQ(shadowcert::icosphere({0, 0, 0}, 1, 3).vertices, shadowcert::icosphere({0, 0, 0}, 1, 3).vertices);
  EXPECT_EQ(shadowcert::icosphere({0, 0, 0}, 1, 3).triangles, shadowcert::icosphere({0, 0, 0}, 1, 3).triangles);
  EXPECT_EQ(shadowcert::sphere_grid(32'000).vertices, shadowcert::sphere_grid(32'000).vertices);
}

TEST(Generators, BadParameters_ThrowNamingFunction) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::floor_quad(0.0); }, "floor_quad"));
  EXPECT_TRUE(ThrowsNaming([&] { (void)shadowcert::floor_quad(nan); }, "floor_quad"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::box({0, 0, 0}, {1, 0, 1}); }, "box"));
  EXPECT_TRUE(ThrowsNaming([&] { (void)shadowcert::box({0, 0, 0}, {1, inf, 1}); }, "box"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::uv_sphere({0, 0, 0}, 1, 2, 4); }, "uv_sphere"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::uv_sphere({0, 0, 0}, 1, 4, 1); }, "uv_sphere"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::uv_sphere({0, 0, 0}, -1, 4, 4); }, "uv_sphere"));
  EXPECT_TRUE(ThrowsNaming([&] { (void)shadowcert::uv_sphere({nan, 0, 0}, 1, 4, 4); }, "uv_sphere"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::uv_sphere({0, 0, 0}, 1, 100'000, 100'000); }, "uv_sphere"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::icosphere({0, 0, 0}, 1, 11); }, "icosphere"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::icosphere({0, 0, 0}, 0, 1); }, "icosphere"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::torus({0, 0, 0}, 1, 1, 8, 8); }, "torus"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::torus({0, 0, 0}, 1, 0.5, 2, 8); }, "torus"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::torus({0, 0, 0}, 1, 0.5, 8, 2); }, "torus"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::torus_knot({0, 0, 0}, 2, 4, 1, 0.4, 0.1, 64, 8); }, "torus_knot"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::torus_knot({0, 0, 0}, 0, 3, 1, 0.4, 0.1, 64, 8); }, "torus_knot"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::torus_knot({0, 0, 0}, 2, 3, 1, 1.0, 0.1, 64, 8); }, "torus_knot"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::torus_knot({0, 0, 0}, 2, 3, 1, 0.4, 0.0, 64, 8); }, "torus_knot"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::torus_knot({0, 0, 0}, 2, 3, 1, 0.4, 0.1, 2, 8); }, "torus_knot"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::torus_knot({0, 0, 0}, 2, 3, 1, 0.4, 0.1, 64, 2); }, "torus_knot"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::sphere_grid(599); }, "sphere_grid"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::sphere_grid(100'000'001); }, "sphere_grid"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::random_soup(1, 10, 0.0); }, "random_soup"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::random_soup(1, 2'000'000'000, 1.0); }, "random_soup"));
  EXPECT_TRUE(ThrowsNaming([] { (void)shadowcert::nonmanifold_fan(0); }, "nonmanifold_fan"));
}
