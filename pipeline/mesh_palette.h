#pragma once
// Mesh colours of the rendered pictures, in scene order (cycled): only a picture, nothing is
// decided from them.
#include <array>
#include <vector>

#include "core/scene.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert {

inline constexpr std::array<std::array<float, 3>, 4> kMeshPalette{
    {{0.85f, 0.85f, 0.85f}, {0.95f, 0.55f, 0.35f}, {0.45f, 0.75f, 0.95f}, {0.6f, 0.9f, 0.5f}}};

// Every mesh of `scene` as a shaded receiver, casting as the mesh says (SceneMesh::casts); the
// scene must outlive the result.
[[nodiscard]] inline std::vector<gpu::ShadedSoupPart> shaded_parts(const Scene& scene) {
  std::vector<gpu::ShadedSoupPart> parts;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i)
    parts.push_back({&scene.meshes[i].soup, kMeshPalette[i % kMeshPalette.size()], scene.meshes[i].casts});
  return parts;
}

}  // namespace shadowcert
