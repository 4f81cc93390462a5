// pipeline/comparison_pictures.h: the counts in viridis (not n mod 256 in gray, where 1 and 2
// are black), their legend bar, and the hard-error overlay.
#include "pipeline/comparison_pictures.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace shadowcert {
namespace {

ExactImage counts_image(std::vector<std::uint32_t> counts) {
  ExactImage image;
  image.width = static_cast<std::uint32_t>(counts.size());
  image.height = 1;
  image.lights.resize(1);
  image.lights[0].counts = std::move(counts);
  return image;
}

TEST(Viridis, EndsAndClamp) {
  EXPECT_EQ(viridis_colour(0.0), (std::array<std::uint8_t, 3>{68, 1, 84}));     // dark purple
  EXPECT_EQ(viridis_colour(1.0), (std::array<std::uint8_t, 3>{253, 231, 37}));  // yellow
  EXPECT_EQ(viridis_colour(-3.0), viridis_colour(0.0));
  EXPECT_EQ(viridis_colour(7.0), viridis_colour(1.0));
  EXPECT_EQ(viridis_colour(std::nan("")), viridis_colour(0.0));
}

TEST(CountColourImage, CountsSpreadOverTheMap_UndefinedMagenta_NoHitTransparent) {
  const ExactImage image = counts_image({0, 1, 2, kUndefinedCount, kNoHit});
  EXPECT_EQ(max_count(image, 0), 2u);
  const gpu::RgbaImage c = count_colour_image(image, 0, 2);
  const auto rgb = [&](std::size_t p) { return std::array<std::uint8_t, 3>{c.pixels[4 * p], c.pixels[4 * p + 1], c.pixels[4 * p + 2]}; };
  EXPECT_EQ(rgb(0), viridis_colour(0.0));
  EXPECT_EQ(rgb(1), viridis_colour(0.5));
  EXPECT_EQ(rgb(2), viridis_colour(1.0));
  // Counts 1 and 2 are far apart (in gray mod 256 they were 1 and 2 of 255).
  EXPECT_GT(std::abs(int{rgb(2)[0]} - int{rgb(1)[0]}), 100);
  EXPECT_EQ(rgb(3), (std::array<std::uint8_t, 3>{255, 0, 255}));
  EXPECT_EQ(c.pixels[4 * 3 + 3], 255);
  EXPECT_EQ(c.pixels[4 * 4 + 3], 0);
}

TEST(CountColourBar, OneBandPerCount) {
  const gpu::RgbaImage bar = count_colour_bar(3, 40, 2);
  EXPECT_EQ(bar.width, 40u);
  EXPECT_EQ(bar.at(0, 0)[0], viridis_colour(0.0)[0]);
  EXPECT_EQ(bar.at(39, 1)[0], viridis_colour(1.0)[0]);
  EXPECT_EQ(bar.at(12, 0)[1], viridis_colour(1.0 / 3.0)[1]);  // the second band
  EXPECT_THROW((void)count_colour_bar(3, 0, 2), std::invalid_argument);
}

TEST(ErrorOverlay, HardErrorsRed_AmbiguousYellowish_Opaque) {
  gpu::RgbaImage frame(3, 1);
  PixelComparison c;
  c.verdicts = {PixelVerdict::agree, PixelVerdict::ambiguous, PixelVerdict::hard_error};
  const gpu::RgbaImage o = error_overlay(frame, c);
  EXPECT_EQ(o.pixels[0], 0);
  EXPECT_EQ(o.pixels[4], 127);
  EXPECT_EQ(o.pixels[8], 255);
  EXPECT_EQ(o.pixels[9], 0);
  EXPECT_EQ(o.pixels[3], 255);
  c.verdicts.pop_back();
  EXPECT_THROW((void)error_overlay(frame, c), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert
