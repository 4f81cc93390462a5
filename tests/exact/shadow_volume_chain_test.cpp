// The shadow-volume chain (exact/shadow_volume_chain.h, docs/definitions.md#counts): faces, orientations,
// multiplicity copies, far vertices for both light kinds, and the picture writer.
#include "exact/shadow_volume_chain.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "support/certificate_test_support.h"
#include "io/soup_file.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;
using namespace shadowcert::test_support;

using Face = std::vector<std::uint32_t>;

// A face as a cycle: rotated so that its smallest id comes first (orientation kept).
Face cycle(Face f) {
  std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
  return f;
}

std::vector<Face> faces_of(const ShadowVolumeChain& chain) {
  std::vector<Face> faces;
  for (const auto& t : chain.triangles) faces.push_back(cycle({t[0], t[1], t[2]}));
  for (const auto& q : chain.quads) faces.push_back(cycle({q[0], q[1], q[2], q[3]}));
  std::sort(faces.begin(), faces.end());
  return faces;
}

std::vector<Face> sorted(std::vector<Face> faces) {
  for (Face& f : faces) f = cycle(f);
  std::sort(faces.begin(), faces.end());
  return faces;
}

// Canonical ids: (0,0,0) -> 0, (0,1,0) -> 1, (1,0,0) -> 2 (lexicographic order).
Soup one_triangle(bool counter_clockwise_from_above) {
  if (counter_clockwise_from_above) return soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  return soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 2, 1}});
}

TEST(AssembleChain, TriangleFacingPointLight_FrontCapBackCapAndDesignSideQuads) {
  const Pipeline p = build_pipeline(one_triangle(true), point_light(0.2, 0.2, 5.0));
  // t' = (0, 2, 1) (normal +z, towards the light); far id of x is 3 + x.
  // docs/definitions.md#counts: directed edge (u, v) of t' gives the side quad (v, u, u_inf, v_inf).
  const std::vector<Face> expected = sorted({{0, 2, 1},
                                             {3, 4, 5},  // back cap: t' at infinity, reversed
                                             {2, 0, 3, 5},
                                             {1, 2, 5, 4},
                                             {0, 1, 4, 3}});
  EXPECT_EQ(faces_of(p.chain), expected);
  EXPECT_EQ(p.chain.finite_vertices, 3u);
  EXPECT_FALSE(p.chain.directional);
  ASSERT_EQ(p.chain.cap_triangles.size(), 1u);
  EXPECT_EQ(p.chain.cap_sign[0], Sign::positive);
  EXPECT_EQ(p.chain.side_edges.size(), 3u);
}

TEST(AssembleChain, TriangleFacingAway_SameChainWithReversedCapSign) {
  const Light light = point_light(0.2, 0.2, 5.0);
  const Pipeline towards = build_pipeline(one_triangle(true), light);
  const Pipeline away = build_pipeline(one_triangle(false), light);
  EXPECT_EQ(faces_of(away.chain), faces_of(towards.chain));
  ASSERT_EQ(away.chain.cap_sign.size(), 1u);
  EXPECT_EQ(away.chain.cap_sign[0], Sign::negative);
}

TEST(AssembleChain, FrontCapsFaceTheLight_ForEveryCastingTriangle) {
  const Light light = point_light(3.0, 7.0, -2.0);
  const Soup sphere = uv_sphere({0.0, 0.0, 0.0}, 1.0, 16, 8);
  const Pipeline p = build_pipeline(sphere, light);
  const HomogeneousPoint l = light.position;
  std::size_t caps = 0;
  for (const auto& t : p.chain.triangles) {
    if (t[0] >= p.chain.finite_vertices) continue;  // back caps and sides touch far ids
    if (t[1] >= p.chain.finite_vertices || t[2] >= p.chain.finite_vertices) continue;
    ++caps;
    const auto& v = p.canonical.vertices;
    EXPECT_EQ(orient(finite_point(v[t[0]]), finite_point(v[t[1]]), finite_point(v[t[2]]), l), Sign::positive);
  }
  EXPECT_EQ(caps, p.chain.cap_triangles.size());
}

