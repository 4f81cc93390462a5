#include "io/volume_file.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/input_error.h"
#include "io/detail/text_token.h"
#include "scene/welded_volume.h"

namespace shadowcert {

void write_volume_file(const std::filesystem::path& file, const HomogeneousMesh& volume,
                       std::string_view comment) {
  const HomogeneousMesh welded = weld_volume(volume);
  std::ofstream out(file, std::ios::binary);
  if (!out) throw InputError(file.string(), "cannot open for writing");
  std::string text = "# shadowcert captured shadow volume (docs/cli.md): v x y z w, f a b c (1-based)\n";
  std::string_view rest = comment;
  while (!rest.empty()) {
    const auto end = rest.find('\n');
    text.append("# ").append(rest.substr(0, end)).append("\n");
    rest.remove_prefix(end == std::string_view::npos ? rest.size() : end + 1);
  }
  // 9 significant digits (max_digits10 of float) read back bit for bit.
  // to_chars, not printf: no locale can turn the decimal point into a comma.
  char buffer[32];
  for (const auto& v : welded.vertices) {
    text += 'v';
    for (float x : v) {
      const auto end = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, 9).ptr;
      text.append(" ").append(buffer, end);
    }
    text += '\n';
  }
  for (const auto& t : welded.triangles)
    text.append("f ")
        .append(std::to_string(t[0] + std::uint64_t{1}))
        .append(" ")
        .append(std::to_string(t[1] + std::uint64_t{1}))
        .append(" ")
        .append(std::to_string(t[2] + std::uint64_t{1}))
        .append("\n");
  out << text;
  out.flush();
  if (!out) throw InputError(file.string(), "write failed");
}

namespace {

using io_detail::next_token;

// The records of a .vol text, from any stream; `name` is the file named in messages.
HomogeneousMesh read_records(std::istream& in, const std::string& name) {
  HomogeneousMesh volume;
  struct Face {
    std::vector<std::uint64_t> indices;
    std::size_t line;
  };
  std::vector<Face> faces;  // checked once every vertex is known (vertices may follow faces)
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::string_view rest = line;
    const std::string_view tag = next_token(rest);
    if (tag.empty() || tag.front() == '#') continue;
    if (tag == "v") {
      std::array<float, 4> v{};
      for (int k = 0; k < 4; ++k) {
        const std::string_view token = next_token(rest);
        if (token.empty()) throw InputError(name, number, "a vertex needs four numbers x y z w");
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v[k]);
        if (ec != std::errc() || end != token.data() + token.size())
          throw InputError(name, number, "'" + std::string(token) + "' is not a float");
        if (!std::isfinite(v[k])) throw InputError(name, number, "coordinates must be finite");
      }
      if (!next_token(rest).empty()) throw InputError(name, number, "a vertex has exactly four numbers x y z w");
      if (v[3] != 0.0f && v[3] != 1.0f) throw InputError(name, number, "w must be 1 (finite) or 0 (at infinity)");
      volume.vertices.push_back(v);
    } else if (tag == "f") {
      Face face{{}, number};
      for (std::string_view token = next_token(rest); !token.empty(); token = next_token(rest)) {
        std::uint64_t index = 0;
        const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), index);
        if (ec != std::errc() || end != token.data() + token.size() || index == 0)
          throw InputError(name, number, "'" + std::string(token) + "' is not a 1-based vertex index");
        face.indices.push_back(index - 1);
      }
      if (face.indices.size() < 3) throw InputError(name, number, "a face needs at least 3 vertices");
      faces.push_back(std::move(face));
    } else {
      throw InputError(name, number, "unknown record '" + std::string(tag) + "' (expected v, f or #)");
    }
  }
  if (in.bad()) throw InputError(name, "read failed");
  for (const Face& face : faces) {
    for (std::uint64_t index : face.indices)
      if (index >= volume.vertices.size())
        throw InputError(name, face.line,
                         "vertex index " + std::to_string(index + 1) + " but the file has " +
                             std::to_string(volume.vertices.size()) + " vertices");
    for (std::size_t k = 1; k + 1 < face.indices.size(); ++k)
      volume.triangles.push_back({static_cast<std::uint32_t>(face.indices[0]),
                                  static_cast<std::uint32_t>(face.indices[k]),
                                  static_cast<std::uint32_t>(face.indices[k + 1])});
  }
  return volume;
}

}  // namespace

HomogeneousMesh read_volume_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(name, "cannot open");
  return read_records(in, name);
}

HomogeneousMesh parse_volume_file(std::string_view text, const std::string& file_name) {
  std::istringstream in(std::string(text), std::ios::binary);
  return read_records(in, file_name);
}

}  // namespace shadowcert
