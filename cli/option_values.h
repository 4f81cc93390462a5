#pragma once
// The `--size WxH` option of the commands that render: the camera's image size, each side in
// [1, 16384] (GL_MAX_RENDERBUFFER_SIZE of every driver we target).
#include <CLI/CLI.hpp>

#include <string>

#include "core/camera.h"

namespace shadowcert::cli {

// Sets camera.width and camera.height from "WxH" (e.g. "1024x768"); an empty string leaves
// the scene camera's size. Throws CLI::ValidationError naming `option` otherwise.
void apply_image_size(const std::string& size, Camera& camera, const std::string& option = "--size");

}  // namespace shadowcert::cli
