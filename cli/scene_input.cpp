#include "cli/scene_input.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <string>

#include "core/input_error.h"
#include "exact/soup_file.h"
#include "scene/scene_file.h"

namespace shadowcert::cli {

Scene load_scene_or_mesh(const std::filesystem::path& input) {
  std::string ext = input.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".json") return load_scene(input, [](const std::filesystem::path& p) { return read_soup(p); });

  Scene scene;
  scene.meshes.push_back({input.string(), read_soup(input)});
  scene.lights.emplace_back();
  return scene;
}

Soup merged_soup(const Scene& scene) {
  Soup out;
  const bool all_normals = std::all_of(scene.meshes.begin(), scene.meshes.end(),
                                       [](const SceneMesh& m) { return !m.soup.normals.empty(); });
  for (const SceneMesh& mesh : scene.meshes) {
    if (out.vertices.size() + mesh.soup.vertices.size() > std::numeric_limits<std::uint32_t>::max())
      throw InputError(mesh.name, "the scene has more than 2^32-1 vertices in all");
    const auto offset = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), mesh.soup.vertices.begin(), mesh.soup.vertices.end());
    if (all_normals) out.normals.insert(out.normals.end(), mesh.soup.normals.begin(), mesh.soup.normals.end());
    for (Triangle t : mesh.soup.triangles) out.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  return out;
}

}  // namespace shadowcert::cli
