#pragma once
// How sphere_grid (procedural_mesh.h) sizes and places its spheres: private to scene/, shared
// with the tests and docs/scene-format.md so that the rule is stated once.
#include <cstdint>

namespace shadowcert {

inline constexpr std::uint32_t kSphereGridSide = 10;  // 10 x 10 spheres, as in Milet 2014
inline constexpr double kSphereGridRadius = 1.0;      // centres at y = radius: resting on y = 0
inline constexpr double kSphereGridSpacing = 2.5;     // centre to centre, gaps of 0.5 between spheres
// 100 spheres of the coarsest UV sphere (3 slices, 2 stacks: 6 triangles) up to 1M each.
inline constexpr std::uint64_t kSphereGridMinTriangles = 600;
inline constexpr std::uint64_t kSphereGridMaxTriangles = 100'000'000;

struct SphereGridLayout {
  std::uint32_t slices;
  std::uint32_t stacks;
  std::uint64_t total_triangles;  // 100 * 2 * slices * (stacks - 1)
};

// The rule: among slices s >= 3 and stacks k >= 2 with |s - 2k| <= max(2, floor(k/4)) (so the
// quads at the equator stay near square), minimise |100 * 2s(k-1) - requested|; ties go to the
// smaller |s - 2k|, then the smaller s. Throws std::invalid_argument outside
// [kSphereGridMinTriangles, kSphereGridMaxTriangles].
[[nodiscard]] SphereGridLayout sphere_grid_layout(std::uint64_t requested_triangles);

}  // namespace shadowcert
