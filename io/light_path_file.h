#pragma once
// Light paths (`shadowcert track --path FILE`): one light per line, "x y z w" (w = 1: a point
// light at (x, y, z); w = 0: a directional light towards (x, y, z), core/light.h), blank lines
// and lines starting with '#' ignored. Errors are InputErrors naming the file and line.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/light.h"

namespace shadowcert {

// Throws InputError when `file` is a directory, cannot be opened, holds a bad line, or holds
// no light.
[[nodiscard]] std::vector<Light> read_light_path_file(const std::filesystem::path& file);

// The same on the file's text already in memory; messages name `file_name`.
[[nodiscard]] std::vector<Light> parse_light_path_file(std::string_view text, const std::string& file_name);

}  // namespace shadowcert
