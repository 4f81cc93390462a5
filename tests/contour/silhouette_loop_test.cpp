// contour/silhouette_loop.h: discrete and accurate silhouette loops, held to the geometry they
// approximate (the circle where a sphere's normals turn from the light), closed on closed
// casters, ending at borders on open ones, the two methods equal where every edge is a crease,
// and unchanged by vertex relabelling.
#include "contour/silhouette_loop.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/vector3.h"
#include "scene/procedural_mesh.h"
#include "support/contour_test_support.h"

namespace {

using namespace shadowcert;
using test_support::caster_of;
using test_support::face_sides;
using test_support::lit_faces;

Light point_light(double x, double y, double z) { return Light{{x, y, z, 1.0}}; }
Light directional(double x, double y, double z) { return Light{{x, y, z, 0.0}}; }

std::size_t closed_loops(const std::vector<SilhouetteLoop>& loops) {
  return static_cast<std::size_t>(std::count_if(loops.begin(), loops.end(), [](const auto& l) { return l.closed; }));
}

// The directed segments of the loops, as position pairs.
std::set<std::pair<Vec3, Vec3>> segments(const std::vector<SilhouetteLoop>& loops) {
  std::set<std::pair<Vec3, Vec3>> out;
  for (const SilhouetteLoop& loop : loops) {
    const std::size_t n = loop.points.size();
    for (std::size_t i = 0; i + 1 < n + (loop.closed ? 1 : 0); ++i)
      out.emplace(loop.points[i].position, loop.points[(i + 1) % n].position);
  }
  return out;
}

TEST(AccurateSilhouette, SphereUnderAPointLight_IsOneClosedLoopOnTheTangentCircle) {
  // Light at distance 5 on +z: the smooth silhouette is the circle z = 1/5 of radius sqrt(24)/5.
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 48, 24));
  const std::vector<SilhouetteLoop> loops = accurate_silhouette(c, point_light(0.0, 0.0, 5.0));
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_TRUE(loops[0].closed);
  EXPECT_GE(loops[0].points.size(), 48u);
  for (const SilhouettePoint& p : loops[0].points) {
    // On a chord of the sphere (|p| within 1 - cos(pi / 24)) near the circle, its normal tangent.
    EXPECT_NEAR(std::sqrt(dot(p.position, p.position)), 1.0, 0.01);
    EXPECT_NEAR(p.position[2], 0.2, 0.01);
    const Vec3 to_light{-p.position[0], -p.position[1], 5.0 - p.position[2]};
    EXPECT_NEAR(dot(p.normal, normalized(to_light)), 0.0, 0.01);
    EXPECT_NEAR(dot(p.normal, p.normal), 1.0, 1e-12);
    EXPECT_LT(p.edge_from, p.edge_to);
    EXPECT_GT(p.u, 0.0);
    EXPECT_LT(p.u, 1.0);
  }
}

TEST(AccurateSilhouette, LoopRunsWithTheLitPartOnItsLeft) {
  // Seen from the light (+z, above the circle z = 0.2), a loop with the lit cap on its left
  // turns counter-clockwise: its signed area in the xy plane is positive.
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 32, 16));
  const std::vector<SilhouetteLoop> loops = accurate_silhouette(c, point_light(0.0, 0.0, 5.0));
  ASSERT_EQ(loops.size(), 1u);
  double area = 0.0;
  const auto& pts = loops[0].points;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec3& p = pts[i].position;
    const Vec3& q = pts[(i + 1) % pts.size()].position;
    area += p[0] * q[1] - q[0] * p[1];
  }
  EXPECT_GT(area, 0.0);
}

TEST(AccurateSilhouette, DirectionalLight_IsTheGreatCircleAcrossIt) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 40, 20));
  const std::vector<SilhouetteLoop> loops = accurate_silhouette(c, directional(1.0, 0.5, 0.25));
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_TRUE(loops[0].closed);
  const Vec3 d = normalized(Vec3{1.0, 0.5, 0.25});
  for (const SilhouettePoint& p : loops[0].points) EXPECT_NEAR(dot(p.position, d), 0.0, 0.01);
}

