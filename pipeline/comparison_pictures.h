#pragma once
// Pictures of the exact image and of a method against it, for `diff --out/--report` and
// `shadowcert bench` (docs/diff.md, docs/bench.md), as gpu/image.h images for gpu/png_image.h:
//   - the exact counts n(P) in a perceptual colour map (viridis), so that the counts 1 and 2 of a
//     simple scene are not two shades of black as in the 8-bit gray file (n mod 256);
//   - a method's frame with its hard errors and ambiguous pixels marked.
#include <array>
#include <cstdint>

#include "gpu/image.h"
#include "reference/exact_image.h"
#include "reference/pixel_comparison.h"

namespace shadowcert {

// matplotlib's viridis (256 entries, perceptually uniform, readable in gray and by colour-blind
// readers) at t in [0, 1] (clamped; NaN gives t = 0), nearest entry.
[[nodiscard]] std::array<std::uint8_t, 3> viridis_colour(double t);

// The largest defined count of a light of the exact image (no hit and undefined counts left
// out); 0 when none.
[[nodiscard]] std::uint32_t max_count(const ExactImage& image, std::size_t light);

// Light `light`'s counts, opaque, n in viridis_colour(n / max(1, scale_max)) (scale_max: the
// legend's top, max_count of the light for the full range; larger counts clamp to yellow); an
// undefined count magenta (255, 0, 255); no hit transparent black. Throws std::out_of_range for
// a light out of range.
[[nodiscard]] gpu::RgbaImage count_colour_image(const ExactImage& image, std::size_t light, std::uint32_t scale_max);

// A horizontal legend bar for count_colour_image: `width` x `height` (both >= 1), count 0 at the
// left, scale_max at the right, one band per count (scale_max + 1 bands) when width allows, else
// continuous. Throws std::invalid_argument on a zero side.
[[nodiscard]] gpu::RgbaImage count_colour_bar(std::uint32_t scale_max, std::uint32_t width, std::uint32_t height);

// `colour` (a frame, made opaque) with hard errors red and ambiguous pixels tinted yellow
// (docs/definitions.md#pixel-protocol); the comparison's verdicts must be one per pixel
// (std::invalid_argument("error_overlay: ...") otherwise).
[[nodiscard]] gpu::RgbaImage error_overlay(const gpu::RgbaImage& colour, const PixelComparison& comparison);

}  // namespace shadowcert
