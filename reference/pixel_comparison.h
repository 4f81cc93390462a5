#pragma once
// The pixel protocol's verdict (docs/definitions.md#pixel-protocol): one light's rendered pixels (whatever drew them:
// a GL method's readback, or a test's planted fault) against the exact image. GL-free, so that
// the comparison itself is tested without a renderer (tests/reference/pixel_comparison_test.cpp).
//
// Per pixel: AMBIGUOUS when the exact image says so (reference/exact_image.h), whatever was drawn;
// otherwise a HARD ERROR when coverage differs (a receiver drawn where the centre ray hits
// nothing, or none where it hits) or, on a covered pixel, for a method that counts (a stencil
// method) when its count differs from n(P) modulo 256 (stencil counts wrap, docs/definitions.md#pixel-protocol: a stencil
// holding 256 crossings shows the pixel lit, and that is compared as 0), for a mask-only
// method (the shadow map) when lit/shadowed differ; otherwise AGREE.
#include <cstdint>
#include <span>
#include <vector>

#include "reference/exact_image.h"

namespace shadowcert {

// One light's rendered pixels, row-major, row 0 at the TOP (gpu/image.h), each span
// width * height bytes long (counts may be empty).
struct RenderedPixels {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::span<const std::uint8_t> covered;  // nonzero where a receiver covers the pixel (GL alpha)
  std::span<const std::uint8_t> lit;      // nonzero where the method shows the light
  std::span<const std::uint8_t> counts;   // the stencil counts modulo 256; empty: a mask-only method
};

enum class PixelVerdict : std::uint8_t { agree, ambiguous, hard_error };

struct PixelComparison {
  std::uint64_t agree = 0;
  std::uint64_t ambiguous = 0;
  std::uint64_t hard_errors = 0;
  // The hard errors by their first failed test (each hard error is counted once).
  std::uint64_t coverage_errors = 0;
  std::uint64_t lit_errors = 0;    // lit/shadowed wrong (for counts: zero or not modulo 256)
  std::uint64_t count_errors = 0;  // lit/shadowed right, count wrong (counting methods only)
  std::vector<PixelVerdict> verdicts;  // per pixel
};

// Compares light number `light` of `exact` with `rendered`. Throws std::invalid_argument
// ("compare_pixels: ...") when the sizes disagree or `light` is out of range.
[[nodiscard]] PixelComparison compare_pixels(const ExactImage& exact, std::size_t light,
                                             const RenderedPixels& rendered);

}  // namespace shadowcert
