// The `cs` method (gpu/compute_volume.h) on llvmpipe or any EGL device:
//  1. its multiplicities and cap signs, read back from the GPU, equal exact/'s
//     glsign_multiplicities (exact signs of the float inputs, the default) and, under
//     SignMode::float32, refedge_multiplicities(..., Precision::float32) bit for bit (the shader
//     mirrors core/light_side_formula.h with `precise`; Milet 2014 §2.2), on the default scene soup, a
//     closed UV sphere and a fan of 100 triangles on one edge, point and directional lights;
//  2. the emitted triangles form a closed chain (docs/definitions.md#counts): welded bitwise, every directed
//     edge is balanced by its reverse;
//  3. the stencil counts drawn from it equal those of the exact cpu chain except on volume
//     boundaries (default.json, z-fail).
#include "gpu/compute_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "exact/edge_multiplicity.h"
#include "support/gl_test_support.h"
#include "support/volume_test_support.h"
#include "gpu/shadow_method_renderer.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;
using namespace test;

// Pixels of default.json at its 1024x768 camera where the cs and cpu stencil counts may
// differ. They can only differ on volume boundaries: the far vertices are rounded differently
// (x_f - l_f in float on the GPU, x - l in double then rounded by cli/), which moves a side
// plane by about one float ulp, and float refedge signs may differ from exact ones for a light
// (almost) in a triangle's plane, whose sides are then (almost) edge-on. Measured: see the
// test's output (4 on llvmpipe); the bound leaves room for another rasteriser's ties.
constexpr std::size_t kMaxBoundaryPixels = 64;

NamedSoups test_soups() {
  return {{"default scene", merged_soup(default_scene())},
          {"uv sphere", uv_sphere({0.2, 0.1, -0.3}, 1.0, 32, 16)},
          {"fan of 100", nonmanifold_fan(100)}};
}
// The GL context fixture (support/gl_test_support.h) under this unit's name, for
// --gtest_filter=ComputeVolumeTest.*
class ComputeVolumeTest : public GlTest {};

TEST_F(ComputeVolumeTest, FloatSigns_MultiplicitiesAndCapSignsEqualCpuRefedgeFloat32) {
  for_each_build<ComputeShadowVolume>(
      test_soups(), {kPointLight, kDirectionalLight},
      [](const ComputeShadowVolume& volume, const Prepared& p, const Light& light) {
        const EdgeMultiplicities cpu = refedge_multiplicities(p.canonical.soup, p.table, light, Precision::float32);
        EXPECT_EQ(volume.read_multiplicities(), cpu.multiplicity);
        EXPECT_EQ(volume.read_triangle_signs(), triangle_signs(cpu));
        EXPECT_LE(volume.read_requested_vertices(), volume.capacity_vertices());
      },
      SignMode::float32);
}

TEST_F(ComputeVolumeTest, ExactSigns_MultiplicitiesAndCapSignsEqualGlsign) {
  for_each_build<ComputeShadowVolume>(
      test_soups(), {kPointLight, kDirectionalLight},
      [](const ComputeShadowVolume& volume, const Prepared& p, const Light& light) {
        const EdgeMultiplicities cpu = glsign_multiplicities(p.canonical.soup, p.table, light);
        EXPECT_EQ(volume.read_multiplicities(), cpu.multiplicity);
        EXPECT_EQ(volume.read_triangle_signs(), triangle_signs(cpu));
      });
}

// A half fan (volume_test_support.h) lit from the plane x = 0: |m| = k, the worst case the
// output buffer is sized for.
TEST_F(ComputeVolumeTest, HalfFanEdgeReachesMultiplicityK) {
  constexpr std::uint32_t kBlades = 100;
  const Prepared p = prepare(half_fan(kBlades));
  const ComputeVolumeSoup gpu_soup(p.canonical.soup, p.table);
  ComputeShadowVolume volume(gpu_soup);
  const Light light = kHalfFanLight;
  volume.build(light);
  std::int32_t largest = 0;
  for (std::int32_t m : volume.read_multiplicities()) largest = std::max(largest, std::abs(m));
  EXPECT_EQ(largest, static_cast<std::int32_t>(kBlades));
  EXPECT_EQ(volume.read_multiplicities(), glsign_multiplicities(p.canonical.soup, p.table, light).multiplicity);
  EXPECT_TRUE(unbalanced_edges(volume.read_triangles()).empty());
}

TEST_F(ComputeVolumeTest, CapturedVolumeIsClosed) {
  for_each_build<ComputeShadowVolume>(test_soups(), {kPointLight, kDirectionalLight},
                                      [](const ComputeShadowVolume& volume, const Prepared&, const Light&) {
                                        expect_drawn_closed(volume);
                                      });
}

TEST_F(ComputeVolumeTest, StencilCountsMatchCpuExceptOnBoundaries) {
  const Scene scene = default_scene();
  const StencilDifference c =
      stencil_difference_from_cpu(ShadowMethod::cs, merged_soup(scene), scene.lights.front(), scene.camera);
  std::cout << "cs vs cpu: " << c.differing << " differing stencil pixels of " << c.shadowed << " shadowed\n";
  EXPECT_GT(c.shadowed, 10000u);  // the scene's shadows are in view: the comparison means something
  EXPECT_LE(c.differing, kMaxBoundaryPixels);
}

}  // namespace
}  // namespace shadowcert::gpu
