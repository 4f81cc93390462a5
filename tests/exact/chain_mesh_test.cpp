// exact/chain_mesh.h: the exact chain as float homogeneous triangles (what `render --method
// cpu` draws): vertex ids kept, far vertices rounded once from double, quads split with their
// orientation and boundary kept, so a closed chain gives a closed mesh.
#include "exact/chain_mesh.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "support/certificate_test_support.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;
using namespace shadowcert::test_support;

using DirectedEdges = std::map<std::pair<std::uint32_t, std::uint32_t>, int>;

// How often each directed edge occurs, over the mesh's triangles.
DirectedEdges directed_edges(const HomogeneousMesh& mesh) {
  DirectedEdges edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  return edges;
}

// Each directed edge minus its reverse, by vertex id; empty when the mesh is closed
// (docs/definitions.md#closure on ids, as the chain's closure certificate balances them).
DirectedEdges unbalanced(const HomogeneousMesh& mesh) {
  DirectedEdges balance;
  for (const auto& [edge, count] : directed_edges(mesh)) {
    if (edge.first == edge.second) continue;
    const bool forward = edge.first < edge.second;
    balance[forward ? edge : std::pair{edge.second, edge.first}] += forward ? count : -count;
  }
  std::erase_if(balance, [](const auto& entry) { return entry.second == 0; });
  return balance;
}

// Coordinates whose difference with the light's rounds differently in double-then-float and
// in float-then-float (checked below), so the far vertices show which rule was used.
Soup skew_triangle() { return soup_of({{0.1, 0.7, 1.3}, {2.9, 0.35, 0.1}, {0.7, 1.3, 0.35}}, {{0, 1, 2}}); }
const Light kSkewLight = point_light(0.3, 4.1, 5.7);

TEST(ChainMesh, PointLight_FiniteVerticesThenFarVerticesRoundedOnceFromDouble) {
  const Pipeline p = build_pipeline(skew_triangle(), kSkewLight);
  const HomogeneousMesh mesh = chain_mesh(p.chain, p.canonical, kSkewLight);
  const std::size_t n = p.canonical.vertices.size();
  ASSERT_EQ(mesh.vertices.size(), 2 * n);
  bool rounding_told_apart = false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& x = p.canonical.vertices[i];
    const auto& l = kSkewLight.position;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(mesh.vertices[i][k], static_cast<float>(x[k])) << "vertex " << i;
      const float far = static_cast<float>(x[k] - l[k]);
      EXPECT_EQ(mesh.vertices[n + i][k], far) << "far vertex " << i;
      rounding_told_apart |= far != static_cast<float>(x[k]) - static_cast<float>(l[k]);
    }
    EXPECT_EQ(mesh.vertices[i][3], 1.0f);
    EXPECT_EQ(mesh.vertices[n + i][3], 0.0f);
  }
  EXPECT_TRUE(rounding_told_apart) << "the test data no longer distinguishes the two roundings";
}

TEST(ChainMesh, PointLight_EachQuadIsTwoTrianglesWithItsOrientedBoundary) {
  const Pipeline p = build_pipeline(skew_triangle(), kSkewLight);
  ASSERT_EQ(p.chain.triangles.size(), 2u);  // front and back cap
  ASSERT_EQ(p.chain.quads.size(), 3u);
  const HomogeneousMesh mesh = chain_mesh(p.chain, p.canonical, kSkewLight);
  ASSERT_EQ(mesh.triangles.size(), p.chain.triangles.size() + 2 * p.chain.quads.size());
  for (std::size_t i = 0; i < p.chain.triangles.size(); ++i) EXPECT_EQ(mesh.triangles[i], p.chain.triangles[i]);
  const DirectedEdges edges = directed_edges(mesh);
  for (const auto& q : p.chain.quads)
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(edges.count({q[k], q[(k + 1) % 4]}), 1u) << "quad edge " << q[k] << "->" << q[(k + 1) % 4];
  EXPECT_TRUE(unbalanced(mesh).empty());
}

TEST(ChainMesh, DirectionalLight_OneFarVertexAtMinusL) {
  const Light light = directional_light(0.3, 4.1, 5.7);
  const Pipeline p = build_pipeline(skew_triangle(), light);
  const HomogeneousMesh mesh = chain_mesh(p.chain, p.canonical, light);
  const std::size_t n = p.canonical.vertices.size();
  ASSERT_EQ(mesh.vertices.size(), n + 1);
  const std::array<float, 4> far{-0.3f, -4.1f, -5.7f, 0.0f};
  EXPECT_EQ(mesh.vertices[n], far);
  EXPECT_TRUE(p.chain.quads.empty());  // directional sides are triangles (u, v, inf)
  EXPECT_EQ(mesh.triangles, p.chain.triangles);
  EXPECT_TRUE(unbalanced(mesh).empty());
}

