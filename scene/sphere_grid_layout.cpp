#include "scene/sphere_grid_layout.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <tuple>

namespace shadowcert {
namespace {

std::uint64_t slice_band(std::uint64_t stacks) { return std::max<std::uint64_t>(2, stacks / 4); }

std::uint64_t grid_triangles(std::uint64_t slices, std::uint64_t stacks) {
  return std::uint64_t{kSphereGridSide} * kSphereGridSide * 2 * slices * (stacks - 1);
}

std::uint64_t distance(std::uint64_t a, std::uint64_t b) { return a > b ? a - b : b - a; }

}  // namespace

SphereGridLayout sphere_grid_layout(std::uint64_t requested) {
  if (requested < kSphereGridMinTriangles || requested > kSphereGridMaxTriangles)
    throw std::invalid_argument("sphere_grid_layout: requested triangles must be in [" +
                                std::to_string(kSphereGridMinTriangles) + ", " +
                                std::to_string(kSphereGridMaxTriangles) + "], got " + std::to_string(requested));
  // Key (error, |s - 2k|, s): lexicographic minimum is the documented rule.
  std::tuple<std::uint64_t, std::uint64_t, std::uint64_t> best{UINT64_MAX, 0, 0};
  SphereGridLayout layout{3, 2, grid_triangles(3, 2)};
  for (std::uint64_t k = 2;; ++k) {
    const std::uint64_t band = slice_band(k);
    const std::uint64_t s_min = std::max<std::uint64_t>(3, 2 * k > band ? 2 * k - band : 0);
    // Counts grow with k at the band's low end: once it overshoots by more than the best
    // error so far, no larger k can do better.
    if (grid_triangles(s_min, k) > requested && grid_triangles(s_min, k) - requested > std::get<0>(best)) break;
    for (std::uint64_t s = s_min; s <= 2 * k + band; ++s) {
      const std::uint64_t count = grid_triangles(s, k);
      const std::tuple<std::uint64_t, std::uint64_t, std::uint64_t> key{distance(count, requested),
                                                                         distance(s, 2 * k), s};
      if (key < best) {
        best = key;
        layout = {static_cast<std::uint32_t>(s), static_cast<std::uint32_t>(k), count};
      }
    }
  }
  return layout;
}

}  // namespace shadowcert
