#pragma once
// `render --light-image FILE.png` (docs/smoothies.md, "The light image"): the first light's amount
// of light per pixel (gpu::StencilShadowFrame::first_light) as two files:
//   FILE.png  8-bit gray, round(255 * amount): 255 lit, 0 shadowed, values between in a
//             penumbra; 0 where no receiver covers the pixel;
//   FILE.pfm  the same amounts as 32-bit floats (io/float_image_file.h), exactly as rendered, -1
//             where no receiver covers the pixel: the copy for measurements. Its name is the
//             PNG's with the extension .png replaced by .pfm (.pfm appended when the name has no
//             .png extension).
#include <cstdint>
#include <filesystem>
#include <span>

#include "gpu/image.h"

namespace shadowcert::cli {

// FILE.png -> FILE.pfm, FILE -> FILE.pfm (the rule above).
[[nodiscard]] std::filesystem::path light_image_float_path(const std::filesystem::path& png);

// The 8-bit picture: round(255 * clamp(amount, 0, 1)) where amount >= 0, 0 where it is negative.
[[nodiscard]] gpu::GrayImage light_image_gray(std::uint32_t width, std::uint32_t height,
                                              std::span<const float> amount);

// Writes both files (parent folders created). Throws std::invalid_argument when the sizes do not
// match, InputError / std::runtime_error naming a file that cannot be written.
void write_light_image(const std::filesystem::path& png, std::uint32_t width, std::uint32_t height,
                       std::span<const float> amount);

}  // namespace shadowcert::cli