TEST(AccurateSilhouette, TorusLitAlongItsAxis_HasTwoClosedLoops_EvenThroughZeroCorners) {
  // The ring of vertices at the tube's equators has f = 0 exactly (normal (cos u, 0, sin u)):
  // lit by the fixed rule, the loops pass through those vertices and stay closed.
  const SmoothCaster c = caster_of(torus({0, 0, 0}, 2.0, 0.5, 32, 16));
  for (const Light& light : {directional(0.0, 1.0, 0.0), directional(0.1, 1.0, 0.05)}) {
    const std::vector<SilhouetteLoop> loops = accurate_silhouette(c, light);
    EXPECT_EQ(loops.size(), 2u);
    EXPECT_EQ(closed_loops(loops), loops.size());
  }
}

TEST(AccurateSilhouette, OpenHemisphere_EndsAtItsBorder) {
  Soup sphere = uv_sphere({0, 0, 0}, 1.0, 32, 16);
  Soup half = sphere;
  half.triangles.clear();
  for (const Triangle& t : sphere.triangles)
    if (sphere.vertices[t[0]][2] + sphere.vertices[t[1]][2] + sphere.vertices[t[2]][2] > 0.0) half.triangles.push_back(t);
  const SmoothCaster c = caster_of(half);
  // Light along x: the silhouette is the half of the great circle x = 0 with z > 0.
  const std::vector<SilhouetteLoop> loops = accurate_silhouette(c, directional(1.0, 0.0, 0.0));
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_FALSE(loops[0].closed);
  // Both ends on the border z = 0 (the triangles' lowest ring).
  EXPECT_NEAR(loops[0].points.front().position[2], 0.0, 1e-9);
  EXPECT_NEAR(loops[0].points.back().position[2], 0.0, 1e-9);
}

TEST(AccurateSilhouette, CubeWithEveryEdgeACrease_IsTheDiscreteSilhouette) {
  // Flat faces: f is constant on each face, so the accurate silhouette runs along the creases
  // between lit and unlit faces, exactly the discrete one.
  const SmoothCaster c = caster_of(box({0, 0, 0}, {1, 1, 1}));
  for (const Light& light : {point_light(3.0, 4.0, 5.0), point_light(0.5, 3.0, 0.5), directional(1.0, 2.0, 3.0)}) {
    const std::vector<SilhouetteLoop> accurate = accurate_silhouette(c, light);
    const std::vector<SilhouetteLoop> discrete = discrete_silhouette(c, lit_faces(c, light));
    ASSERT_EQ(discrete.size(), 1u);
    EXPECT_TRUE(discrete[0].closed);
    EXPECT_EQ(closed_loops(accurate), accurate.size());
    EXPECT_EQ(segments(accurate), segments(discrete));
  }
}

TEST(AccurateSilhouette, SmoothedCube_IsOneClosedLoop) {
  const SmoothCaster c = caster_of(box({0, 0, 0}, {1, 1, 1}), {.crease_angle_degrees = 120.0});
  const std::vector<SilhouetteLoop> loops = accurate_silhouette(c, point_light(3.0, 4.0, 5.0));
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_TRUE(loops[0].closed);
}

