// Exact self-intersections of welded soups (exact/triangle_soup_self_intersections.h):
// every sharing case of docs/definitions.md#caster-diagnostics by hand, then the parallel split against brute force.
#include "core/vector3.h"
#include "exact/triangle_soup_self_intersections.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "exact/degenerate_triangles.h"
#include "scene/procedural_mesh.h"
#include "scene/welded_soup.h"

namespace {

using shadowcert::find_self_intersecting_pairs;
using shadowcert::Soup;
using shadowcert::cross;
using shadowcert::difference;
using shadowcert::dot;
using shadowcert::Triangle;
using shadowcert::TrianglePair;
using shadowcert::Vec3;

Soup soup_of(std::vector<Vec3> vertices, std::vector<Triangle> triangles) {
  Soup s;
  s.vertices = std::move(vertices);
  s.triangles = std::move(triangles);
  return shadowcert::weld_soup(s).soup;
}

std::size_t pair_count(const Soup& s) { return find_self_intersecting_pairs(s).size(); }

// Two triangles without a common vertex.
TEST(SelfIntersections, CrossingTriangles_OnePair) {
  const Soup s = soup_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {5, 5, 0}},
                         {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(find_self_intersecting_pairs(s), (std::vector<TrianglePair>{{0, 1}}));
}

TEST(SelfIntersections, SeparateTrianglesWithTouchingBoxes_None) {
  // The boxes share the plane x = 1, the triangles do not meet.
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}, {2, 2, 0}}, {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(pair_count(s), 0u);
}

TEST(SelfIntersections, TJunctionVertexOnForeignEdge_OnePair) {
  // (1, 0, 0) is a vertex of the second triangle and an interior point of the first's edge:
  // not a common vertex, so the contact is not accounted for (a T-junction, a crack).
  const Soup s = soup_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0, 0}, {1, -1, 1}, {1, -1, -1}},
                         {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(pair_count(s), 1u);
}

TEST(SelfIntersections, TouchingAtOnePointOffTheFloatGrid_OnePair) {
  // The boxes touch only in the plane x = 0.1, a double that no float equals: the candidate
  // boxes (float) must still meet there. The first triangle's corner (0.1, 0, 0) is the
  // midpoint of the second's first edge, a contact no common vertex accounts for.
  const Soup s = soup_of({{0, 0, 0}, {0.1, 0, 0}, {0, 1, 0}, {0.1, -1, -1}, {0.1, 1, 1}, {5, 0, 0}},
                         {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(pair_count(s), 1u);
}

TEST(SelfIntersections, HugeCoordinatesBeyondFloatRange_Found) {
  const double big = 1e300;
  const Soup s = soup_of({{0, 0, 0}, {2 * big, 0, 0}, {0, 2 * big, 0}, {big / 4, big / 4, -big}, {big / 4, big / 4, big},
                          {3 * big, 3 * big, 0}},
                         {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(pair_count(s), 1u);
}

// One common vertex.
TEST(SelfIntersections, CommonVertexTouchingOnlyThere_None) {
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, 0, 1}}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(pair_count(s), 0u);
}

TEST(SelfIntersections, CommonVertexCoplanarTouchingOnlyThere_None) {
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(pair_count(s), 0u);
}

TEST(SelfIntersections, CommonVertexCoplanarSharingARay_OnePair) {
  // Both contain the segment from the origin along +x: they meet beyond the common vertex.
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(pair_count(s), 1u);
}

TEST(SelfIntersections, CommonVertexCrossingElsewhere_OnePair) {
  const Soup s = soup_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 1, -1}, {1, 1, 1}}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(pair_count(s), 1u);
}

TEST(SelfIntersections, CommonVertexCoplanarNested_OnePair) {
  const Soup s = soup_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0.5, 0}, {0.5, 1, 0}}, {{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(pair_count(s), 1u);
}

// Two common vertices (a common edge).
TEST(SelfIntersections, CommonEdgeFold_None) {
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}});
  EXPECT_EQ(pair_count(s), 0u);
}

TEST(SelfIntersections, CommonEdgeCoplanarHinge_None) {
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}}, {{0, 1, 2}, {1, 0, 3}});
  EXPECT_EQ(pair_count(s), 0u);
}

