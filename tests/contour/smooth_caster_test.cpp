// contour/smooth_caster.h: which soups qualify as smooth casters (and the report naming the
// offenders when they do not), the corner normals (file, or computed with a crease angle) and
// the connectivity across edges.
#include "contour/smooth_caster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "core/vector3.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

SmoothCaster qualified(const Soup& soup, const SmoothCasterOptions& options = {}) {
  SmoothCasterResult r = smooth_caster(soup, options);
  EXPECT_TRUE(r.qualification.qualifies()) << r.qualification.summary();
  if (!r.caster) throw std::runtime_error("no caster");
  return *r.caster;
}

std::size_t count_creases(const SmoothCaster& c) {
  std::size_t n = 0;
  for (const auto& t : c.crease) n += std::size_t{t[0]} + t[1] + t[2];
  return n / 2;  // each crease edge is seen from both triangles
}

std::size_t count_borders(const SmoothCaster& c) {
  std::size_t n = 0;
  for (const auto& t : c.across)
    for (std::uint32_t a : t) n += a == kBorder;
  return n;
}

double angle_degrees(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(dot(a, b) / std::sqrt(dot(a, a) * dot(b, b)), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

TEST(SmoothCaster, UvSphere_QualifiesClosedAndSmooth) {
  const Soup sphere = uv_sphere({0, 0, 0}, 1.0, 12, 6);
  ASSERT_FALSE(sphere.normals.empty());  // the generator's radial normals
  EXPECT_EQ(qualified(sphere).normal_source, CornerNormalSource::file);
  const SmoothCaster c = qualified(sphere, {.use_file_normals = false});
  EXPECT_EQ(c.normal_source, CornerNormalSource::computed);
  EXPECT_EQ(count_borders(c), 0u);
  EXPECT_EQ(count_creases(c), 0u);
  EXPECT_EQ(c.wedge_vertex.size(), c.vertices.size());  // smooth everywhere: one wedge per vertex
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(c.wedge_vertex[c.wedge[t][k]], c.triangles[t][k]);
      EXPECT_EQ(c.wedge_normal[c.wedge[t][k]], c.normals[t][k]);
    }
  // Every corner normal is close to the radial direction, and bitwise one per vertex.
  std::map<std::uint32_t, Vec3> at_vertex;
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const auto [it, inserted] = at_vertex.emplace(c.triangles[t][k], c.normals[t][k]);
      EXPECT_EQ(it->second, c.normals[t][k]);
    }
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(dot(c.normals[t][k], c.normals[t][k]), 1.0, 1e-12);
      EXPECT_LT(angle_degrees(c.normals[t][k], c.vertices[c.triangles[t][k]]), 8.0) << t << ", " << k;
    }
}

TEST(SmoothCaster, Box_CreasesItsTwelveEdgesButNotTheFaceDiagonals) {
  const SmoothCaster c = qualified(box({0, 0, 0}, {1, 2, 3}));
  EXPECT_EQ(count_borders(c), 0u);
  EXPECT_EQ(count_creases(c), 12u);
  EXPECT_EQ(c.crease_edges.size(), 12u);
  EXPECT_EQ(c.wedge_vertex.size(), 24u);  // each cube corner: three faces, three normals
  for (std::size_t t = 0; t < c.triangles.size(); ++t) {
    const Triangle& tri = c.triangles[t];
    const Vec3 face = normalized(cross(difference(c.vertices[tri[1]], c.vertices[tri[0]]),
                                       difference(c.vertices[tri[2]], c.vertices[tri[0]])));
    for (std::size_t k = 0; k < 3; ++k) EXPECT_LT(angle_degrees(c.normals[t][k], face), 1e-6);
  }
}

TEST(SmoothCaster, CreaseAngleAboveTheDihedral_AveragesAcrossTheBoxEdges) {
  const SmoothCaster c = qualified(box({0, 0, 0}, {1, 1, 1}), {.crease_angle_degrees = 120.0});
  EXPECT_EQ(count_creases(c), 0u);
  // Each corner of the cube gets one normal along its diagonal (the three faces' normals
  // summed; two triangles of a face count twice, so the diagonal is exact only up to that).
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& v = c.vertices[c.triangles[t][k]];
      const Vec3 outward{v[0] - 0.5, v[1] - 0.5, v[2] - 0.5};
      EXPECT_LT(angle_degrees(c.normals[t][k], outward), 20.0);
    }
}

TEST(SmoothCaster, OpenFloor_QualifiesWithBorders) {
  const SmoothCaster c = qualified(floor_quad(2.0));
  EXPECT_EQ(count_borders(c), 4u);
  EXPECT_EQ(c.across[0][0] == kBorder ? 0 : 1, c.across[0][0] == kBorder ? 0 : 1);
}

