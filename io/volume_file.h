#pragma once
// Volume files (.vol): the homogeneous float triangles a volume method handed to the GPU
// (core/homogeneous_mesh.h), stored so that exact/ can certify the closure
// (docs/definitions.md#closure) of what was actually drawn, not of the chain it was meant to be.
//
// File format (.vol, text, one record per line; blank lines and lines starting with '#' are
// ignored):
//   v X Y Z W     a vertex; floats printed with 9 significant digits (max_digits10) so they
//                 read back bit for bit; W is 1 (a finite point) or 0 (a point at infinity)
//   f A B C ...   a face, 1-based vertex indices (as in OBJ), at least 3, oriented outwards;
//                 a polygon is read as the fan (A, B, C), (A, C, D), ... (its boundary edges
//                 are unchanged: the fan's diagonals cancel)
// Writing welds bitwise-equal vertices first (scene/welded_volume.h) so files stay small.
#include <filesystem>
#include <string>
#include <string_view>

#include "core/homogeneous_mesh.h"

namespace shadowcert {

// Writes the welded volume; `comment` (may span lines) is written as '#' lines at the top.
// Throws InputError naming the file when it cannot be written.
void write_volume_file(const std::filesystem::path& file, const HomogeneousMesh& volume,
                       std::string_view comment = {});

// Reads and validates a .vol file (finite coordinates, w in {0, 1}, indices in range,
// at least 3 per face); throws InputError naming file:line otherwise. Not welded.
[[nodiscard]] HomogeneousMesh read_volume_file(const std::filesystem::path& file);
// The same on the file's text already in memory (the fuzz harness, fuzz/); messages name
// `file_name`.
[[nodiscard]] HomogeneousMesh parse_volume_file(std::string_view text, const std::string& file_name);

}  // namespace shadowcert
