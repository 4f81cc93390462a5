// The edge table of a canonical soup (scene/edge_table.h) against hand counts and against an
// independent std::map construction.
#include "scene/edge_table.h"

#include <gtest/gtest.h>

#include <iostream>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>

#include "scene/canonical_soup.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

// (u, v) -> [(triangle, opposite)] in ascending triangle order: the documented table order.
using BruteTable = std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::uint32_t, std::uint32_t>>>;

BruteTable brute_table(const Soup& soup) {
  BruteTable table;
  for (std::uint32_t t = 0; t < soup.triangles.size(); ++t) {
    const Triangle& tri = soup.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      table[{std::min(a, b), std::max(a, b)}].push_back({t, tri[(k + 2) % 3]});
    }
  }
  return table;
}

void expect_equal(const EdgeTable& table, const BruteTable& expected) {
  ASSERT_EQ(table.size(), expected.size());
  ASSERT_EQ(table.first_opposite.size(), table.size() + 1);
  ASSERT_EQ(table.first_opposite.front(), 0u);
  ASSERT_EQ(table.opposite_vertex.size(), table.first_opposite.back());
  ASSERT_EQ(table.opposite_triangle.size(), table.first_opposite.back());
  std::size_t e = 0;
  for (const auto& [edge, uses] : expected) {
    ASSERT_EQ(table.edges[e][0], edge.first) << "edge " << e;
    ASSERT_EQ(table.edges[e][1], edge.second) << "edge " << e;
    ASSERT_EQ(table.first_opposite[e + 1] - table.first_opposite[e], uses.size()) << "edge " << e;
    for (std::size_t i = 0; i < uses.size(); ++i) {
      EXPECT_EQ(table.opposite_triangle[table.first_opposite[e] + i], uses[i].first);
      EXPECT_EQ(table.opposite_vertex[table.first_opposite[e] + i], uses[i].second);
    }
    ++e;
  }
}

TEST(BuildEdgeTable, ClosedCube_EighteenEdgesTwoOppositesEach) {
  const Soup cube = canonical_soup(box({0, 0, 0}, {1, 1, 1})).soup;
  const EdgeTable table = build_edge_table(cube);
  ASSERT_EQ(table.size(), 18u);
  for (std::size_t e = 0; e < table.size(); ++e) {
    EXPECT_EQ(table.first_opposite[e + 1] - table.first_opposite[e], 2u);
    EXPECT_LT(table.edges[e][0], table.edges[e][1]);
    if (e > 0) {
      EXPECT_LT(table.edges[e - 1], table.edges[e]);
    }
  }
  expect_equal(table, brute_table(cube));
}

TEST(BuildEdgeTable, FanOfK_OneEdgeWithKOpposites) {
  for (std::uint32_t k : {1u, 2u, 3u, 17u, 64u, 256u}) {
    const Soup fan = canonical_soup(nonmanifold_fan(k)).soup;
    const EdgeTable table = build_edge_table(fan);
    ASSERT_EQ(table.size(), 1 + 2 * std::size_t{k}) << "k=" << k;
    std::size_t shared = 0;
    for (std::size_t e = 0; e < table.size(); ++e) {
      const std::uint32_t count = table.first_opposite[e + 1] - table.first_opposite[e];
      if (count == k && k > 1) ++shared;
      if (count != k) {
        EXPECT_EQ(count, 1u);
      }
    }
    if (k > 1) {
      EXPECT_EQ(shared, 1u) << "k=" << k;
    }
    expect_equal(table, brute_table(fan));
  }
}

TEST(BuildEdgeTable, RepeatedIndexTriangles_ContributeNothing) {
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.triangles = {{0, 0, 1}, {1, 2, 2}, {2, 0, 2}, {1, 1, 1}};
  const EdgeTable table = build_edge_table(s);
  EXPECT_EQ(table.size(), 0u);
  EXPECT_EQ(table.first_opposite, (std::vector<std::uint32_t>{0}));
  EXPECT_TRUE(table.opposite_vertex.empty());

  s.triangles.push_back({0, 1, 2});
  const EdgeTable one = build_edge_table(s);
  ASSERT_EQ(one.size(), 3u);
  for (std::uint32_t t : one.opposite_triangle) EXPECT_EQ(t, 4u);
}

TEST(BuildEdgeTable, DuplicateAndFlippedTriangles_AppearOncePerCopy) {
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.triangles = {{0, 1, 2}, {0, 1, 2}, {2, 1, 0}};
  const EdgeTable table = build_edge_table(s);
  ASSERT_EQ(table.size(), 3u);
  EXPECT_EQ(table.edges[0], (std::array<std::uint32_t, 2>{0, 1}));
  EXPECT_EQ(table.edges[1], (std::array<std::uint32_t, 2>{0, 2}));
  EXPECT_EQ(table.edges[2], (std::array<std::uint32_t, 2>{1, 2}));
  for (std::size_t e = 0; e < 3; ++e) {
    ASSERT_EQ(table.first_opposite[e + 1] - table.first_opposite[e], 3u);
    for (std::uint32_t i = 0; i < 3; ++i) EXPECT_EQ(table.opposite_triangle[table.first_opposite[e] + i], i);
  }
  EXPECT_EQ(table.opposite_vertex, (std::vector<std::uint32_t>{2, 2, 2, 1, 1, 1, 0, 0, 0}));
}

TEST(BuildEdgeTable, EmptySoup_EmptyTable) {
  const EdgeTable table = build_edge_table(Soup{});
  EXPECT_EQ(table.size(), 0u);
  EXPECT_EQ(table.first_opposite, (std::vector<std::uint32_t>{0}));
}

TEST(BuildEdgeTable, IndexOutOfRange_Throws) {
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.triangles = {{0, 1, 3}};
  EXPECT_THROW((void)build_edge_table(s), std::invalid_argument);
}

TEST(BuildEdgeTable, RandomIndexSoups_MatchMapConstruction) {
  constexpr std::uint64_t kSeed = 77;
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 engine(kSeed);
  for (int round = 0; round < 50; ++round) {
    const auto n = static_cast<std::uint32_t>(3 + engine() % 40);
    Soup s;
    s.vertices.assign(n, Vec3{0, 0, 0});  // positions play no part in the table
    const std::size_t triangles = engine() % 400;
    for (std::size_t t = 0; t < triangles; ++t)
      s.triangles.push_back({static_cast<std::uint32_t>(engine() % n), static_cast<std::uint32_t>(engine() % n),
                             static_cast<std::uint32_t>(engine() % n)});
    expect_equal(build_edge_table(s), brute_table(s));
  }
}

TEST(BuildEdgeTable, VertexWithManyEdges_SortedLikeMap) {
  // One vertex in every triangle (a cone apex with 2000 uses): the bucket sort's large path.
  Soup s;
  s.vertices.assign(1002, Vec3{0, 0, 0});
  for (std::uint32_t i = 0; i < 1000; ++i) s.triangles.push_back({0, 1 + (i * 7919) % 1001, 1 + (i * 7919 + 1) % 1001});
  expect_equal(build_edge_table(s), brute_table(s));
}

}  // namespace
