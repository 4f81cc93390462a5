// campaign/window_comparison.h: one method and one light over a window of pixels give each pixel
// of the window the verdict compare_scene gives it (the frame drawn alike, the window's exact
// image the whole image's there), judge no pixel outside it, and certify the volume as
// compare_scene does.
#include "campaign/window_comparison.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "campaign/hard_scene.h"
#include "support/gl_test_support.h"

namespace shadowcert {
namespace {

using gpu::test::GlTest;

class WindowComparisonTest : public GlTest {};

TEST_F(WindowComparisonTest, WindowVerdicts_AreCompareScenesThereAndAmbiguousElsewhere) {
  const Scene scene = hard_scene_case(7, 2, 96, 72).scene;
  const std::vector<gpu::ShadowMethod> methods{gpu::ShadowMethod::cpu, gpu::ShadowMethod::pertri};
  const SceneComparison whole = compare_scene(scene, methods, {});
  const PixelWindow window{30, 20, 40, 30};
  for (std::size_t m = 0; m < methods.size(); ++m)
    for (std::size_t k = 0; k < scene.lights.size(); ++k) {
      SCOPED_TRACE(std::string(gpu::shadow_method_name(methods[m])) + ", light " + std::to_string(k));
      const LightRun part = compare_in_window(scene, methods[m], k, window);
      const LightRun& full = whole.runs[m].lights[k];
      ASSERT_TRUE(part.closure && full.closure);
      EXPECT_EQ(part.closure->closed, full.closure->closed);
      EXPECT_EQ(part.volume_triangles, full.volume_triangles);
      EXPECT_EQ(part.frame.first_stencil.pixels, full.frame.first_stencil.pixels);  // the same frame
      std::uint64_t agree = 0;
      for (std::uint32_t r = 0; r < 72; ++r)
        for (std::uint32_t i = 0; i < 96; ++i) {
          const std::size_t p = std::size_t{r} * 96 + i;
          const bool in = i >= window.x && i < window.x + window.width && r >= window.y && r < window.y + window.height;
          EXPECT_EQ(part.comparison.verdicts[p], in ? full.comparison.verdicts[p] : PixelVerdict::ambiguous)
              << i << "," << r;
          agree += in && full.comparison.verdicts[p] == PixelVerdict::agree ? 1 : 0;
        }
      EXPECT_GT(agree, 0u);  // not vacuous
      EXPECT_EQ(part.comparison.agree, agree);
    }
  EXPECT_THROW((void)compare_in_window(scene, methods[0], scene.lights.size(), window), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert
