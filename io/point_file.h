#pragma once
// User sample points (`shadowcert certify --points FILE`): one point "x y z" per line, blank
// lines and lines starting with '#' ignored. Errors are InputErrors naming the file and line.
// Plain text, no CGAL: it lives in io/ so that the CLI and the fuzz harness (fuzz/) share it.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/soup.h"

namespace shadowcert {

// Throws InputError when `file` is a directory, cannot be opened, or holds a bad line.
[[nodiscard]] std::vector<Vec3> read_point_file(const std::filesystem::path& file);

// The same on the file's text already in memory; messages name `file_name`.
[[nodiscard]] std::vector<Vec3> parse_point_file(std::string_view text, const std::string& file_name);

}  // namespace shadowcert
