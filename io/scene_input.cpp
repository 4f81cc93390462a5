#include "io/scene_input.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "core/input_error.h"
#include "core/near_plane.h"
#include "io/soup_file.h"
#include "scene/framed_scene.h"
#include "scene/scene_file.h"

namespace shadowcert {

Scene load_scene_or_mesh(const std::filesystem::path& input) {
  std::string ext = input.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".json") return load_scene(input, [](const std::filesystem::path& p) { return read_soup(p); });

  Scene scene;
  SceneMesh& mesh = scene.meshes.emplace_back();
  mesh.name = input.string();
  mesh.soup = read_soup(input);
  scene.lights.emplace_back();
  scene.camera = camera_fitted_to(scene);
  return scene;
}

namespace {

bool is_scene_file(const std::filesystem::path& input) {
  std::string ext = input.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".json";
}

}  // namespace

Scene load_image_scene(const std::filesystem::path& input) {
  if (is_scene_file(input)) return load_scene_or_mesh(input);
  const Soup mesh = read_soup(input);
  if (mesh.triangles.empty()) throw InputError(input.string(), "the mesh has no triangle to frame");
  FramedMeshOptions options;
  options.width = 1024;
  options.height = 768;
  return framed_mesh_scene(mesh, input.string(), options);
}

}  // namespace shadowcert
