#include "io/detail/soup_file_ply_header.h"

#include <array>
#include <charconv>
#include <optional>
#include <utility>

#include "io/detail/soup_file_lines.h"

namespace shadowcert::soup_file_detail {

namespace {

// Both spellings of every type that CGAL's PLY reader knows; any other makes it skip the
// property silently.
std::optional<PlyType> ply_type_named(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, PlyType>, 16> kNames{{
      {"char", PlyType::int8},     {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},   {"short", PlyType::int16},     {"int16", PlyType::int16},
      {"ushort", PlyType::uint16}, {"uint16", PlyType::uint16},   {"int", PlyType::int32},
      {"int32", PlyType::int32},   {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
      {"float", PlyType::float32}, {"float32", PlyType::float32}, {"double", PlyType::float64},
      {"float64", PlyType::float64},
  }};
  for (const auto& [spelling, type] : kNames)
    if (spelling == name) return type;
  return std::nullopt;
}

class HeaderParser {
 public:
  HeaderParser(std::string_view data, const std::string& file) : lines_(data), file_(file) {}

  PlyHeader parse() {
    read_magic();
    read_format();
    while (next_line()) {
      if (keyword() == "end_header") return finish();
      read_declaration();
    }
    fail(file_, lines_.number(), "the PLY header has no 'end_header' line");
  }

 private:
  bool next_line() {
    if (!lines_.next()) return false;
    split_tokens(lines_.line(), tokens_);
    return true;
  }
  std::string_view keyword() const { return tokens_.empty() ? std::string_view() : tokens_[0]; }
  [[noreturn]] void fail_here(const std::string& message) const { fail(file_, lines_.number(), message); }

  void read_magic() {
    if (!next_line() || tokens_.size() != 1 || keyword() != "ply")
      fail(file_, 1, "not a PLY file: the first line must be 'ply'");
  }

  void read_format() {
    if (!next_line() || tokens_.size() != 3 || keyword() != "format")
      fail_here("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
    if (tokens_[1] == "ascii") header_.format = PlyFormat::ascii;
    else if (tokens_[1] == "binary_little_endian") header_.format = PlyFormat::binary_little_endian;
    else if (tokens_[1] == "binary_big_endian") header_.format = PlyFormat::binary_big_endian;
    else fail_here("unknown PLY format " + quoted(tokens_[1]));
  }

  void read_declaration() {
    if (keyword() == "comment" || keyword() == "obj_info") return;
    if (keyword() == "element") return read_element();
    if (keyword() == "property") return read_property();
    if (tokens_.empty()) fail_here("empty line in the PLY header");
    fail_here("unknown PLY header keyword " + quoted(keyword()));
  }

  void read_element() {
    if (tokens_.size() != 3) fail_here("expected 'element <name> <count>'");
    std::size_t count = 0;
    const std::string_view digits = tokens_[2];
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), count);
    if (error != std::errc() || end != digits.data() + digits.size())
      fail_here("element count " + quoted(digits) + " is not a non-negative integer");
    header_.elements.push_back({std::string(tokens_[1]), count, lines_.number(), {}});
  }

  PlyType type_at(std::size_t token) const {
    const auto type = ply_type_named(tokens_[token]);
    if (!type) fail_here("unknown PLY type " + quoted(tokens_[token]));
    return *type;
  }

  void read_property() {
    if (header_.elements.empty()) fail_here("property declared before any element");
    const bool is_list = tokens_.size() > 1 && tokens_[1] == "list";
    if (tokens_.size() != (is_list ? 5U : 3U))
      fail_here(is_list ? "expected 'property list <count type> <item type> <name>'"
                        : "expected 'property <type> <name>'");
    PlyProperty property{std::string(tokens_.back()), type_at(is_list ? 3 : 1), is_list, PlyType::uint8};
    if (is_list) {
      property.count_type = type_at(2);
      if (!is_ply_integer(property.count_type)) fail_here("a list count type must be an integer type");
    }
    header_.elements.back().properties.push_back(std::move(property));
  }

  PlyHeader finish() {
    header_.line_count = lines_.number();
    header_.body_offset = lines_.end_offset();
    check_elements();
    return std::move(header_);
  }

  void check_elements() const {
    bool has_vertices = false;
    bool has_faces = false;
    for (const PlyElement& element : header_.elements) {
      // A property-less element costs nothing per item, so a huge count would make CGAL
      // loop for ages over nothing.
      if (element.properties.empty() && element.count > 0)
        fail(file_, element.line, "element '" + element.name + "' has no property");
      if (is_ply_vertex_element(element)) {
        check_vertex_element(element);
        has_vertices = true;
      }
      if (is_ply_face_element(element)) {
        check_face_element(element);
        has_faces = true;
      }
    }
    if (!has_vertices) fail(file_, header_.line_count, "the PLY header declares no 'vertex' element");
    if (!has_faces) fail(file_, header_.line_count, "the PLY header declares no 'face' element");
  }

  void check_vertex_element(const PlyElement& element) const {
    for (const char* axis : {"x", "y", "z"}) {
      const PlyProperty* property = find(element, axis);
      if (property == nullptr || property->is_list || is_ply_integer(property->type))
        fail(file_, element.line,
             std::string("the vertex element needs a float or double property '") + axis + "'");
    }
  }

  // CGAL looks for these names and index types only, in this order.
  void check_face_element(const PlyElement& element) const {
    for (const char* name : {"vertex_indices", "vertex_index"}) {
      const PlyProperty* property = find(element, name);
      if (property != nullptr && property->is_list &&
          (property->type == PlyType::int32 || property->type == PlyType::uint32))
        return;
    }
    fail(file_, element.line, "the face element needs a 'vertex_indices' list of int or uint");
  }

  static const PlyProperty* find(const PlyElement& element, std::string_view name) {
    for (const PlyProperty& property : element.properties)
      if (property.name == name) return &property;
    return nullptr;
  }

  LineReader lines_;
  const std::string& file_;
  std::vector<std::string_view> tokens_;
  PlyHeader header_;
};

}  // namespace

PlyHeader read_ply_header(std::string_view data, const std::string& file) {
  return HeaderParser(data, file).parse();
}

std::size_t ply_type_size(PlyType type) {
  switch (type) {
    case PlyType::int8:
    case PlyType::uint8: return 1;
    case PlyType::int16:
    case PlyType::uint16: return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32: return 4;
    case PlyType::float64: return 8;
  }
  return 0;
}

bool is_ply_integer(PlyType type) { return type != PlyType::float32 && type != PlyType::float64; }

bool is_ply_vertex_element(const PlyElement& element) {
  return element.name == "vertex" || element.name == "vertices";
}

bool is_ply_face_element(const PlyElement& element) {
  return element.name == "face" || element.name == "faces";
}

bool has_ply_vertex_normals(const PlyHeader& header) {
  for (const PlyElement& element : header.elements) {
    if (!is_ply_vertex_element(element)) continue;
    int found = 0;
    for (const PlyProperty& property : element.properties)
      if ((property.name == "nx" || property.name == "ny" || property.name == "nz") && !property.is_list &&
          !is_ply_integer(property.type))
        ++found;
    return found == 3;
  }
  return false;
}

}  // namespace shadowcert::soup_file_detail