TEST(AssembleChain, DirectionalLight_OneFarVertexSideTrianglesNoBackCaps) {
  const Pipeline p = build_pipeline(one_triangle(true), directional_light(0.1, 0.2, 1.0));
  // far vertex id 3; directed edge (u, v) of t' = (0, 2, 1) gives (v, u, inf).
  const std::vector<Face> expected = sorted({{0, 2, 1}, {2, 0, 3}, {1, 2, 3}, {0, 1, 3}});
  EXPECT_EQ(faces_of(p.chain), expected);
  EXPECT_TRUE(p.chain.directional);
  EXPECT_TRUE(p.chain.quads.empty());
}

TEST(AssembleChain, Multiplicities_ExpandAbsMCopiesOrientedBySign) {
  Soup s = one_triangle(true);
  const Soup canonical = canonical_soup(s).soup;
  const EdgeTable table = build_edge_table(canonical);
  ASSERT_EQ(table.size(), 3u);  // (0,1), (0,2), (1,2)
  EdgeMultiplicities m;
  m.multiplicity = {3, 0, -2};
  m.triangle_sign = {Sign::zero};
  const ShadowVolumeChain chain = assemble_chain(canonical, table, m, point_light(0, 0, 9));
  EXPECT_TRUE(chain.triangles.empty());
  std::vector<Face> expected;
  for (int k = 0; k < 3; ++k) expected.push_back({0, 1, 4, 3});  // m copies of (u, v, v_inf, u_inf)
  for (int k = 0; k < 2; ++k) expected.push_back({2, 1, 4, 5});  // -(1, 2, 5, 4)
  EXPECT_EQ(faces_of(chain), sorted(expected));
  EXPECT_EQ(chain.side_edges, (std::vector<std::array<std::uint32_t, 2>>{{0, 1}, {1, 2}}));
  EXPECT_EQ(chain.side_multiplicity, (std::vector<std::int32_t>{3, -2}));

  const ShadowVolumeChain directional = assemble_chain(canonical, table, m, directional_light(0, 0, 1));
  std::vector<Face> expected_directional;
  for (int k = 0; k < 3; ++k) expected_directional.push_back({0, 1, 3});
  for (int k = 0; k < 2; ++k) expected_directional.push_back({2, 1, 3});
  EXPECT_EQ(faces_of(directional), sorted(expected_directional));
}

TEST(AssembleChain, ZeroCapSign_NoCaps) {
  const Pipeline p = build_pipeline(one_triangle(true), point_light(5.0, 0.0, 0.0));  // light in the plane
  EXPECT_TRUE(p.chain.triangles.empty());
  EXPECT_TRUE(p.chain.quads.empty());
  EXPECT_TRUE(p.chain.cap_triangles.empty());
}

TEST(AssembleChain, MismatchedInputs_Throw) {
  const Soup canonical = canonical_soup(one_triangle(true)).soup;
  const EdgeTable table = build_edge_table(canonical);
  EdgeMultiplicities m;
  m.multiplicity = {1, 1};  // one short
  m.triangle_sign = {Sign::positive};
  EXPECT_THROW((void)assemble_chain(canonical, table, m, point_light(0, 0, 1)), std::invalid_argument);
  m.multiplicity = {1, 1, 1};
  m.triangle_sign = {};
  EXPECT_THROW((void)assemble_chain(canonical, table, m, point_light(0, 0, 1)), std::invalid_argument);
  m.triangle_sign = {Sign::positive};
  EXPECT_THROW((void)assemble_chain(canonical, table, m, Light{{0, 0, 0, 0}}), std::invalid_argument);
}

class WriteChainFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(WriteChainFormat, PointAndDirectional_ReadBackWithEveryFaceAsTriangles) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "shadowcert_chain_test";
  std::filesystem::create_directories(dir);
  for (const Light& light : {point_light(0.3, 0.2, 4.0), directional_light(0.1, 0.3, 1.0)}) {
    const Pipeline p = build_pipeline(unit_cube(), light);
    const std::filesystem::path file = dir / (std::string("chain") + GetParam());
    write_soup(file, chain_picture(p.chain, p.canonical, light, 10.0));
    const Soup back = read_soup(file);
    EXPECT_EQ(back.vertices.size(), 2 * p.canonical.vertices.size());
    std::size_t expected = p.chain.triangles.size() + 2 * p.chain.quads.size();
    if (light.directional()) expected += p.chain.triangles.size() - p.chain.cap_triangles.size();  // sides as quads
    EXPECT_EQ(back.triangles.size(), expected);
    std::filesystem::remove(file);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, WriteChainFormat, ::testing::Values(".off", ".obj", ".ply"));

}  // namespace
