#include "scene/welded_volume.h"

#include <bit>
#include <stdexcept>
#include <unordered_map>

namespace shadowcert {
namespace {

using Key = std::array<std::uint32_t, 4>;

// -0 and +0 are one point; everything else (NaN payloads included) is compared by bits.
Key weld_key(const std::array<float, 4>& v) {
  Key k{};
  for (int i = 0; i < 4; ++i) k[i] = v[i] == 0.0f ? 0u : std::bit_cast<std::uint32_t>(v[i]);
  return k;
}

struct KeyHash {
  std::size_t operator()(const Key& k) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::uint32_t x : k) h = (h ^ x) * 0xff51afd7ed558ccdull;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};

}  // namespace

HomogeneousMesh weld_volume(const HomogeneousMesh& volume) {
  HomogeneousMesh welded;
  std::unordered_map<Key, std::uint32_t, KeyHash> ids;
  ids.reserve(volume.vertices.size());
  std::vector<std::uint32_t> remap(volume.vertices.size());
  for (std::size_t i = 0; i < volume.vertices.size(); ++i) {
    const auto [it, inserted] = ids.try_emplace(weld_key(volume.vertices[i]),
                                                static_cast<std::uint32_t>(welded.vertices.size()));
    // The first-seen bits represent the welded vertex, so a lone -0 is written as -0.
    if (inserted) welded.vertices.push_back(volume.vertices[i]);
    remap[i] = it->second;
  }
  welded.triangles.reserve(volume.triangles.size());
  for (const auto& t : volume.triangles) {
    std::array<std::uint32_t, 3> w{};
    for (int k = 0; k < 3; ++k) {
      if (t[k] >= remap.size())
        throw std::invalid_argument("weld_volume: vertex index " + std::to_string(t[k]) + " but " +
                                    std::to_string(remap.size()) + " vertices");
      w[k] = remap[t[k]];
    }
    welded.triangles.push_back(w);
  }
  return welded;
}

}  // namespace shadowcert
