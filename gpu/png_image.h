#pragma once
// PNG files through libpng: colour renders and, losslessly, 8-bit gray images such as the
// stencil counts (a PNG stores the bytes as given: no gamma, no dithering on write).
// Failures throw std::runtime_error "FILE: libpng message".
#include <string>

#include "gpu/image.h"

namespace shadowcert::gpu {

void write_png(const std::string& path, const RgbaImage& image);
void write_png(const std::string& path, const GrayImage& image);

}  // namespace shadowcert::gpu
