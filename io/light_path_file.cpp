#include "io/light_path_file.h"

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

std::vector<Light> read_lights(std::istream& in, const std::string& name) {
  std::vector<Light> lights;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::string_view rest = line;
    const std::string_view first = next_token(rest);
    if (first.empty() || first.front() == '#') continue;
    Light light;
    for (std::size_t k = 0; k < 4; ++k) {
      const std::string_view token = k == 0 ? first : next_token(rest);
      if (token.empty()) throw InputError(name, number, "expected four values \"x y z w\"");
      double& value = light.position[k];
      const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
      if (ec != std::errc() || end != token.data() + token.size())
        throw InputError(name, number, "not a number: '" + std::string(token) + "'");
      if (!std::isfinite(value)) throw InputError(name, number, "value is not finite");
    }
    if (!next_token(rest).empty()) throw InputError(name, number, "more than four values on the line");
    if (!light.well_formed()) throw InputError(name, number, "w must be 1 (point light) or 0 (directional light)");
    if (!light.defined()) throw InputError(name, number, "a directional light needs a nonzero direction");
    lights.push_back(light);
  }
  if (lights.empty()) throw InputError(name, "no light in the path (one \"x y z w\" per line)");
  return lights;
}

}  // namespace

std::vector<Light> read_light_path_file(const std::filesystem::path& file) {
  if (std::filesystem::is_directory(file)) throw InputError(file.string(), "is a directory, not a light path file");
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open light path file");
  return read_lights(in, file.string());
}

std::vector<Light> parse_light_path_file(std::string_view text, const std::string& file_name) {
  std::istringstream in{std::string(text)};
  return read_lights(in, file_name);
}

}  // namespace shadowcert