TEST(AccurateSilhouette, CreaseBetweenTwoSmoothHalves_DoublesItsPoint) {
  // A cylinder-like crease: two smooth half-spheres, the crease along the equator y = 0 (file
  // normals bent apart there so the two sides' normals differ).
  Soup sphere = uv_sphere({0, 0, 0}, 1.0, 24, 12);
  // Duplicate the equator's vertices per side: the upper half's normals tilt up, the lower's down.
  for (std::size_t v = 0; v < sphere.vertices.size(); ++v)
    if (sphere.vertices[v][1] == 0.0) sphere.normals[v] = {float(sphere.vertices[v][0]), 0.3f, float(sphere.vertices[v][2])};
  const std::size_t n = sphere.vertices.size();
  for (std::size_t v = 0; v < n; ++v)
    if (sphere.vertices[v][1] == 0.0) {
      sphere.vertices.push_back(sphere.vertices[v]);
      sphere.normals.push_back({float(sphere.vertices[v][0]), -0.3f, float(sphere.vertices[v][2])});
    }
  std::vector<std::uint32_t> twin(n, 0);
  for (std::size_t v = 0, next = n; v < n; ++v)
    if (sphere.vertices[v][1] == 0.0) twin[v] = static_cast<std::uint32_t>(next++);
  for (Triangle& t : sphere.triangles) {
    const double y = sphere.vertices[t[0]][1] + sphere.vertices[t[1]][1] + sphere.vertices[t[2]][1];
    if (y < 0.0)
      for (std::uint32_t& v : t)
        if (sphere.vertices[v][1] == 0.0) v = twin[v];
  }
  const SmoothCaster c = caster_of(sphere);
  std::size_t creases = 0;
  for (const auto& t : c.crease) creases += std::size_t{t[0]} + t[1] + t[2];
  EXPECT_EQ(creases / 2, 24u);
  // A light across the equator: the silhouette crosses the crease twice, each time through a
  // pair of points on one edge, one per side's normal.
  const std::vector<SilhouetteLoop> loops = accurate_silhouette(c, directional(1.0, 0.05, 0.3));
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_TRUE(loops[0].closed);
  std::size_t doubled = 0;
  const auto& pts = loops[0].points;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const SilhouettePoint& p = pts[i];
    const SilhouettePoint& q = pts[(i + 1) % pts.size()];
    if (p.edge_from == q.edge_from && p.edge_to == q.edge_to && p.triangle != q.triangle) {
      ++doubled;
      EXPECT_NE(p.normal, q.normal);
    }
  }
  EXPECT_GE(doubled, 2u);
}

TEST(DiscreteSilhouette, Sphere_IsOneClosedLoopOfMeshVertices) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 24, 12));
  const Light light = point_light(0.3, 0.2, 6.0);
  const std::vector<SilhouetteLoop> loops = discrete_silhouette(c, lit_faces(c, light));
  EXPECT_GE(loops.size(), 1u);
  EXPECT_EQ(closed_loops(loops), loops.size());
  for (const SilhouetteLoop& loop : loops)
    for (const SilhouettePoint& p : loop.points) EXPECT_EQ(p.position, c.vertices[p.edge_from]);
  EXPECT_THROW((void)discrete_silhouette(c, std::vector<std::uint8_t>(3)), std::invalid_argument);
}

TEST(AccurateSilhouette, VertexRelabelling_GivesTheSameLoopPoints) {
  const Soup sphere = uv_sphere({0, 0, 0}, 1.0, 20, 10);
  Soup relabelled = sphere;
  const std::size_t n = sphere.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    relabelled.vertices[n - 1 - i] = sphere.vertices[i];
    relabelled.normals[n - 1 - i] = sphere.normals[i];
  }
  for (Triangle& t : relabelled.triangles)
    for (std::uint32_t& v : t) v = static_cast<std::uint32_t>(n - 1 - v);
  const Light light = point_light(0.4, 1.5, 4.0);
  const auto a = accurate_silhouette(caster_of(sphere), light);
  const auto b = accurate_silhouette(caster_of(relabelled), light);
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  ASSERT_EQ(a[0].points.size(), b[0].points.size());
  std::vector<Vec3> pa, pb;
  for (const auto& p : a[0].points) pa.push_back(p.position);
  for (const auto& p : b[0].points) pb.push_back(p.position);
  std::sort(pa.begin(), pa.end());
  std::sort(pb.begin(), pb.end());
  for (std::size_t i = 0; i < pa.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(pa[i][k], pb[i][k], 1e-12);
}

}  // namespace
