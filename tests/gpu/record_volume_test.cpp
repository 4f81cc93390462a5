// The two edge-record silhouette methods, `gs` (gpu/geometry_shader_volume.h) and `ts`
// (gpu/tessellation_volume.h, Milet 2014 §2.2), on llvmpipe or any EGL device. They share
// cs's signs and far vertices and differ only in how a record's |m| quads are emitted, so one
// typed suite checks both:
//  1. the captured triangles form a closed chain (docs/definitions.md#counts) on the default scene soup, a
//     closed UV sphere and a fan of 100 triangles on one edge, point and directional lights,
//     and the draw count is every generated primitive (no overflow);
//  2. the stencil counts drawn from it equal those of the exact cpu chain except on volume
//     boundaries: default.json at its camera, and a half fan whose shared edge has 100
//     opposite vertices, |m| = 100, split into records whose partial quads must add up (z-fail).
#include <gtest/gtest.h>
#include <cstdint>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "support/gl_test_support.h"
#include "support/volume_test_support.h"
#include "gpu/compute_volume.h"
#include "gpu/geometry_shader_volume.h"
#include "gpu/tessellation_volume.h"
#include "gpu/shadow_method_renderer.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

namespace shadowcert::gpu {
namespace {

// What differs between the two methods: the method and the opposites one record holds.
template <typename Volume>
struct RecordMethod;
template <>
struct RecordMethod<GeometryShaderShadowVolume> {
  static constexpr ShadowMethod kMethod = ShadowMethod::gs;
  static constexpr std::uint32_t kOpposites = kOppositesPerRecord;
};
template <>
struct RecordMethod<TessellationShadowVolume> {
  static constexpr ShadowMethod kMethod = ShadowMethod::ts;
  static constexpr std::uint32_t kOpposites = kTessellationOppositesPerRecord;
};

template <typename Volume>
class RecordVolumeTest : public test::GlTest {};
using namespace test;
using RecordVolumes = ::testing::Types<GeometryShaderShadowVolume, TessellationShadowVolume>;
TYPED_TEST_SUITE(RecordVolumeTest, RecordVolumes);

// Pixels where the gs/ts and cpu stencil counts may differ: only on volume boundaries, for the
// reasons compute_volume_test.cpp gives for cs (far vertices x_f - l_f rounded in float on the
// GPU, float refedge signs for a light almost in a triangle's plane). gs and ts use the very
// signs and far vertices of cs, so the same bound applies. Measured: see the test's output.
constexpr std::size_t kMaxBoundaryPixels = 64;
// Enough shadowed pixels for a comparison to mean something.
constexpr std::size_t kMinShadowedPixels = 10000;

// volume_test_support.h's half fan of 100 blades before its wall: with kHalfFanLight the
// shared edge's |m| is 100, ceil(100 / opposites per record) records.
constexpr std::uint32_t kBlades = 100;

TYPED_TEST(RecordVolumeTest, CapturedVolumeIsClosed) {
  const NamedSoups soups{{"default scene", merged_soup(default_scene())},
                         {"uv sphere", uv_sphere({0.2, 0.1, -0.3}, 1.0, 32, 16)},
                         {"fan of 100", nonmanifold_fan(100)},
                         {"half fan", half_fan_and_wall(kBlades)}};
  for_each_build<TypeParam>(soups, {kPointLight, kDirectionalLight, kHalfFanLight},
                            [](const TypeParam& volume, const Prepared& p, const Light&) {
                              EXPECT_GE(volume.record_count(), p.table.size());
                              expect_drawn_closed(volume);
                            });
}

TYPED_TEST(RecordVolumeTest, StencilCountsMatchCpuExceptOnBoundaries) {
  const Scene scene = default_scene();
  const StencilDifference c = stencil_difference_from_cpu(RecordMethod<TypeParam>::kMethod, merged_soup(scene),
                                                          scene.lights.front(), scene.camera);
  std::cout << shadow_method_name(RecordMethod<TypeParam>::kMethod) << " vs cpu (default.json): " << c.differing << " differing stencil pixels of " << c.shadowed
            << " shadowed\n";
  EXPECT_GT(c.shadowed, kMinShadowedPixels);
  EXPECT_LE(c.differing, kMaxBoundaryPixels);
}

TYPED_TEST(RecordVolumeTest, SplitRecordsOfAHalfFanAddUp) {
  Camera camera;
  camera.eye = {4.0, 3.0, -6.0};  // on the light's side, looking at the fan and the wall
  camera.target = {0.0, 0.5, kHalfFanWallZ};
  const Prepared p = prepare(half_fan_and_wall(kBlades));
  const ComputeVolumeSoup gpu_soup(p.canonical.soup, p.table);
  // The shared edge's 100 opposites take several records instead of 1: the split is exercised.
  constexpr std::uint32_t k = RecordMethod<TypeParam>::kOpposites;
  ASSERT_LT(k, kBlades);
  EXPECT_EQ(TypeParam(gpu_soup, p.table).record_count(), p.table.size() + (kBlades + k - 1) / k - 1);
  const StencilDifference c =
      stencil_difference_from_cpu(RecordMethod<TypeParam>::kMethod, half_fan_and_wall(kBlades), kHalfFanLight, camera);
  std::cout << shadow_method_name(RecordMethod<TypeParam>::kMethod) << " vs cpu (half fan, |m| = " << kBlades << "): " << c.differing << " differing stencil pixels of "
            << c.shadowed << " shadowed\n";
  EXPECT_GT(c.shadowed, kMinShadowedPixels);
  EXPECT_LE(c.differing, kMaxBoundaryPixels);
}

}  // namespace
}  // namespace shadowcert::gpu
