#pragma once
// The JSON scene format (docs/scene-format.md). Every field has a default; unknown keys and
// wrong types are InputErrors naming the file and the key path (e.g. "meshes[1].transform").
#include <filesystem>
#include <functional>
#include <string_view>

#include "core/scene.h"

namespace shadowcert {

// Reads a mesh file into a soup (the CLI passes exact's read_soup); throws InputError.
using MeshFileReader = std::function<Soup(const std::filesystem::path&)>;

// Parses a scene file; mesh paths are relative to the scene file's folder.
[[nodiscard]] Scene load_scene(const std::filesystem::path& file, const MeshFileReader& read_mesh);

// Parses scene JSON text; `file_name` is used in error messages, `base_dir` resolves mesh paths.
[[nodiscard]] Scene parse_scene(std::string_view json_text, const std::string& file_name,
                                const std::filesystem::path& base_dir, const MeshFileReader& read_mesh);

}  // namespace shadowcert
