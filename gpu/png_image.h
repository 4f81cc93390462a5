#pragma once
// PNG files through libpng: colour renders and, losslessly, 8-bit gray images such as the
// stencil counts (a PNG stores the bytes as given: no gamma, no dithering on write).
// Failures throw std::runtime_error "FILE: libpng message".
#include <cstdint>
#include <string>
#include <vector>

#include "gpu/image.h"

namespace shadowcert::gpu {

void write_png(const std::string& path, const RgbaImage& image);
void write_png(const std::string& path, const GrayImage& image);

// The same PNG bytes in memory (e.g. for a data: URI in an HTML report). Failures throw
// std::runtime_error "encode_png: libpng message".
[[nodiscard]] std::vector<std::uint8_t> encode_png(const RgbaImage& image);
[[nodiscard]] std::vector<std::uint8_t> encode_png(const GrayImage& image);

}  // namespace shadowcert::gpu
