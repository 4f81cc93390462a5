#pragma once
// A triangle soup: the one input every shadowcert module works on (DESIGN.md §1).
//
// Nothing is assumed about it: edges may carry any number of triangles, triangles may
// repeat (in either orientation), indices may repeat inside a triangle, vertices may be
// unreferenced or bitwise duplicates. Readers guarantee only what §1 makes an input
// error: every coordinate finite and every index < vertices.size().
#include <array>
#include <cstdint>
#include <vector>

namespace shadowcert {

using Vec3 = std::array<double, 3>;          // x, y, z
using Triangle = std::array<std::uint32_t, 3>;  // indices into Soup::vertices
using Normal = std::array<float, 3>;

struct Soup {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
  // Per-vertex shading normals: either empty or exactly vertices.size() entries.
  // Only shading uses them; no geometric decision ever reads a normal.
  std::vector<Normal> normals;
};

}  // namespace shadowcert
