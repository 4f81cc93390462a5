#include "scene/welded_soup.h"

#include <bit>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace shadowcert {
namespace {

// The welding key is the bit pattern of each coordinate, with -0 mapped to +0 (docs/definitions.md#inputs
// ): bitwise identity is the only equality that never merges points an exact predicate
// would tell apart. Readers have already rejected NaN, so no NaN payloads reach here.
struct PositionKey {
  std::array<std::uint64_t, 3> bits;
  bool operator==(const PositionKey&) const = default;
};

std::uint64_t canonical_bits(double x) { return std::bit_cast<std::uint64_t>(x == 0.0 ? 0.0 : x); }

PositionKey key_of(const Vec3& p) { return {{canonical_bits(p[0]), canonical_bits(p[1]), canonical_bits(p[2])}}; }

struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    // splitmix64-style mixing: coordinates on a grid share low bits, so mix thoroughly.
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (std::uint64_t b : k.bits) {
      h ^= b + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
      h ^= h >> 31;
      h *= 0xbf58476d1ce4e5b9ULL;
      h ^= h >> 27;
    }
    return static_cast<std::size_t>(h);
  }
};

}  // namespace

WeldedSoup weld_soup(const Soup& soup) {
  const std::size_t n = soup.vertices.size();
  const bool has_normals = !soup.normals.empty();
  if (has_normals && soup.normals.size() != n)
    throw std::invalid_argument("weld_soup: normals must be empty or one per vertex");

  WeldedSoup out;
  out.welded_id.resize(n);
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> first_index;
  first_index.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto next = static_cast<std::uint32_t>(out.soup.vertices.size());
    const auto [it, inserted] = first_index.try_emplace(key_of(soup.vertices[i]), next);
    if (inserted) {
      // Keep the first occurrence's coordinates verbatim (a -0 stays -0 in the output).
      out.soup.vertices.push_back(soup.vertices[i]);
      if (has_normals) out.soup.normals.push_back(soup.normals[i]);
    }
    out.welded_id[i] = it->second;
  }

  out.soup.triangles.reserve(soup.triangles.size());
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    Triangle welded{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = soup.triangles[t][k];
      if (v >= n)
        throw std::invalid_argument("weld_soup: triangle " + std::to_string(t) + " has index " + std::to_string(v) +
                                    " but the soup has " + std::to_string(n) + " vertices");
      welded[k] = out.welded_id[v];
    }
    out.soup.triangles.push_back(welded);
  }
  return out;
}

}  // namespace shadowcert
