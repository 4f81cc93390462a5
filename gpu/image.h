#pragma once
// An 8-bit image read back from GL, row 0 at the TOP (GL's rows are bottom-up; readback
// flips them so images, PNG files and the exact module's pixel grid agree, docs/gpu.md).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace shadowcert::gpu {

template <int Channels>
struct Image {
  static constexpr int kChannels = Channels;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> pixels;  // row-major, top row first, Channels bytes per pixel

  Image() = default;
  Image(std::uint32_t w, std::uint32_t h) : width(w), height(h), pixels(std::size_t{w} * h * Channels, 0) {}

  // Pointer to the first channel of pixel (x, row), row 0 at the top.
  [[nodiscard]] std::uint8_t* at(std::uint32_t x, std::uint32_t row) {
    return pixels.data() + (std::size_t{row} * width + x) * Channels;
  }
  [[nodiscard]] const std::uint8_t* at(std::uint32_t x, std::uint32_t row) const {
    return pixels.data() + (std::size_t{row} * width + x) * Channels;
  }
};

using RgbaImage = Image<4>;  // RGBA8
using GrayImage = Image<1>;  // one byte per pixel: stencil counts, lit masks

}  // namespace shadowcert::gpu
