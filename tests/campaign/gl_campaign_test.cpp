// The GL campaign (campaign/gl_campaign.h, `shadowcert fuzz --gl`) bounded for the test label:
// the robust methods cpu, cs, gs, ts and pertri with their default exact signs show no failing
// case (no open volume, no hard error) over a seeded run that holds every light placement of
// campaign/random_soup.h, adversarial ones included (docs/campaign.md, "The GL methods"); and the
// same over a few hard-soup scenes (campaign/hard_scene.h) at a small size, every part among them.
#include "campaign/gl_campaign.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <iostream>

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

}  // namespace
}  // namespace shadowcert
