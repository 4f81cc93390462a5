#pragma once
// What the GL volume tests share (compute, per-triangle, gs/ts and shadow-map tests): the
// canonical soup and edge table of a test soup, the default scene, and the closure check of
// captured triangles. The reference every method is compared with is the exact cpu chain as
// GPU geometry, exact/chain_mesh.h's chain_mesh (what render --method cpu draws): tests that
// use it link shadowcert_exact (CPU reference only: gpu/ never does).
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/scene.h"
#include "gpu/compute_volume.h"
#include "gpu/shadow_volume_geometry.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/scene_file.h"

namespace shadowcert::gpu::test {

inline const Light kPointLight{{1.5, 4.0, 2.5, 1.0}};
inline const Light kDirectionalLight{{0.3, 1.0, 0.2, 0.0}};

struct Prepared {
  CanonicalSoup canonical;
  EdgeTable table;
};

inline Prepared prepare(const Soup& soup) {
  Prepared p{canonical_soup(soup), {}};
  p.table = build_edge_table(p.canonical.soup);
  return p;
}

inline Scene default_scene() {
  return load_scene(std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/default.json",
                    [](const std::filesystem::path& file) -> Soup {
                      throw std::runtime_error("default.json should need no mesh file: " + file.string());
                    });
}

// As cli/scene_input.cpp's merged_soup: every mesh's vertices and triangles, one soup.
inline Soup merged(const Scene& scene) {
  Soup out;
  for (const SceneMesh& mesh : scene.meshes) {
    const auto offset = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), mesh.soup.vertices.begin(), mesh.soup.vertices.end());
    for (Triangle t : mesh.soup.triangles) out.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  return out;
}

// Every directed edge (a, b) of the welded triangles minus its reverse: zero when closed.
inline std::map<std::pair<std::uint32_t, std::uint32_t>, int> unbalanced_edges(const std::vector<VolumeTriangle>& triangles) {
  std::map<std::array<std::uint32_t, 4>, std::uint32_t> ids;  // bitwise weld of vec4 vertices
  auto id = [&ids](const Vec4f& x) {
    const std::array<std::uint32_t, 4> bits{std::bit_cast<std::uint32_t>(x[0]), std::bit_cast<std::uint32_t>(x[1]),
                                            std::bit_cast<std::uint32_t>(x[2]), std::bit_cast<std::uint32_t>(x[3])};
    return ids.emplace(bits, static_cast<std::uint32_t>(ids.size())).first->second;
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> balance;
  for (const VolumeTriangle& t : triangles) {
    const std::array<std::uint32_t, 3> v{id(t[0]), id(t[1]), id(t[2])};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      if (a == b) continue;  // a degenerate triangle's collapsed edge bounds nothing
      balance[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
    }
  }
  std::erase_if(balance, [](const auto& entry) { return entry.second == 0; });
  return balance;
}

}  // namespace shadowcert::gpu::test
