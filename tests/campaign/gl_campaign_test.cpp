// The GL campaign (campaign/gl_campaign.h, `shadowcert fuzz --gl`) bounded for the test label:
// the robust methods cpu, cs, gs, ts and pertri with their default exact signs show no failing
// case (no open volume, no hard error) over a seeded run that holds every light placement of
// campaign/random_soup.h, adversarial ones included (docs/campaign.md, "The GL methods"); and the
// same over a few hard-soup scenes (campaign/hard_scene.h) at a small size, every part among them.
#include "campaign/gl_campaign.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <iostream>

#include "campaign/window_comparison.h"
#include "support/gl_test_support.h"

namespace shadowcert {
namespace {

using gpu::test::GlTest;

class GlCampaignTest : public GlTest {};

constexpr std::uint64_t kSeed = 31;
constexpr std::uint64_t kCases = 120;

TEST_F(GlCampaignTest, EveryPlacement_RobustMethodsHaveNoFailingCase) {
  std::cout << "seed " << kSeed << ", " << kCases << " cases\n";
  std::array<std::uint64_t, kLightPlacements> placements{};
  for (std::uint64_t i = 0; i < kCases; ++i) ++placements[static_cast<std::size_t>(draw_case_kind(kSeed, i).light)];
  for (std::size_t p = 0; p < kLightPlacements; ++p)
    EXPECT_GT(placements[p], 0u) << placement_name(static_cast<LightPlacement>(p)) << " never drawn";

  GlCampaignOptions options;
  options.seed = kSeed;
  options.cases = kCases;
  options.triangles = 40;
  options.methods = {gpu::ShadowMethod::cpu, gpu::ShadowMethod::cs, gpu::ShadowMethod::gs, gpu::ShadowMethod::ts,
                     gpu::ShadowMethod::pertri};
  options.max_shrunk_per_method = 0;
  const GlCampaignResult result = run_gl_campaign(options);
  ASSERT_EQ(result.cases, kCases);
  for (std::size_t m = 0; m < options.methods.size(); ++m) {
    const GlCampaignTally& t = result.methods[m];
    SCOPED_TRACE(gl_run_name(options.methods[m]));
    EXPECT_EQ(t.failures, 0u);
    EXPECT_EQ(t.closure_failures, 0u);
    EXPECT_EQ(t.hard_error_pixels, 0u);
    EXPECT_EQ(t.capacity_errors, 0u);
    EXPECT_GT(t.agree_pixels, 0u);  // the comparison compared something
  }
}

TEST_F(GlCampaignTest, HardScenes_RobustMethodsHaveNoFailingScene) {
  GlCampaignOptions options;
  options.scenes = GlSceneSource::hard;
  options.seed = kSeed;
  options.cases = 4;
  options.width = 128;
  options.height = 96;
  options.methods = {gpu::ShadowMethod::cpu, gpu::ShadowMethod::cs, gpu::ShadowMethod::gs, gpu::ShadowMethod::ts,
                     gpu::ShadowMethod::pertri};
  options.max_shrunk_per_method = 0;
  const GlCampaignResult result = run_gl_campaign(options);
  ASSERT_EQ(result.cases, options.cases);
  std::uint64_t parts = 0;
  for (std::uint64_t n : result.cases_by_part) parts += n;
  EXPECT_GE(parts, 3 * options.cases);
  for (std::size_t m = 0; m < options.methods.size(); ++m) {
    const GlCampaignTally& t = result.methods[m];
    SCOPED_TRACE(gl_run_name(options.methods[m]));
    EXPECT_EQ(t.failures, 0u);
    EXPECT_EQ(t.hard_error_pixels, 0u);
    EXPECT_GT(t.agree_pixels, options.cases * options.width * options.height / 4);
  }
}

// The hard scenes' shrinking (shrink_scene_failure) on a scene that fails: case 15 of seed 2
// (30 triangles) in its campaign view, drawn by cs with float signs (CliFuzz.GlFailure...):
// fewer triangles, the same failure, and the pixel it names fails alone.
TEST_F(GlCampaignTest, ShrinkSceneFailure_FewerTrianglesSameFailureOnTheNamedPixel) {
  const Scene scene = campaign_view_scene(campaign_view(campaign_case(2, 15, 30), 64, 48));
  SceneComparisonOptions float_signs;
  float_signs.method_options.sign = gpu::SignMode::float32;
  const SceneComparison whole = compare_scene(scene, {gpu::ShadowMethod::cs}, float_signs);
  const std::vector<PixelVerdict>& verdicts = whole.runs.front().lights.front().comparison.verdicts;
  const auto first = std::find(verdicts.begin(), verdicts.end(), PixelVerdict::hard_error);
  ASSERT_NE(first, verdicts.end()) << "the case no longer fails: pick another";
  const auto p = static_cast<std::uint32_t>(first - verdicts.begin());
  const SceneShrink s = shrink_scene_failure(scene, 1, 0, gpu::ShadowMethod::cs, GlFailureKind::hard_errors,
                                             {p % 64, p / 64}, gpu::SignMode::float32);
  EXPECT_EQ(s.original_triangles, 30u);
  EXPECT_LT(s.scene.meshes[1].soup.triangles.size(), 30u);
  EXPECT_EQ(s.scene.meshes[0].soup.triangles, scene.meshes[1].soup.triangles);  // the floor held
  EXPECT_GT(s.tests, 1u);
  ASSERT_FALSE(s.pixels.empty());
  EXPECT_EQ(s.window.width * s.window.height, 1u);
  EXPECT_EQ(s.window.x, s.pixels.front()[0]);
  EXPECT_EQ(s.window.y, s.pixels.front()[1]);
  gpu::ShadowMethodOptions options;
  options.sign = gpu::SignMode::float32;
  EXPECT_EQ(compare_in_window(s.scene, gpu::ShadowMethod::cs, 0, s.window, options).comparison.hard_errors, 1u);
}

}  // namespace
}  // namespace shadowcert
