#pragma once
// How fake a fake soft shadow is (docs/smoothies.md#the-exact-soft-reference): a
// method's per-pixel amount of light for its first light against the exact soft reference
// (pipeline/soft_reference.h). Plain arithmetic on images: no GL, no exact predicate.
//
// A method's light image: width x height floats, row-major, row 0 at the TOP (gpu/image.h),
// each in [0, 1] (1 lit) where a receiver covers the pixel and negative where none does
// (gpu/light_image_target.h's kUncoveredLight).
//
// Pixels and figures:
//   - compared: the reference has a light there (a centre hit with some defined sample) and
//     the method covers the pixel; the coverage differences are counted apart (reference_only,
//     method_only) and enter no error figure;
//   - error = method - reference (positive: too bright); mean and max |error| over the
//     compared pixels, and the mean |error| per reference region: inside the exact umbra, in
//     the penumbra, and outside the penumbra (umbra or fully lit: where a fake soft shadow
//     should be exact, the hard part of the shadow and the light around it);
//   - leaks: compared contact pixels (SoftReference::contact: umbra at a caster's foot) that the
//     method lights above kLeakTolerance;
//   - acne: compared pixels fully lit in the reference whose surface faces every sample
//     (SoftShadowImage::faces_light: a lit receiver, not a terminator) that the method darkens
//     below 1 - kAcneTolerance;
//   - the reference's own noise (docs/smoothies.md#the-estimators-noise): each pixel's light is
//     the mean of K independent stratified verdicts, an unbiased estimate of the lit fraction p
//     of the light with variance at most p (1 - p) / K; reference_ci95 is the 95 % half-width
//     any one compared pixel has (reference_half_width at the fewest defined samples of a
//     compared pixel), reference_noise the mean over the compared pixels of
//     sqrt(light (1 - light) / K), the plug-in estimate of how far, in expectation, the
//     reference's sampling can move mean_error (|mean |m - r| - mean |m - p|| <= mean |r - p|);
//   - flicker, over a sequence of frames (a light orbit): per pixel compared in two
//     consecutive frames, the method's change of light |m' - m| against the reference's own
//     |r' - r|; reported are both means, their difference (the flicker the method adds) and the
//     mean |(m' - m) - (r' - r)| (change the reference does not make).
#include <cstdint>
#include <span>
#include <vector>

#include "pipeline/soft_reference.h"
#include "reference/soft_shadow_image.h"

namespace shadowcert {

// A method's light above this at a reference umbra pixel of a contact counts as a leak: it
// absorbs an 8-bit readback's quantisation (1/255) and a filter's float arithmetic, and is
// well below the light a viewer sees through a shadow (5% of full light).
inline constexpr float kLeakTolerance = 0.05f;
// A method's light below 1 - this at a fully lit, light-facing reference pixel counts as acne:
// the same margin as kLeakTolerance, from the other side.
inline constexpr float kAcneTolerance = 0.05f;

struct SoftShadowErrors {
  std::uint64_t compared = 0;
  std::uint64_t reference_only = 0;  // the reference has a light, the method covers nothing
  std::uint64_t method_only = 0;     // the method covers a pixel the reference has no light at
  double mean_error = 0.0;           // mean |method - reference| over the compared pixels
  double max_error = 0.0;
  double mean_signed_error = 0.0;    // mean (method - reference): > 0 too bright, < 0 too dark
  // Per reference region: the compared pixels there, and their mean |error|.
  std::uint64_t umbra = 0;
  double umbra_mean_error = 0.0;
  std::uint64_t penumbra = 0;
  double penumbra_mean_error = 0.0;
  std::uint64_t outside_penumbra = 0;  // umbra or fully lit
  double outside_penumbra_mean_error = 0.0;
  std::uint64_t contact = 0;  // compared contact pixels
  std::uint64_t leaks = 0;    // of those, lit above kLeakTolerance
  std::uint64_t lit_facing = 0;  // compared pixels fully lit and facing every sample
  std::uint64_t acne = 0;        // of those, darker than 1 - kAcneTolerance
  // Compared pixels whose surface does not face every sample (faces_light = 0): around its own
  // terminator, where the reference counts only occluders (on a closed caster the segment to a
  // sample behind the surface crosses the caster: shadowed) but the shadow map family's light
  // image is 0 wherever the surface turns away, so an open surface seen from behind differs.
  std::uint64_t turned_away = 0;
  double turned_away_mean_error = 0.0;
  // The reference's sampling noise (above): a pixel's 95 % half-width, whatever its p, and the
  // mean standard deviation bound over the compared pixels; 0 without a compared pixel, and for
  // a reference of a light without size (SoftReference::hard: exact).
  double reference_ci95 = 0.0;
  double reference_noise = 0.0;
};

// The 95 % (or `confidence`) half-width of a pixel of the soft reference whose light is the mean
// of K independent verdicts (one per stratum, so independent and in [0, 1]) whatever the lit
// fraction p: Hoeffding's bound, P(|r - p| >= t) <= 2 exp(-2 K t^2), solved for t:
// sqrt(ln(2 / (1 - confidence)) / (2 K)), 1.358 / sqrt(K) at 95 % (0.170 at K = 64). Throws
// std::invalid_argument("reference_half_width: ...") for K = 0 or a confidence outside (0, 1).
[[nodiscard]] double reference_half_width(std::uint32_t samples, double confidence = 0.95);

struct SoftFlicker {
  std::uint64_t frame_pairs = 0;
  std::uint64_t pixels = 0;  // pixel pairs compared, over every pair of consecutive frames
  double method_change = 0.0;     // mean |m' - m|
  double reference_change = 0.0;  // mean |r' - r|
  double excess = 0.0;            // method_change - reference_change
  double change_error = 0.0;      // mean |(m' - m) - (r' - r)|
};

// `light` (a method's light image, above) against `reference`. Throws std::invalid_argument
// ("compare_soft_shadow: ...") when light does not hold one value per pixel, the contact mask is
// neither empty (no contact pixel) nor one flag per pixel, or a value is NaN or above 1.
[[nodiscard]] SoftShadowErrors compare_soft_shadow(const SoftReference& reference, std::span<const float> light);

// The flicker of `frames` (a method's light images, one per frame) against `references` (the
// soft image of each frame, same order and size). Fewer than two frames: zero pairs. Throws
// std::invalid_argument("soft_flicker: ...") when the counts differ, a frame is not of its
// reference's size, or two references differ in size.
[[nodiscard]] SoftFlicker soft_flicker(std::span<const SoftShadowImage> references,
                                       std::span<const std::vector<float>> frames);

}  // namespace shadowcert
