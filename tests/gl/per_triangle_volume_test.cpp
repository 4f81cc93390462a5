// The `pertri` method (gpu/per_triangle_volume.h, Milet 2014 §2.1) on llvmpipe or any EGL
// device:
//  1. its per-triangle signs equal exact/'s refedge_multiplicities(..., Precision::float32)
//     triangle_sign bit for bit, on the default scene soup and a UV sphere, point and
//     directional lights;
//  2. the emitted triangles, welded bitwise, balance every directed edge (each V(t) is closed,
//     DESIGN.md §3, so their union is);
//  3. its stencil counts equal those of the exact cpu chain on default.json's camera except on
//     volume boundaries (z-fail).
#include "gpu/per_triangle_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "exact/chain_mesh.h"
#include "exact/edge_multiplicity.h"
#include "exact/shadow_volume_chain.h"
#include "gl_test_support.h"
#include "volume_test_support.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_volume_geometry.h"
#include "gpu/stencil_shadow_renderer.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_file.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;
using namespace test;

// Pixels of default.json at its 1024x768 camera where the pertri and cpu stencil counts may
// differ. pertri's union of closed V(t) counts what the chain counts (DESIGN.md §3: interior
// sides cancel in pairs, per_triangle_volume.comp.glsl emits them as bitwise-identical
// reversed triangles), so they differ only next to volume boundaries: a silhouette quad is
// split on the lower-index diagonal, cpu splits it first-to-third vertex, which for half the
// quads is the other diagonal of a rounded, not quite planar quad; far vertices are rounded
// in float on the GPU rather than from double; float refedge signs may differ from exact ones
// for triangles (almost) edge-on to the light. Measured: see the test's output (145 on
// llvmpipe, all +-1); the bound leaves room for another rasteriser's ties.
constexpr std::size_t kMaxBoundaryPixels = 256;

std::vector<std::pair<std::string, Soup>> test_soups() {
  return {{"default scene", merged_soup(default_scene())},
          {"uv sphere", uv_sphere({0.2, 0.1, -0.3}, 1.0, 32, 16)}};
}

TEST_F(GlTest, PerTriangleSignsEqualCpuRefedgeFloat32) {
  for (const auto& [name, soup] : test_soups()) {
    const Prepared p = prepare(soup);
    const ComputeVolumeSoup gpu_soup(p.canonical.soup, p.table);
    PerTriangleShadowVolume volume(gpu_soup);
    for (const Light& light : {kPointLight, kDirectionalLight}) {
      SCOPED_TRACE(name + (light.directional() ? ", directional" : ", point"));
      const EdgeMultiplicities cpu = refedge_multiplicities(p.canonical.soup, p.table, light, Precision::float32);
      volume.build(light);
      std::vector<std::int32_t> cpu_signs;
      for (Sign s : cpu.triangle_sign) cpu_signs.push_back(to_int(s));
      EXPECT_EQ(volume.read_triangle_signs(), cpu_signs);
      EXPECT_LE(volume.read_requested_vertices(), volume.capacity_vertices());
    }
  }
}

TEST_F(GlTest, CapturedPerTriangleVolumesAreClosed) {
  for (const auto& [name, soup] : test_soups()) {
    const Prepared p = prepare(soup);
    const ComputeVolumeSoup gpu_soup(p.canonical.soup, p.table);
    PerTriangleShadowVolume volume(gpu_soup);
    for (const Light& light : {kPointLight, kDirectionalLight}) {
      SCOPED_TRACE(name + (light.directional() ? ", directional" : ", point"));
      volume.build(light);
      const std::vector<VolumeTriangle> triangles = volume.read_triangles();
      std::size_t casting = 0;
      for (std::int32_t s : volume.read_triangle_signs()) casting += s != 0;
      // 8 triangles per casting triangle for a point light, 4 for a directional one.
      EXPECT_EQ(triangles.size(), casting * (light.directional() ? 4u : 8u));
      EXPECT_EQ(triangles.size() * 3, volume.read_requested_vertices());
      EXPECT_FALSE(triangles.empty());
      EXPECT_TRUE(unbalanced_edges(triangles).empty());
    }
  }
}

TEST_F(GlTest, StencilCountsMatchCpuExceptOnBoundaries) {
  const Scene scene = default_scene();
  const Soup soup = merged_soup(scene);
  const Prepared p = prepare(soup);
  const Light& light = scene.lights.front();
  const EdgeMultiplicities exact = exact_multiplicities(p.canonical.soup, p.table, light);
  const ShadowVolumeMesh cpu_volume(
      chain_mesh(assemble_chain(p.canonical.soup, p.table, exact, light), p.canonical.soup, light));
  const ComputeVolumeSoup gpu_soup(p.canonical.soup, p.table);
  PerTriangleShadowVolume pertri_volume(gpu_soup);
  pertri_volume.build(light);

  const ShadedSoupMesh receivers(soup);
  const OffscreenTarget target(scene.camera.width, scene.camera.height);
  const StencilShadowRenderer renderer;
  const std::array cpu_light{LightVolume{light, &cpu_volume, {}}};
  const std::array pertri_light{LightVolume{light, nullptr, pertri_volume.draw()}};
  const StencilShadowFrame cpu = renderer.render(target, receivers, scene.camera, cpu_light);
  const StencilShadowFrame pertri = renderer.render(target, receivers, scene.camera, pertri_light);

  ASSERT_EQ(cpu.first_stencil.pixels.size(), pertri.first_stencil.pixels.size());
  std::size_t differing = 0, shadowed = 0;
  for (std::size_t i = 0; i < cpu.first_stencil.pixels.size(); ++i) {
    differing += cpu.first_stencil.pixels[i] != pertri.first_stencil.pixels[i];
    shadowed += cpu.first_stencil.pixels[i] != 0;
  }
  std::cout << "pertri vs cpu: " << differing << " differing stencil pixels of " << shadowed << " shadowed\n";
  EXPECT_GT(shadowed, 10000u);  // the scene's shadows are in view: the comparison means something
  EXPECT_LE(differing, kMaxBoundaryPixels);
}

}  // namespace
}  // namespace shadowcert::gpu
