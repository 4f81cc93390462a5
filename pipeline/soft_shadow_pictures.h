#pragma once
// Pictures of the exact soft reference and of a method's error against it
// (docs/smoothies.md#the-exact-soft-reference), as gpu/image.h images for gpu/png_image.h
// (files, or an HTML report's data: URIs). Light images as in pipeline/soft_shadow_comparison.h;
// a light image itself as gray and float files: cli/light_image_output.h.
#include <array>
#include <cstdint>
#include <span>

#include "gpu/image.h"
#include "pipeline/soft_reference.h"
#include "reference/soft_shadow_image.h"

namespace shadowcert {

// The diverging colour of a signed error in [-1, 1] (clamped): ColorBrewer's RdBu, 11 classes
// interpolated linearly: dark blue at -1 (the method too dark), near white (247, 247, 247) at
// 0, dark red at +1 (too bright). NaN gives the white.
[[nodiscard]] std::array<std::uint8_t, 3> diverging_colour(double error);

// The signed error method - reference per pixel in diverging_colour, opaque, where both have a
// light; green (0, 160, 0) where the coverage differs (one has a light, the other none);
// transparent black where neither has. Throws std::invalid_argument("soft_error_image: ...")
// when light does not hold one value per pixel of the reference.
[[nodiscard]] gpu::RgbaImage soft_error_image(const SoftShadowImage& reference, std::span<const float> light);

// A legend for soft_error_image: `width` x `height` (both >= 1), -1 at the left, +1 at the right.
[[nodiscard]] gpu::RgbaImage diverging_colour_bar(std::uint32_t width, std::uint32_t height);

// The reference's regions: umbra black, penumbra gray (128), fully lit white, a contact pixel
// red (255, 0, 0), a hit without a defined sample yellow (255, 255, 0), all opaque; no hit
// transparent black.
[[nodiscard]] gpu::RgbaImage soft_region_image(const SoftReference& reference);

}  // namespace shadowcert
