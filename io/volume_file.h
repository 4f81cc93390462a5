#pragma once
// A captured shadow volume (issue 4): the homogeneous float triangles a volume method handed
// to the GPU, stored so that exact/ can certify the closure (DESIGN.md §4.1) of what was
// actually drawn, not of the chain it was meant to be.
//
// File format (.vol, text, one record per line; blank lines and lines starting with '#' are
// ignored):
//   v X Y Z W     a vertex; floats printed with 9 significant digits (max_digits10) so they
//                 read back bit for bit; W is 1 (a finite point) or 0 (a point at infinity)
//   f A B C ...   a face, 1-based vertex indices (as in OBJ), at least 3, oriented outwards;
//                 a polygon is read as the fan (A, B, C), (A, C, D), ... (its boundary edges
//                 are unchanged: the fan's diagonals cancel)
// Writing welds bitwise-equal vertices first (-0 and +0 are one vertex) so files stay small.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/homogeneous_mesh.h"
#include "exact/closure_certificate.h"

namespace shadowcert {

// Homogeneous vertices (w in {0, 1}) and 0-based triangles in memory.
using CapturedVolume = HomogeneousMesh;

// Merges vertices whose four floats are bitwise equal after mapping -0 to +0 (the GPU may
// emit either for one point), keeping first-seen order and bits, and renumbers the triangles.
// Throws std::invalid_argument on an index out of range.
[[nodiscard]] CapturedVolume weld_captured_volume(const CapturedVolume& volume);

// Writes the welded volume; `comment` (may span lines) is written as '#' lines at the top.
// Throws InputError naming the file when it cannot be written.
void write_captured_volume(const std::filesystem::path& file, const CapturedVolume& volume,
                           std::string_view comment = {});

// Reads and validates a .vol file (finite coordinates, w in {0, 1}, indices in range,
// at least 3 per face); throws InputError naming file:line otherwise. Not welded.
[[nodiscard]] CapturedVolume read_captured_volume(const std::filesystem::path& file);
// The same on the file's text already in memory (the fuzz harness, fuzz/); messages name
// `file_name`.
[[nodiscard]] CapturedVolume parse_captured_volume(std::string_view text, const std::string& file_name);

// Closure of the volume as drawn: welds (as weld_captured_volume) and balances directed
// edges exactly as certify_closure. UnbalancedEdge ids index `welded`.
struct CapturedClosure {
  CapturedVolume welded;
  ClosureCertificate certificate;
};
[[nodiscard]] CapturedClosure certify_captured_closure(const CapturedVolume& volume);

}  // namespace shadowcert
