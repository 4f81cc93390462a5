#pragma once
// Reading and writing soups in mesh files. Readers are CGAL's polygon-soup I/O, wrapped so
// that every failure is an InputError naming the file (and the line for text formats).
//
// Read: .obj .off .ply (ASCII, binary LE/BE) .stl (ASCII, binary); extension case-insensitive.
// Polygons with n > 3 vertices are fan-triangulated from their first vertex:
// (v0, v1, v2), (v0, v2, v3), ... (the orientation of the polygon is kept).
// Rejected (InputError): missing file, directory, unknown extension, empty or truncated
// file, unparsable content, NaN/inf coordinates, out-of-range or negative indices,
// faces with fewer than three vertices, no triangle at all.
// Write: .off .obj .ply (ASCII, with max_digits10 so that values round-trip bitwise).
#include <filesystem>
#include <string>
#include <string_view>

#include "core/soup.h"

namespace shadowcert {

[[nodiscard]] Soup read_soup(const std::filesystem::path& file);

// The same on a file's bytes already in memory (the fuzz harnesses, fuzz/): `file_name`'s
// extension picks the format, as read_soup's path does, and messages name `file_name`.
// Everything read_soup rejects after opening the file is rejected alike, with the same message.
[[nodiscard]] Soup parse_soup(std::string_view data, const std::string& file_name);

void write_soup(const std::filesystem::path& file, const Soup& soup);

}  // namespace shadowcert