TEST(SmoothCaster, FileNormals_AreTakenPerCorner) {
  Soup soup = floor_quad(1.0);
  soup.normals.assign(soup.vertices.size(), Normal{0.0f, 2.0f, 0.0f});
  soup.normals[0] = {0.0f, 1.0f, 1.0f};
  const SmoothCaster c = qualified(soup);
  EXPECT_EQ(c.normal_source, CornerNormalSource::file);
  for (std::size_t t = 0; t < c.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3 expected = soup.triangles[t][k] == 0 ? normalized(Vec3{0, 1, 1}) : Vec3{0, 1, 0};
      EXPECT_LT(angle_degrees(c.normals[t][k], expected), 1e-9);
    }
  const SmoothCaster computed = qualified(soup, {.use_file_normals = false});
  EXPECT_EQ(computed.normal_source, CornerNormalSource::computed);
}

TEST(SmoothCaster, ThreeTrianglesOnOneEdge_AreANonManifoldEdge) {
  const SmoothCasterResult r = smooth_caster(nonmanifold_fan(3));
  EXPECT_FALSE(r.caster);
  EXPECT_EQ(r.qualification.non_manifold_edge_count, 1u);
  EXPECT_NE(r.qualification.summary().find("1 non-manifold edge ((0, 1))"), std::string::npos)
      << r.qualification.summary();
}

TEST(SmoothCaster, TwoTrianglesRunningAnEdgeTheSameWay_AreMisoriented) {
  const Soup soup{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 1, 3}}, {}};
  const SmoothCasterResult r = smooth_caster(soup);
  EXPECT_FALSE(r.caster);
  ASSERT_EQ(r.qualification.misoriented_edges.size(), 1u);
  EXPECT_EQ(r.qualification.misoriented_edges[0], (std::array<std::uint32_t, 2>{0, 1}));
  EXPECT_EQ(r.qualification.summary(), "not an oriented 2-manifold: 1 misoriented edge ((0, 1))");
}

TEST(SmoothCaster, TwoFansTouchingAtAVertex_AreANonManifoldVertex) {
  // Two triangles sharing only vertex 0 (a bow tie).
  const Soup soup{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}, {}};
  const SmoothCasterResult r = smooth_caster(soup);
  EXPECT_FALSE(r.caster);
  EXPECT_EQ(r.qualification.non_manifold_vertices, (std::vector<std::uint32_t>{0}));
}

TEST(SmoothCaster, RepeatedIndexOrCollinearTriangle_IsDegenerate) {
  const Soup soup{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}}, {{0, 1, 3}, {0, 0, 3}, {0, 1, 2}}, {}};
  const SmoothCasterResult r = smooth_caster(soup);
  EXPECT_FALSE(r.caster);
  EXPECT_EQ(r.qualification.degenerate_triangles, (std::vector<std::uint32_t>{1, 2}));
}

TEST(SmoothCaster, DuplicatedPositions_AreWeldedIntoOneMesh) {
  // The floor's two triangles with their shared edge's vertices duplicated: welded, one edge.
  const Soup soup{{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 2, 1}, {3, 5, 4}}, {}};
  const SmoothCaster c = qualified(soup);
  EXPECT_EQ(count_borders(c), 4u);
}

TEST(SmoothCaster, VertexRelabellingAndTranslation_LeaveTheCornerNormalsUnchanged) {
  const Soup sphere = uv_sphere({0, 0, 0}, 1.0, 10, 5);
  Soup relabelled = sphere;
  const std::size_t n = sphere.vertices.size();
  for (std::size_t i = 0; i < n; ++i) relabelled.vertices[n - 1 - i] = sphere.vertices[i];
  for (Triangle& t : relabelled.triangles)
    for (std::uint32_t& v : t) v = static_cast<std::uint32_t>(n - 1 - v);
  Soup moved = sphere;
  for (Vec3& v : moved.vertices) v = {v[0] + 8.0, v[1] - 4.0, v[2] + 2.0};
  for (std::size_t i = 0; i < n; ++i) relabelled.normals[n - 1 - i] = sphere.normals[i];
  for (const bool file : {true, false}) {
    const SmoothCaster c = qualified(sphere, {.use_file_normals = file});
    for (const Soup& other : {relabelled, moved}) {
      const SmoothCaster d = qualified(other, {.use_file_normals = file});
      for (std::size_t t = 0; t < c.triangles.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k)
          for (std::size_t i = 0; i < 3; ++i)
            EXPECT_NEAR(c.normals[t][k][i], d.normals[t][k][i], 1e-12) << file << ", " << t << ", " << k;
    }
  }
}

TEST(SmoothCaster, BadOptionsOrIndices_ThrowNamingTheFunction) {
  EXPECT_THROW((void)smooth_caster(floor_quad(1.0), {.crease_angle_degrees = -1.0}), std::invalid_argument);
  const Soup bad{{{0, 0, 0}}, {{0, 1, 2}}, {}};
  try {
    (void)smooth_caster(bad);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("smooth_caster:", 0), 0u) << e.what();
  }
}

TEST(SmoothCaster, EmptySoup_QualifiesAsAnEmptyCaster) {
  const SmoothCaster c = qualified(Soup{});
  EXPECT_TRUE(c.triangles.empty());
}

}  // namespace
