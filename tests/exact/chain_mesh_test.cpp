// exact/chain_mesh.h: the exact chain as float homogeneous triangles (what `render --method
// cpu` draws): vertex ids kept, far vertices rounded once from double, quads split with their
// orientation and boundary kept, so a closed chain gives a closed mesh.
#include "exact/chain_mesh.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <utility>

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
