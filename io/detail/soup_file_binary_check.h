#pragma once
// Checks of binary mesh files before CGAL reads them (private to io/soup_file.cpp).
// A binary file has no lines: messages name the element ("triangle 12: ...") instead.
#include <string>
#include <string_view>

#include "io/detail/soup_file_ply_header.h"

namespace shadowcert::soup_file_detail {

enum class StlEncoding { ascii, binary };

// CGAL takes any STL that starts with "solid" for ASCII and tries binary only when that
// fails, but many binary STL headers start with "solid" too. So decide by size first: a
// file of exactly 84 + 50 n bytes, n being the triangle count at byte 80, is binary; else
// one that starts with "solid" is ASCII; anything else is a binary STL of the wrong size
// (InputError stating the expected and the actual size).
[[nodiscard]] StlEncoding classify_stl(std::string_view data, const std::string& file);

// Throws InputError naming the first triangle with a NaN or infinite vertex coordinate
// (CGAL would put it in a std::map, whose ordering NaN breaks). Needs classify_stl first.
void check_binary_stl_coordinates(std::string_view data, const std::string& file);

// Walks the element layout of a binary PLY body without decoding values, so that a
// truncated file, a negative list length or trailing bytes get a message naming the
// element, and CGAL never sizes a list from a length that the file cannot hold.
void check_binary_ply_layout(std::string_view data, const PlyHeader& header, const std::string& file);

}  // namespace shadowcert::soup_file_detail
