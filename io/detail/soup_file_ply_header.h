#pragma once
// The PLY header, read before CGAL sees the file (private to io/soup_file.cpp).
//
// CGAL's PLY reader does not check its header against what it later assumes: it skips a
// property of unknown type (so every following value is read shifted), fills a missing
// x/y/z with 0, and dereferences a null pointer when x is an integer property. So the
// header is checked here first; its element layout then also serves to name the line
// of an ASCII record and to walk a binary body.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace shadowcert::soup_file_detail {

enum class PlyFormat { ascii, binary_little_endian, binary_big_endian };

enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::float32;  // the value type, or the item type of a list
  bool is_list = false;
  PlyType count_type = PlyType::uint8;  // lists only
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::size_t line = 0;  // 1-based line of its "element" declaration
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t line_count = 0;   // lines up to and including "end_header"
  std::size_t body_offset = 0;  // first byte after the "end_header" line
};

// Throws InputError(file, line, ...) for anything CGAL would misread: a first line other
// than "ply", a bad format line, an unknown type or keyword, no end_header, no vertex
// element with float/double x, y, z, no face element with an int/uint vertex index list.
[[nodiscard]] PlyHeader read_ply_header(std::string_view data, const std::string& file);

[[nodiscard]] std::size_t ply_type_size(PlyType type);
[[nodiscard]] bool is_ply_integer(PlyType type);
// CGAL reads the elements named "vertex"/"vertices" as points and "face"/"faces" as polygons.
[[nodiscard]] bool is_ply_vertex_element(const PlyElement& element);
[[nodiscard]] bool is_ply_face_element(const PlyElement& element);
// True when the vertex element has float/double nx, ny, nz (read into Soup::normals).
[[nodiscard]] bool has_ply_vertex_normals(const PlyHeader& header);

}  // namespace shadowcert::soup_file_detail
