#pragma once
// What every subcommand takes as input: a mesh file (one soup, default light and camera, or
// framed over a floor for the image commands) or a JSON scene. Errors are InputErrors naming
// the file.
#include <filesystem>

#include "core/scene.h"

namespace shadowcert {

// `.json` -> a scene file (scene/scene_file.h); anything else -> a mesh file read by
// exact's read_soup, wrapped in a scene with the defaults of core/scene.h.
[[nodiscard]] Scene load_scene_or_mesh(const std::filesystem::path& input);

// For the commands that make images of a scene (render, diff, soft, edges): `.json` -> the scene
// file as it is; a mesh file -> the mesh framed over a floor by scene/framed_scene.h's rule
// (docs/bench.md#the-suites: a receiving floor 0.01r under its box, a point light and the eye
// placed from its centre c and half diagonal r), at 1024 x 768 like the default camera. The
// default camera and light of load_scene_or_mesh see nothing of a mesh far from the origin or
// much larger or smaller than the unit, and the shadows a mesh casts need a receiver. A mesh
// without a triangle is an InputError naming the file.
[[nodiscard]] Scene load_image_scene(const std::filesystem::path& input);

}  // namespace shadowcert