TEST(SelfIntersections, CommonEdgeCoplanarOverlap_OnePair) {
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 2}, {1, 0, 3}});
  EXPECT_EQ(pair_count(s), 1u);
}

TEST(SelfIntersections, CommonEdgeFoldOneUlpOffThePlane_None) {
  // The opposite vertex a denormal away from the common plane: exact predicates see a fold.
  const double tiny = std::nextafter(0.0, 1.0);
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, tiny}}, {{0, 1, 2}, {1, 0, 3}});
  EXPECT_EQ(pair_count(s), 0u);
}

TEST(SelfIntersections, CommonEdgeTiltedCoplanarOverlap_OnePair) {
  // All four points in the plane y = z, which no axis-aligned projection keeps flat-on.
  const Soup s = soup_of({{0, 0, 0}, {1, 1, 1}, {1, 0, 0}, {2, 1, 1}}, {{0, 1, 2}, {1, 0, 3}});
  EXPECT_EQ(pair_count(s), 1u);
}

TEST(SelfIntersections, CommonEdgeTiltedCoplanarHinge_None) {
  const Soup s = soup_of({{0, 0, 0}, {1, 1, 1}, {1, 0, 0}, {-1, 0, 0}}, {{0, 1, 2}, {1, 0, 3}});
  EXPECT_EQ(pair_count(s), 0u);
}

TEST(SelfIntersections, CommonEdgeVerticalCoplanarOverlap_OnePair) {
  const Soup s = soup_of({{0, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 1, 1}}, {{0, 1, 2}, {1, 0, 3}});
  EXPECT_EQ(pair_count(s), 1u);
}

// Integer reference for the common-edge rule: on small integer coordinates every determinant
// is exact in int64, so the rule itself (coplanar, and r, s on the same side of pq) can be
// evaluated directly. A grid this small makes coplanar and collinear configurations common.
std::array<std::int64_t, 3> minus(const Vec3& a, const Vec3& b) {
  return {static_cast<std::int64_t>(a[0] - b[0]), static_cast<std::int64_t>(a[1] - b[1]),
          static_cast<std::int64_t>(a[2] - b[2])};
}

TEST(SelfIntersections, CommonEdgeOnIntegerGrid_MatchesIntegerReference) {
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> coordinate(-2, 2);
  const auto random_point = [&] { return Vec3{double(coordinate(rng)), double(coordinate(rng)), double(coordinate(rng))}; };
  int overlaps = 0;
  int checked = 0;
  while (checked < 3000) {
    const Vec3 p = random_point(), q = random_point(), r = random_point(), t = random_point();
    const auto n_r = cross(minus(q, p), minus(r, p));
    const auto n_t = cross(minus(q, p), minus(t, p));
    if (n_r == std::array<std::int64_t, 3>{0, 0, 0} || n_t == std::array<std::int64_t, 3>{0, 0, 0}) continue;
    if (r == t) continue;  // a duplicate, not a common edge
    const bool coplanar = dot(n_r, minus(t, p)) == 0;
    const bool expected = coplanar && dot(n_r, n_t) > 0;
    const Soup s = soup_of({p, q, r, t}, {{0, 1, 2}, {1, 0, 3}});
    EXPECT_EQ(pair_count(s), expected ? 1u : 0u) << "p q r s = " << p[0] << p[1] << p[2] << " " << q[0] << q[1]
                                                 << q[2] << " " << r[0] << r[1] << r[2] << " " << t[0] << t[1] << t[2];
    overlaps += expected;
    ++checked;
  }
  EXPECT_GT(overlaps, 50);
}

// Three common vertices (duplicates).
TEST(SelfIntersections, DuplicateAndFlippedDuplicate_EveryPair) {
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {2, 1, 0}, {1, 2, 0}});
  EXPECT_EQ(find_self_intersecting_pairs(s), (std::vector<TrianglePair>{{0, 1}, {0, 2}, {1, 2}}));
}

TEST(SelfIntersections, DuplicateBeforeWelding_OnePair) {
  // Bitwise-equal copies of the corners under other indices: welding makes them common.
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}}, {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(pair_count(s), 1u);
}

