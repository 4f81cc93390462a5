// scene/merged_soup.h: concatenation keeps every triangle on its own three points, in order;
// normals survive only when every part has them; empty parts are neutral.
#include "scene/merged_soup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include "scene/procedural_mesh.h"

namespace shadowcert {
namespace {

Scene scene_of(std::vector<Soup> soups) {
  Scene scene;
  for (std::size_t i = 0; i < soups.size(); ++i) {
    SceneMesh& mesh = scene.meshes.emplace_back();
    mesh.name = "mesh " + std::to_string(i);
    mesh.soup = soups[i];
  }
  return scene;
}

// Triangle `t` of `soup` as its three positions.
std::array<Vec3, 3> corners(const Soup& soup, const Triangle& t) {
  return {soup.vertices.at(t[0]), soup.vertices.at(t[1]), soup.vertices.at(t[2])};
}

TEST(MergedSoup, EveryMesh_ItsVerticesInOrderAndItsTrianglesOnTheSamePoints) {
  constexpr std::uint64_t kSeed = 20240611;
  std::cout << "random_soup seed " << kSeed << "\n";
  Soup repeated;  // a repeated index and an unreferenced vertex are kept as they are
  repeated.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {9, 9, 9}};
  repeated.triangles = {{0, 1, 1}, {2, 1, 0}};
  const Scene scene = scene_of({floor_quad(2.0), random_soup(kSeed, 40, 3.0), repeated, nonmanifold_fan(5)});
  const Soup merged = merged_soup(scene);

  std::size_t vertex = 0, triangle = 0;
  for (const SceneMesh& mesh : scene.meshes) {
    SCOPED_TRACE(mesh.name);
    for (const Vec3& v : mesh.soup.vertices) EXPECT_EQ(merged.vertices.at(vertex++), v);
    for (const Triangle& t : mesh.soup.triangles) {
      const Triangle& m = merged.triangles.at(triangle++);
      EXPECT_EQ(corners(merged, m), corners(mesh.soup, t));
      EXPECT_EQ(m[1] - m[0], t[1] - t[0]);  // repeated indices stay repeated
      EXPECT_EQ(m[2] - m[0], t[2] - t[0]);
    }
  }
  EXPECT_EQ(merged.vertices.size(), vertex);
  EXPECT_EQ(merged.triangles.size(), triangle);
}

TEST(MergedSoup, NormalsOnlyWhenEveryMeshHasThem) {
  const Soup floor = floor_quad(1.0);                        // normals
  const Soup sphere = uv_sphere({0.0, 1.0, 0.0}, 0.5, 6, 3);  // normals
  const Soup cube = box({0, 0, 0}, {1, 1, 1});                // none
  ASSERT_FALSE(floor.normals.empty());
  ASSERT_FALSE(sphere.normals.empty());
  ASSERT_TRUE(cube.normals.empty());

  const Soup both = merged_soup(scene_of({floor, sphere}));
  ASSERT_EQ(both.normals.size(), both.vertices.size());
  std::vector<Normal> expected = floor.normals;
  expected.insert(expected.end(), sphere.normals.begin(), sphere.normals.end());
  EXPECT_EQ(both.normals, expected);

  EXPECT_TRUE(merged_soup(scene_of({floor, cube})).normals.empty());
  EXPECT_TRUE(merged_soup(scene_of({cube, floor})).normals.empty());
  EXPECT_TRUE(merged_soup(scene_of({floor, cube, sphere})).normals.empty());
}

TEST(MergedSoup, EmptyMeshesAndScene_AreNeutral) {
  EXPECT_TRUE(merged_soup(Scene{}).vertices.empty());
  EXPECT_TRUE(merged_soup(Scene{}).triangles.empty());
  const Soup floor = floor_quad(1.0);
  const Soup merged = merged_soup(scene_of({Soup{}, floor, Soup{}}));
  EXPECT_EQ(merged.vertices, floor.vertices);
  EXPECT_EQ(merged.triangles, floor.triangles);
  EXPECT_EQ(merged.normals, floor.normals);  // a soup without vertices has all its normals
}

void expect_same_soup(const Soup& got, const Soup& expected) {
  EXPECT_EQ(got.vertices, expected.vertices);
  EXPECT_EQ(got.triangles, expected.triangles);
  EXPECT_EQ(got.normals, expected.normals);
}

TEST(MergedCasters, NonCastingMeshes_LeftOutAndFlaggedInMergedSoupsOrder) {
  Scene scene = scene_of({floor_quad(2.0), nonmanifold_fan(5), box({0, 0, 0}, {1, 1, 1}), floor_quad(1.0)});
  scene.meshes[0].casts = false;
  scene.meshes[3].casts = false;
  // The casters are exactly the casting meshes merged alone, in their order.
  expect_same_soup(merged_casters(scene), merged_soup(scene_of({scene.meshes[1].soup, scene.meshes[2].soup})));
  // One flag per triangle of merged_soup, 0 on the floors' triangles only.
  std::vector<std::uint8_t> expected(2, 0);
  expected.insert(expected.end(), 5 + 12, 1);
  expected.insert(expected.end(), 2, 0);
  const std::vector<std::uint8_t> casts = casting_triangles(scene);
  EXPECT_EQ(casts, expected);
  EXPECT_EQ(casts.size(), merged_soup(scene).triangles.size());
}

TEST(MergedCasters, EveryMeshCasting_IsTheMergedSoup) {
  const Scene scene = scene_of({floor_quad(2.0), uv_sphere({0.0, 1.0, 0.0}, 0.5, 6, 3)});
  expect_same_soup(merged_casters(scene), merged_soup(scene));
  EXPECT_EQ(casting_triangles(scene), std::vector<std::uint8_t>(merged_soup(scene).triangles.size(), 1));
}

TEST(AppendSoup, ToASoupWithTriangles_OffsetsByItsVertexCount) {
  Soup to = box({0, 0, 0}, {1, 1, 1});
  const std::size_t before = to.vertices.size();
  const std::vector<Triangle> old = to.triangles;
  const Soup fan = nonmanifold_fan(3);
  append_soup(to, fan);
  ASSERT_EQ(to.triangles.size(), old.size() + fan.triangles.size());
  EXPECT_TRUE(std::equal(old.begin(), old.end(), to.triangles.begin()));
  for (std::size_t i = 0; i < fan.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(to.triangles[old.size() + i][k], fan.triangles[i][k] + before);
}

}  // namespace
}  // namespace shadowcert
