#include "io/scene_input.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "core/near_plane.h"
#include "io/soup_file.h"
#include "scene/scene_file.h"

namespace shadowcert {

Scene load_scene_or_mesh(const std::filesystem::path& input) {
  std::string ext = input.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".json") return load_scene(input, [](const std::filesystem::path& p) { return read_soup(p); });

  Scene scene;
  scene.meshes.push_back({input.string(), read_soup(input)});
  scene.lights.emplace_back();
  scene.camera = camera_fitted_to(scene);
  return scene;
}

}  // namespace shadowcert
