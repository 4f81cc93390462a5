#pragma once
// The canonical form of a soup that multiplicities, chains and certificates work on:
// exactly welded (docs/definitions.md#inputs) and with its vertices renumbered in lexicographic order of
// (x, y, z). Index order is then the strict total vertex order of docs/definitions.md#counts (Milet 2014's
// Greater with weights (4, 2, 1) is this order), so "u < v" on indices compares positions:
// answers cannot depend on how the input labelled its vertices, and a shader that compares
// indices sorts a triangle exactly as the CPU does.
#include <cstdint>
#include <vector>

#include "core/soup.h"

namespace shadowcert {

struct CanonicalSoup {
  Soup soup;  // welded, vertices sorted lexicographically; triangles in input order, remapped
  std::vector<std::uint32_t> canonical_id;  // input vertex index -> canonical index
};

// O(n log n). Throws std::invalid_argument("canonical_soup: ...") on an index out of range.
[[nodiscard]] CanonicalSoup canonical_soup(const Soup& soup);

}  // namespace shadowcert
