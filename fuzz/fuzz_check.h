#pragma once
// Invariants the fuzz harnesses check on every successful read (docs/fuzzing-parsers.md).
// A violation is a finding like a crash: __builtin_trap() stops the run on the spot, and
// libFuzzer saves the input that caused it.
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/soup.h"

namespace shadowcert::fuzz {

// Not assert(): harnesses are built in Release (NDEBUG) too.
inline void require(bool holds) {
  if (!holds) __builtin_trap();
}

inline bool finite(const Vec3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// What docs/definitions.md#inputs makes every reader guarantee: finite coordinates, indices in range (a soup
// indexes with 32 bits), and normals either absent or one per vertex.
inline void require_valid_soup(const Soup& soup) {
  require(soup.vertices.size() <= std::numeric_limits<std::uint32_t>::max());
  for (const Vec3& p : soup.vertices) require(finite(p));
  for (const Triangle& t : soup.triangles)
    for (const std::uint32_t index : t) require(index < soup.vertices.size());
  require(soup.normals.empty() || soup.normals.size() == soup.vertices.size());
}

}  // namespace shadowcert::fuzz
