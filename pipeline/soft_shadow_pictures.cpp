#include "pipeline/soft_shadow_pictures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace shadowcert {
namespace {

// ColorBrewer RdBu (11 classes), from -1 (blue) to +1 (red): Cynthia Brewer, colorbrewer2.org.
constexpr std::array<std::array<std::uint8_t, 3>, 11> kRdBu{{{5, 48, 97},
                                                            {33, 102, 172},
                                                            {67, 147, 195},
                                                            {146, 197, 222},
                                                            {209, 229, 240},
                                                            {247, 247, 247},
                                                            {253, 219, 199},
                                                            {244, 165, 130},
                                                            {214, 96, 77},
                                                            {178, 24, 43},
                                                            {103, 0, 31}}};

void put(gpu::RgbaImage& image, std::size_t p, std::array<std::uint8_t, 3> rgb, std::uint8_t alpha) {
  std::uint8_t* px = image.pixels.data() + 4 * p;
  px[0] = rgb[0];
  px[1] = rgb[1];
  px[2] = rgb[2];
  px[3] = alpha;
}

}  // namespace

std::array<std::uint8_t, 3> diverging_colour(double error) {
  if (std::isnan(error)) return kRdBu[5];
  const double x = (std::clamp(error, -1.0, 1.0) + 1.0) * 5.0;  // [0, 10]
  const auto k = static_cast<std::size_t>(std::min(x, 9.0));
  const double f = x - static_cast<double>(k);
  std::array<std::uint8_t, 3> rgb{};
  for (std::size_t c = 0; c < 3; ++c)
    rgb[c] = static_cast<std::uint8_t>(std::lround((1.0 - f) * kRdBu[k][c] + f * kRdBu[k + 1][c]));
  return rgb;
}

gpu::RgbaImage soft_error_image(const SoftShadowImage& reference, std::span<const float> light) {
  if (light.size() != reference.pixels())
    throw std::invalid_argument("soft_error_image: the light image has " + std::to_string(light.size()) +
                                " values for " + std::to_string(reference.pixels()) + " pixels");
  gpu::RgbaImage image(reference.width, reference.height);
  for (std::size_t p = 0; p < light.size(); ++p) {
    const bool has_reference = reference.light[p] >= 0.0f, covered = light[p] >= 0.0f;
    if (has_reference && covered)
      put(image, p, diverging_colour(static_cast<double>(light[p]) - reference.light[p]), 255);
    else if (has_reference != covered)
      put(image, p, {0, 160, 0}, 255);
  }
  return image;
}

gpu::RgbaImage diverging_colour_bar(std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0) throw std::invalid_argument("diverging_colour_bar: empty size");
  gpu::RgbaImage bar(width, height);
  for (std::uint32_t x = 0; x < width; ++x) {
    const double error = width == 1 ? 0.0 : 2.0 * x / (width - 1) - 1.0;
    for (std::uint32_t y = 0; y < height; ++y) put(bar, std::size_t{y} * width + x, diverging_colour(error), 255);
  }
  return bar;
}

gpu::RgbaImage soft_region_image(const SoftReference& reference) {
  const SoftShadowImage& soft = reference.image;
  gpu::RgbaImage image(soft.width, soft.height);
  for (std::size_t p = 0; p < soft.pixels(); ++p) {
    switch (soft.region(p)) {
      case SoftRegion::none:
        break;
      case SoftRegion::undefined:
        put(image, p, {255, 255, 0}, 255);
        break;
      case SoftRegion::umbra:
        put(image, p, !reference.contact.empty() && reference.contact[p] != 0 ? std::array<std::uint8_t, 3>{255, 0, 0}
                                                                               : std::array<std::uint8_t, 3>{0, 0, 0},
            255);
        break;
      case SoftRegion::penumbra:
        put(image, p, {128, 128, 128}, 255);
        break;
      case SoftRegion::lit:
        put(image, p, {255, 255, 255}, 255);
        break;
    }
  }
  return image;
}

}  // namespace shadowcert