// The exact chain is closed on any soup (docs/definitions.md#counts); splitting its quads must keep it so,
// on a non-manifold fan (|m| up to k) and a closed cube, under both light kinds.
TEST(ChainMesh, ClosedChains_GiveClosedMeshes) {
  for (const Soup& soup : {nonmanifold_fan(7), unit_cube(), open_box_with_fins()}) {
    for (const Light& light : {point_light(0.4, 3.0, 0.7), directional_light(0.2, 1.0, -0.3)}) {
      const Pipeline p = build_pipeline(soup, light);
      const HomogeneousMesh mesh = chain_mesh(p.chain, p.canonical, light);
      EXPECT_EQ(mesh.triangles.size(), p.chain.triangles.size() + 2 * p.chain.quads.size());
      EXPECT_TRUE(unbalanced(mesh).empty()) << soup.triangles.size() << " triangles, w " << light.position[3];
    }
  }
}

// Every triangle edge whose two ends are at infinity, as (direction, direction).
std::vector<std::pair<std::array<float, 4>, std::array<float, 4>>> far_edges(const HomogeneousMesh& mesh) {
  std::vector<std::pair<std::array<float, 4>, std::array<float, 4>>> out;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto& a = mesh.vertices[t[k]];
      const auto& b = mesh.vertices[t[(k + 1) % 3]];
      if (a[3] == 0.0f && b[3] == 0.0f) out.push_back({a, b});
    }
  return out;
}

// The shrunk GL campaign case of a point light just off the line of an edge, between its ends
// (tests/regressions/gl/light_between_edge_ends.json): the edge's far vertices u - l and v - l
// are nearly antipodal, and a far triangle spanning them rasterised a third of a 256x192 image
// wrong. Split at the direction of the edge's midpoint (in the side quad and in the back cap
// that shares the far edge), no far edge spans more than a right angle, and the mesh stays closed.
TEST(ChainMesh, LightBetweenAnEdgesEnds_WideFarEdgeIsSplitAndTheMeshStaysClosed) {
  const Soup soup = soup_of({{0.61239820718765259, -1.4280834794044495, -0.2593187689781189},
                             {0.37003326416015625, -1.1857147216796875, -0.25931549072265625},
                             {0.612396240234375, -1.024139404296875, -0.9589691162109375}},
                            {{0, 1, 2}});
  const Light light = point_light(0.4912147521972656, -1.1049270629882812, -0.6091422438621521);
  const Pipeline p = build_pipeline(soup, light);
  const HomogeneousMesh mesh = chain_mesh(p.chain, p.canonical, light);
  EXPECT_GT(mesh.vertices.size(), 2 * p.canonical.vertices.size()) << "no far edge was split";
  EXPECT_TRUE(unbalanced(mesh).empty());
  // Split pieces and the back cap's spokes span at most a right angle, up to the rounding of
  // the directions to float (relative 2^-24 per coordinate, far below this slack): the
  // interpolation between a far edge's ends then stays at least 0.7 of their length away from
  // the zero vector, where clipping loses every digit.
  constexpr double kWidestFarEdgeCosine = -1e-6;
  for (const auto& [a, b] : far_edges(mesh)) {
    const double ab = double{a[0]} * b[0] + double{a[1]} * b[1] + double{a[2]} * b[2];
    const double aa = double{a[0]} * a[0] + double{a[1]} * a[1] + double{a[2]} * a[2];
    const double bb = double{b[0]} * b[0] + double{b[1]} * b[1] + double{b[2]} * b[2];
    EXPECT_GE(ab / std::sqrt(aa * bb), kWidestFarEdgeCosine) << "a far edge close to antipodal";
  }
  // The same volume for the unsplit reference: no edge of this soup is wide for a light far above.
  const Light above = point_light(0.5, 6.0, -0.5);
  const Pipeline q = build_pipeline(soup, above);
  EXPECT_EQ(chain_mesh(q.chain, q.canonical, above).vertices.size(), 2 * q.canonical.vertices.size());
}

// Moving soup and light together by a vector that keeps every sum exact (open_box_with_fins'
// coordinates are binary fractions) moves the finite vertices and leaves the far ones
// (directions x - l) bit for bit unchanged.
TEST(ChainMesh, TranslatedSoupAndLight_SameFarVertices) {
  const Soup soup = open_box_with_fins();
  Soup moved = soup;
  for (Vec3& x : moved.vertices) x = {x[0] + 8.0, x[1] - 4.0, x[2] + 2.0};
  const Light light = point_light(0.5, 3.0, 0.25);
  const Light moved_light = point_light(8.5, -1.0, 2.25);
  const Pipeline p = build_pipeline(soup, light);
  const Pipeline q = build_pipeline(moved, moved_light);
  const HomogeneousMesh a = chain_mesh(p.chain, p.canonical, light);
  const HomogeneousMesh b = chain_mesh(q.chain, q.canonical, moved_light);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  EXPECT_EQ(a.triangles, b.triangles);
  const std::size_t n = p.canonical.vertices.size();
  for (std::size_t i = n; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]) << "far vertex " << i;
}

TEST(ChainMesh, ChainOfAnotherSoupOrLightKind_Throws) {
  const Pipeline p = build_pipeline(skew_triangle(), kSkewLight);
  EXPECT_THROW((void)chain_mesh(p.chain, nonmanifold_fan(3), kSkewLight), std::invalid_argument);
  EXPECT_THROW((void)chain_mesh(p.chain, p.canonical, directional_light(0.0, 1.0, 0.0)), std::invalid_argument);
}

}  // namespace
