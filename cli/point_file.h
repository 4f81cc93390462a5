#pragma once
// User sample points for `certify --points FILE`: one point "x y z" per line, blank lines and
// lines starting with '#' ignored. Errors are InputErrors naming the file and line.
#include <filesystem>
#include <vector>

#include "core/soup.h"

namespace shadowcert::cli {

[[nodiscard]] std::vector<Vec3> read_point_file(const std::filesystem::path& file);

}  // namespace shadowcert::cli
