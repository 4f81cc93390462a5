#include "reference/pixel_comparison.h"

#include <stdexcept>

namespace shadowcert {

PixelComparison compare_pixels(const ExactImage& exact, std::size_t light, const RenderedPixels& rendered) {
  if (light >= exact.lights.size()) throw std::invalid_argument("compare_pixels: no such light in the exact image");
  const std::size_t pixels = std::size_t{exact.width} * exact.height;
  if (rendered.width != exact.width || rendered.height != exact.height)
    throw std::invalid_argument("compare_pixels: the rendered and exact images differ in size");
  if (rendered.covered.size() != pixels || rendered.lit.size() != pixels ||
      (!rendered.counts.empty() && rendered.counts.size() != pixels))
    throw std::invalid_argument("compare_pixels: a rendered image has the wrong number of pixels");

  const ExactLightImage& e = exact.lights[light];
  PixelComparison c;
  c.verdicts.resize(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    PixelVerdict& v = c.verdicts[p];
    if (e.ambiguity[p] != 0) {
      v = PixelVerdict::ambiguous;
      ++c.ambiguous;
      continue;
    }
    // Unambiguous: the centre ray hits nothing, or hits with a defined count (kZeroSign
    // covers every undefined one).
    const bool hit = exact.hit_triangles[p] != kNoHit;
    const bool covered = rendered.covered[p] != 0;
    v = PixelVerdict::hard_error;
    if (hit != covered) {
      ++c.coverage_errors;
    } else if (hit && rendered.counts.empty() && (e.lit[p] != 0) != (rendered.lit[p] != 0)) {
      ++c.lit_errors;
    } else if (hit && !rendered.counts.empty() && rendered.counts[p] != static_cast<std::uint8_t>(e.counts[p] % 256)) {
      // Counts are compared modulo 256 (docs/definitions.md#pixel-protocol): an 8-bit stencil shows n = 256 as lit.
      ++(((e.counts[p] % 256 == 0) != (rendered.counts[p] == 0)) ? c.lit_errors : c.count_errors);
    } else {
      v = PixelVerdict::agree;
      ++c.agree;
      continue;
    }
    ++c.hard_errors;
  }
  return c;
}

}  // namespace shadowcert
