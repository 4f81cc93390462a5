#include "cli/light_image_output.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gpu/png_image.h"
#include "io/float_image_file.h"
#include "io/output_file.h"

namespace shadowcert::cli {

std::filesystem::path light_image_float_path(const std::filesystem::path& png) {
  std::filesystem::path out = png;
  if (out.extension() == ".png") return out.replace_extension(".pfm");
  out += ".pfm";
  return out;
}

gpu::GrayImage light_image_gray(std::uint32_t width, std::uint32_t height, std::span<const float> amount) {
  if (amount.size() != std::size_t{width} * height)
    throw std::invalid_argument("light_image_gray: " + std::to_string(amount.size()) + " values for " +
                                std::to_string(width) + "x" + std::to_string(height));
  gpu::GrayImage image(width, height);
  for (std::size_t p = 0; p < amount.size(); ++p) {
    const float a = amount[p];
    image.pixels[p] = a >= 0.0f ? static_cast<std::uint8_t>(std::lround(255.0f * std::min(a, 1.0f))) : 0;
  }
  return image;
}

void write_light_image(const std::filesystem::path& png, std::uint32_t width, std::uint32_t height,
                       std::span<const float> amount) {
  const gpu::GrayImage gray = light_image_gray(width, height, amount);
  create_parent_directories(png);
  gpu::write_png(png.string(), gray);
  write_pfm(light_image_float_path(png), width, height, amount);
}

}  // namespace shadowcert::cli
