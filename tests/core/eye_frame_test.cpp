// core/eye_frame.h: the scene moved into its eye's frame keeps what each mesh says of itself
// (casts, silhouette, epsilon) and moves its analytic surface with its triangles.
#include "core/eye_frame.h"

#include <gtest/gtest.h>

namespace {

using namespace shadowcert;

TEST(EyeRelativeScene, MeshKeysKeptAndEllipsoidMovedWithTheSoup) {
  Scene scene;
  scene.camera.eye = {1.0, 2.0, 3.0};
  SceneMesh floor;
  floor.name = "floor";
  floor.soup = Soup{{{-1, 0, -1}, {1, 0, -1}, {0, 0, 1}}, {{0, 1, 2}}, {}};
  floor.casts = false;
  SceneMesh sphere;
  sphere.name = "sphere";
  sphere.soup = Soup{{{0, 2, 0}, {1, 1, 0}, {0, 1, 1}}, {{0, 1, 2}}, {}};
  sphere.silhouette = MeshSilhouette::chain;
  sphere.epsilon = 0.02;
  sphere.ellipsoid = Ellipsoid{{0, 1, 0}, {{{1, 0, 0}, {0, 1, 0}, {0, 0, 2}}}};
  scene.meshes = {floor, sphere};

  const Scene moved = eye_relative_scene(scene);
  ASSERT_EQ(moved.meshes.size(), 2u);
  EXPECT_FALSE(moved.meshes[0].casts);
  EXPECT_FALSE(moved.meshes[0].ellipsoid.has_value());
  EXPECT_TRUE(moved.meshes[1].casts);
  EXPECT_EQ(moved.meshes[1].silhouette, MeshSilhouette::chain);
  EXPECT_EQ(moved.meshes[1].epsilon, 0.02);
  // The surface moves as its vertices do (the pole (0, 2, 0) is centre + axis 1); its axes
  // are directions and stay.
  ASSERT_TRUE(moved.meshes[1].ellipsoid.has_value());
  EXPECT_EQ(moved.meshes[1].ellipsoid->centre, (Vec3{-1, -1, -3}));
  EXPECT_EQ(moved.meshes[1].ellipsoid->axes, sphere.ellipsoid->axes);
  EXPECT_EQ(moved.meshes[1].soup.vertices[0], (Vec3{-1, 0, -3}));
}

}  // namespace
