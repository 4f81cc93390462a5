#pragma once
// A light's smoothies (Chan & Durand 2003; Chen & Tsai, docs/smoothies.md) as plain triangles:
// the one type contour/smoothie.h builds, pipeline/ hands on and gpu/smoothie_map.h draws.
//
// vertices: world positions (the frame the receivers are drawn in);
// alpha:    one per vertex, 0 on the silhouette edge, 1 on the smoothie's outer rim (the map
//           interpolates it linearly over each triangle);
// triangles: indices into `vertices`; no orientation (the map draws both sides).
// Nothing here is validated: gpu::SmoothieQuads checks the sizes and indices on upload.
#include <array>
#include <cstdint>
#include <vector>

namespace shadowcert {

struct SmoothieMesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<float> alpha;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

}  // namespace shadowcert
