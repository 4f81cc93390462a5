#pragma once
// A triangle soup: the one input every shadowcert module works on (docs/definitions.md#inputs).
//
// Nothing is assumed about it: edges may carry any number of triangles, triangles may
// repeat (in either orientation), indices may repeat inside a triangle, vertices may be
// unreferenced or bitwise duplicates. Readers guarantee only what docs/definitions.md#inputs
// makes an input error: every coordinate finite and every index < vertices.size().
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
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

// The preconditions a function taking a Soup states, checked in one wording everywhere. Misuse,
// not bad input (readers report that with file and line): each throws
// std::invalid_argument("<function>: ...") naming the caller.
inline void require_indices_in_range(const Soup& soup, std::string_view function) {
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    for (const std::uint32_t i : soup.triangles[t])
      if (i >= soup.vertices.size())
        throw std::invalid_argument(std::string(function) + ": triangle " + std::to_string(t) + " has vertex index " +
                                    std::to_string(i) + ", but the soup has " + std::to_string(soup.vertices.size()) +
                                    " vertices");
}
inline void require_finite_vertices(const Soup& soup, std::string_view function) {
  for (std::size_t v = 0; v < soup.vertices.size(); ++v)
    for (const double x : soup.vertices[v])
      if (!std::isfinite(x))
        throw std::invalid_argument(std::string(function) + ": vertex " + std::to_string(v) +
                                    " has a non-finite coordinate");
}

}  // namespace shadowcert
