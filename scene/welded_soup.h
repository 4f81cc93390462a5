#pragma once
// Exact welding (docs/definitions.md#inputs): two vertices are the same iff their three doubles are
// bitwise-equal, with -0 == +0. No tolerance: nearby-but-different points stay apart.
#include <cstdint>
#include <vector>

#include "core/soup.h"

namespace shadowcert {

struct WeldedSoup {
  // Distinct positions in order of first occurrence (unreferenced ones kept), triangles
  // remapped to them (repeated indices kept), normals of the first occurrence.
  Soup soup;
  // welded_id[i] is the welded index of input vertex i; size == input vertices.size().
  std::vector<std::uint32_t> welded_id;
};

// O(n log n) expected; throws std::invalid_argument("weld_soup: ...") on an index out of range.
[[nodiscard]] WeldedSoup weld_soup(const Soup& soup);

}  // namespace shadowcert
