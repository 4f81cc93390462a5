// io/scene_input.h: what the subcommands take as input. A scene file as it is; a mesh file
// alone (inspect, certify) or framed over a floor (the image commands), wherever the mesh lies
// and whatever its size.
#include "io/scene_input.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/input_error.h"
#include "core/vector3.h"

namespace shadowcert {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("shadowcert_scene_input_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// A tetrahedron of side `size` at `offset`, as an OFF file.
fs::path write_tetrahedron(const std::string& name, double offset, double size) {
  const fs::path path = temp_dir() / name;
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n4 4 0\n";
  out << offset << ' ' << offset << ' ' << offset << '\n';
  out << offset + size << ' ' << offset << ' ' << offset << '\n';
  out << offset << ' ' << offset + size << ' ' << offset << '\n';
  out << offset << ' ' << offset << ' ' << offset + size << '\n';
  out << "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  return path;
}

// The direction from the eye to `p` is within the camera's half field of view of its axis.
bool in_view(const Camera& camera, const Vec3& p) {
  const Vec3 axis = difference(camera.target, camera.eye);
  const Vec3 to_p = difference(p, camera.eye);
  const double cosine = dot(axis, to_p) / std::sqrt(dot(axis, axis) * dot(to_p, to_p));
  return cosine > std::cos(camera.fov_y_degrees * 3.141592653589793 / 360.0);
}

TEST(SceneInput, MeshAlone_DefaultLightAndCameraNoFloor) {
  const Scene scene = load_scene_or_mesh(write_tetrahedron("alone.off", 0.0, 1.0));
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].soup.triangles.size(), 4u);
  EXPECT_EQ(scene.lights.size(), 1u);
}

// Far from the origin and a thousand times the unit: the default camera sees none of it, the
// framed scene looks at its centre from outside it, with a floor under it and the light above.
TEST(SceneInput, FarLargeMesh_FramedOverAFloorInView) {
  for (const auto& [offset, size] : {std::pair{0.0, 1.0}, std::pair{5000.0, 1000.0}, std::pair{-1e-3, 1e-4}}) {
    SCOPED_TRACE(testing::Message() << "offset " << offset << ", size " << size);
    const fs::path path = write_tetrahedron("framed.off", offset, size);
    const Scene scene = load_image_scene(path);
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.meshes[0].name, path.string());
    EXPECT_TRUE(scene.meshes[0].casts);
    EXPECT_EQ(scene.meshes[1].name, "floor");
    EXPECT_FALSE(scene.meshes[1].casts);
    EXPECT_EQ(scene.camera.width, 1024u);
    EXPECT_EQ(scene.camera.height, 768u);
    const Vec3 centre{offset + size / 2, offset + size / 2, offset + size / 2};
    for (const Vec3& v : scene.meshes[0].soup.vertices) EXPECT_TRUE(in_view(scene.camera, v));
    EXPECT_TRUE(in_view(scene.camera, centre));
    // The floor lies under every vertex; the light above the mesh.
    for (const Vec3& f : scene.meshes[1].soup.vertices) EXPECT_LT(f[1], offset);
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_GT(scene.lights[0].position[1], offset + size);
  }
}

TEST(SceneInput, SceneFile_AsItIsForEveryCommand) {
  const fs::path path = temp_dir() / "scene.json";
  std::ofstream(path) << R"({"meshes": [{"generator": "floor", "params": {"half_size": 2}}], "lights": [[1, 5, 2, 1]]})";
  const Scene alone = load_scene_or_mesh(path);
  const Scene image = load_image_scene(path);
  ASSERT_EQ(image.meshes.size(), 1u);
  EXPECT_EQ(image.meshes[0].soup.triangles, alone.meshes[0].soup.triangles);
  EXPECT_EQ(image.lights[0].position, (std::array<double, 4>{1, 5, 2, 1}));
}

TEST(SceneInput, MeshWithoutTriangle_InputErrorNamingTheFile) {
  const fs::path path = temp_dir() / "empty.off";
  std::ofstream(path) << "OFF\n0 0 0\n";
  try {
    (void)load_image_scene(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shadowcert
