#pragma once
// A shadow volume as float homogeneous triangles (docs/definitions.md#counts): the one type for
// what exact/ hands the GPU (exact/chain_mesh.h), what the GPU draws (gpu/shadow_volume_geometry.h),
// and what it drew, read back (gpu/shadow_method_renderer.h), stored (io/volume_file.h) and
// certified (exact/volume_closure.h).
//
// vertices: (x, y, z, w) with w = 1 for a finite point x and w = 0 for a point at infinity
//   (x_inf = (x - l, 0) for a point light at l, (-l, 0) for a directional light towards l).
// triangles: 0-based indices into `vertices`, oriented outwards (normal by the right-hand
//   rule, seen from outside the volume); a side quad is stored as two triangles.
// Nothing here is validated: consumers check indices (gpu::ShadowVolumeMesh,
// weld_volume) and the .vol reader checks w.
#include <array>
#include <cstdint>
#include <vector>

namespace shadowcert {

struct HomogeneousMesh {
  std::vector<std::array<float, 4>> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

}  // namespace shadowcert
