#pragma once
// Line checks of the text mesh formats, run before CGAL reads a text file (private to
// io/soup_file.cpp).
//
// CGAL's text readers are lax, each in its own way, and a file they accept can still be
// malformed: the OBJ reader ends a face silently at a junk token, skips to the next space
// after each index (a tab drops a corner), takes index 0 as "the next vertex" and checks
// the range off by one; the OFF reader reads indices as doubles (2.5 is 2), ignores junk
// after a vertex and allocates whatever its header or a face's count says; the ASCII PLY
// reader reads a stream of numbers, so an extra value shifts every later one; the ASCII
// STL reader skips any word it does not know. So every text file is checked line by line
// first. A check builds no mesh: it finds the first line that does not fit and throws
// InputError(file, line, why); on success it returns where each record sits, so that a
// problem found later in what CGAL read (a face with two corners, an index out of range)
// can name its line too.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "io/detail/soup_file_ply_header.h"

namespace shadowcert::soup_file_detail {

// The 1-based line of each vertex and face record, in the order CGAL reads them. `vertex`
// stays empty where CGAL's points are not the file's records one to one (STL, which CGAL
// welds).
struct RecordLines {
  std::vector<std::size_t> vertex;
  std::vector<std::size_t> face;
};

// Line of record k, or 0 (no line) when unknown.
[[nodiscard]] std::size_t line_of(const std::vector<std::size_t>& lines, std::size_t k);

[[nodiscard]] RecordLines check_obj_text(std::string_view text, const std::string& file);
[[nodiscard]] RecordLines check_off_text(std::string_view text, const std::string& file);
[[nodiscard]] RecordLines check_ply_ascii_body(std::string_view text, const PlyHeader& header,
                                               const std::string& file);
[[nodiscard]] RecordLines check_stl_ascii_text(std::string_view text, const std::string& file);

}  // namespace shadowcert::soup_file_detail
