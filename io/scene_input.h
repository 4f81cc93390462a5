#pragma once
// What every subcommand takes as input: a mesh file (one soup, default light and camera)
// or a JSON scene. Errors are InputErrors naming the file.
#include <filesystem>

#include "core/scene.h"

namespace shadowcert {

// `.json` -> a scene file (scene/scene_file.h); anything else -> a mesh file read by
// exact's read_soup, wrapped in a scene with the defaults of core/scene.h.
[[nodiscard]] Scene load_scene_or_mesh(const std::filesystem::path& input);

}  // namespace shadowcert
