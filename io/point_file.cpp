#include "io/point_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>
#include <sstream>
#include <string>
#include <string_view>

#include "core/input_error.h"
#include "io/detail/text_token.h"

namespace shadowcert {
namespace {

using io_detail::next_token;

// The points of a point-file text, from any stream; `name` is the file named in messages.
std::vector<Vec3> read_points(std::istream& in, const std::string& name) {
  std::vector<Vec3> points;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::string_view rest = line;
    std::string_view first = next_token(rest);
    if (first.empty() || first.front() == '#') continue;
    Vec3 p{};
    for (int k = 0; k < 3; ++k) {
      const std::string_view token = k == 0 ? first : next_token(rest);
      if (token.empty()) throw InputError(name, number, "expected three coordinates \"x y z\"");
      const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), p[k]);
      if (ec != std::errc() || end != token.data() + token.size())
        throw InputError(name, number, "not a number: '" + std::string(token) + "'");
      if (!std::isfinite(p[k])) throw InputError(name, number, "coordinate is not finite");
    }
    if (!next_token(rest).empty()) throw InputError(name, number, "more than three values on the line");
    points.push_back(p);
  }
  return points;
}

}  // namespace

std::vector<Vec3> read_point_file(const std::filesystem::path& file) {
  if (std::filesystem::is_directory(file)) throw InputError(file.string(), "is a directory, not a point file");
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open point file");
  return read_points(in, file.string());
}

std::vector<Vec3> parse_point_file(std::string_view text, const std::string& file_name) {
  std::istringstream in{std::string(text)};
  return read_points(in, file_name);
}

}  // namespace shadowcert
