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

#include "core/soup.h"

namespace shadowcert {

[[nodiscard]] Soup read_soup(const std::filesystem::path& file);

void write_soup(const std::filesystem::path& file, const Soup& soup);

}  // namespace shadowcert
