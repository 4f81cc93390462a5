// scene/framed_scene.h: the framing rule of a mesh over a floor, and the analytic suite's shapes
// and scenes (docs/bench.md#the-suites).
#include "scene/framed_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "scene/procedural_mesh.h"

namespace shadowcert {
namespace {

TEST(FramedMeshScene, UnitBox_FloorLightAndEyeFollowTheRule) {
  const Soup cube = box({-1, -1, -1}, {1, 1, 1});
  const Scene s = framed_mesh_scene(cube, "cube", {320, 240, false});
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "cube");
  EXPECT_TRUE(s.meshes[0].casts);
  EXPECT_EQ(s.meshes[1].name, "floor");
  EXPECT_FALSE(s.meshes[1].casts);
  const double r = std::sqrt(3.0);  // the box's half diagonal
  for (const Vec3& v : s.meshes[1].soup.vertices) {
    EXPECT_DOUBLE_EQ(v[1], -1.0 - 0.01 * r);
    EXPECT_DOUBLE_EQ(std::abs(v[0]), 3 * r);
    EXPECT_DOUBLE_EQ(std::abs(v[2]), 3 * r);
  }
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_DOUBLE_EQ(s.lights[0].position[0], 1.5 * r);
  EXPECT_DOUBLE_EQ(s.lights[0].position[1], 3.0 * r);
  EXPECT_DOUBLE_EQ(s.lights[0].position[3], 1.0);
  EXPECT_DOUBLE_EQ(s.camera.eye[2], 3.2 * r);
  EXPECT_EQ(s.camera.width, 320u);
  EXPECT_EQ(s.camera.height, 240u);
  EXPECT_GT(s.camera.near_plane, 0.0);
  EXPECT_TRUE(framed_mesh_scene(cube, "cube", {32, 24, true}).meshes[1].casts);
}

TEST(FramedMeshScene, NoTriangleOrZeroSize_Throws) {
  EXPECT_THROW((void)framed_mesh_scene(Soup{}, "empty"), std::invalid_argument);
  EXPECT_THROW((void)framed_mesh_scene(box({0, 0, 0}, {1, 1, 1}), "box", {0, 10, false}), std::invalid_argument);
}

TEST(AnalyticShapes, SevenSpheresAndTheEllipsoid) {
  const std::vector<AnalyticShape> shapes = analytic_shapes();
  ASSERT_EQ(shapes.size(), 8u);
  EXPECT_EQ(shapes.front().name, "sphere8x4");
  EXPECT_EQ(shapes.front().soup.triangles.size(), 2u * 8 * 3);
  EXPECT_EQ(shapes[6].name, "sphere256x128");
  EXPECT_EQ(shapes.back().name, "ellipsoid32x16");
  EXPECT_TRUE(shapes.back().soup.normals.empty());  // computed from the transformed mesh
  EXPECT_DOUBLE_EQ(shapes.back().ellipsoid.axes[0][0], 1.4);
  // Every vertex of the ellipsoid's mesh is on its surface: |A^-1 (x - c)| = 1 (A's columns are
  // independent; checked through the sphere it came from).
  const Soup sphere = uv_sphere({0, 0, 0}, 1.0, 32, 16);
  for (std::size_t i = 0; i < sphere.vertices.size(); ++i) {
    const Vec3& u = sphere.vertices[i];
    const Vec3& x = shapes.back().soup.vertices[i];
    for (std::size_t k = 0; k < 3; ++k) {
      const auto& a = shapes.back().ellipsoid.axes;
      EXPECT_NEAR(x[k], a[0][k] * u[0] + a[1][k] * u[1] + a[2][k] * u[2], 1e-12);
    }
  }
}

TEST(AnalyticShapeScene, FloorThenCasterWithItsEllipsoid) {
  const AnalyticShape shape = analytic_shapes().front();
  const Scene s = analytic_shape_scene(shape, kAnalyticSun, 64, 48);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "floor");
  EXPECT_FALSE(s.meshes[0].casts);
  for (const Vec3& v : s.meshes[0].soup.vertices) EXPECT_DOUBLE_EQ(v[1], kAnalyticFloorHeight);
  EXPECT_EQ(s.meshes[1].name, "sphere8x4");
  ASSERT_TRUE(s.meshes[1].ellipsoid.has_value());
  EXPECT_EQ(s.lights[0].position, kAnalyticSun.position);
  EXPECT_EQ(s.camera.width, 64u);
  EXPECT_DOUBLE_EQ(s.camera.eye[0], -2.5);
}

}  // namespace
}  // namespace shadowcert