// Degenerate triangles cast nothing (docs/definitions.md#orientation) and are skipped.
TEST(SelfIntersections, CollinearTrianglePiercingAFace_None) {
  const Soup s = soup_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 0}, {0.5, 0.5, 1}},
                         {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(pair_count(s), 0u);
}

TEST(SelfIntersections, RepeatedIndexTriangleOnAFace_None) {
  const Soup s = soup_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}}, {{0, 1, 2}, {3, 3, 0}});
  EXPECT_EQ(pair_count(s), 0u);
}

TEST(SelfIntersections, ShapesOfWrongSize_Throws) {
  const Soup s = soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  EXPECT_THROW((void)find_self_intersecting_pairs(s, std::vector<shadowcert::TriangleShape>{}), std::invalid_argument);
}

TEST(SelfIntersections, ClosedIcosphere_None) {
  EXPECT_EQ(pair_count(shadowcert::weld_soup(shadowcert::icosphere({0, 0, 0}, 1.0, 4)).soup), 0u);
}

// The all-pairs reference: every pair of triangles whose closed boxes overlap, decided on a
// soup of those two triangles alone (same vertex array, so common vertices stay common).
std::vector<TrianglePair> brute_force_pairs(const Soup& s) {
  const auto shapes = shadowcert::classify_triangle_shapes(s);
  struct Box {
    Vec3 lo, hi;
  };
  std::vector<Box> boxes(s.triangles.size());
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    Box b{s.vertices[s.triangles[t][0]], s.vertices[s.triangles[t][0]]};
    for (std::uint32_t v : s.triangles[t])
      for (int d = 0; d < 3; ++d) {
        b.lo[d] = std::min(b.lo[d], s.vertices[v][d]);
        b.hi[d] = std::max(b.hi[d], s.vertices[v][d]);
      }
    boxes[t] = b;
  }
  const auto overlap = [](const Box& a, const Box& b) {
    for (int d = 0; d < 3; ++d)
      if (a.hi[d] < b.lo[d] || b.hi[d] < a.lo[d]) return false;
    return true;
  };
  std::vector<TrianglePair> pairs;
  Soup two;
  two.vertices = s.vertices;
  for (std::uint32_t a = 0; a < s.triangles.size(); ++a)
    for (std::uint32_t b = a + 1; b < s.triangles.size(); ++b) {
      if (!overlap(boxes[a], boxes[b])) continue;
      two.triangles = {s.triangles[a], s.triangles[b]};
      if (!find_self_intersecting_pairs(two, std::vector{shapes[a], shapes[b]}).empty()) pairs.emplace_back(a, b);
    }
  return pairs;
}

TEST(SelfIntersections, LargeSoupSplitInParallel_MatchesBruteForce) {
  // Enough boxes for the median splits to happen (more than 2^14 per part at the top), with
  // meshes whose neighbours share vertices and edges, and small random triangles crossing
  // them and each other anywhere, the split planes included.
  Soup s = shadowcert::sphere_grid(20'000);
  s.normals.clear();
  const Soup sprinkles = shadowcert::random_soup(3, 3'000, 12.0);
  const auto base = static_cast<std::uint32_t>(s.vertices.size());
  for (const Vec3& p : sprinkles.vertices) s.vertices.push_back(p);
  for (Triangle t : sprinkles.triangles) {
    // Shrink each to a small triangle near its first corner, on the grid's height range.
    for (int k = 1; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        s.vertices[base + t[k]][d] = s.vertices[base + t[0]][d] + (sprinkles.vertices[t[k]][d] - sprinkles.vertices[t[0]][d]) / 16;
    for (std::uint32_t& v : t) v += base;
    s.triangles.push_back(t);
  }
  for (std::size_t v = base; v < s.vertices.size(); ++v) s.vertices[v][1] = 1.0 + s.vertices[v][1] / 12.0;
  const Soup welded = shadowcert::weld_soup(s).soup;
  const auto pairs = find_self_intersecting_pairs(welded);
  EXPECT_GT(pairs.size(), 100u);
  EXPECT_EQ(pairs, brute_force_pairs(welded));
}

}  // namespace
