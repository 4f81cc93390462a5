#include "pipeline/soft_shadow_comparison.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace shadowcert {
namespace {

// A running mean of |error| over a set of pixels.
struct Mean {
  std::uint64_t n = 0;
  double sum = 0.0;
  void add(double x) {
    ++n;
    sum += x;
  }
  [[nodiscard]] double value() const { return n == 0 ? 0.0 : sum / static_cast<double>(n); }
};

void require_light_values(std::span<const float> light, const char* function) {
  for (std::size_t p = 0; p < light.size(); ++p)
    if (std::isnan(light[p]) || light[p] > 1.0f)
      throw std::invalid_argument(std::string(function) + ": pixel " + std::to_string(p) +
                                  " has a light that is NaN or above 1");
}

}  // namespace

double reference_half_width(std::uint32_t samples, double confidence) {
  if (samples == 0) throw std::invalid_argument("reference_half_width: no sample");
  if (!(confidence > 0.0) || !(confidence < 1.0))
    throw std::invalid_argument("reference_half_width: the confidence must be in (0, 1), got " +
                                std::to_string(confidence));
  return std::sqrt(std::log(2.0 / (1.0 - confidence)) / (2.0 * samples));
}

SoftShadowErrors compare_soft_shadow(const SoftReference& reference, std::span<const float> light) {
  const SoftShadowImage& image = reference.image;
  const std::size_t pixels = image.pixels();
  if (light.size() != pixels)
    throw std::invalid_argument("compare_soft_shadow: the light image has " + std::to_string(light.size()) +
                                " values for " + std::to_string(pixels) + " pixels");
  if (!reference.contact.empty() && reference.contact.size() != pixels)
    throw std::invalid_argument("compare_soft_shadow: the contact mask is not one flag per pixel");
  require_light_values(light, "compare_soft_shadow");

  if (image.defined_samples.size() != pixels)
    throw std::invalid_argument("compare_soft_shadow: the reference has no defined-sample count per pixel");
  SoftShadowErrors e;
  Mean all, umbra, penumbra, outside, away, noise;
  std::uint32_t fewest_samples = 0;  // the fewest defined samples of a compared pixel
  double signed_sum = 0.0;
  for (std::size_t p = 0; p < pixels; ++p) {
    const float truth = image.light[p];
    const bool has_reference = truth >= 0.0f, covered = light[p] >= 0.0f;
    if (has_reference != covered) {
      (has_reference ? e.reference_only : e.method_only) += 1;
      continue;
    }
    if (!has_reference) continue;
    const double error = static_cast<double>(light[p]) - truth;
    const double size = std::abs(error);
    all.add(size);
    signed_sum += error;
    const std::uint32_t k = image.defined_samples[p];
    fewest_samples = fewest_samples == 0 ? k : std::min(fewest_samples, k);
    noise.add(std::sqrt(static_cast<double>(truth) * (1.0 - truth) / k));
    e.max_error = std::max(e.max_error, size);
    if (image.faces_light[p] == 0) away.add(size);
    switch (image.region(p)) {
      case SoftRegion::umbra:
        umbra.add(size);
        outside.add(size);
        if (!reference.contact.empty() && reference.contact[p] != 0) {
          e.contact += 1;
          e.leaks += light[p] > kLeakTolerance ? 1 : 0;
        }
        break;
      case SoftRegion::lit:
        outside.add(size);
        if (image.faces_light[p] != 0) {
          e.lit_facing += 1;
          e.acne += light[p] < 1.0f - kAcneTolerance ? 1 : 0;
        }
        break;
      case SoftRegion::penumbra:
        penumbra.add(size);
        break;
      case SoftRegion::none:
      case SoftRegion::undefined:
        break;  // no light: not reached
    }
  }
  e.compared = all.n;
  e.mean_error = all.value();
  e.mean_signed_error = all.n == 0 ? 0.0 : signed_sum / static_cast<double>(all.n);
  e.umbra = umbra.n;
  e.umbra_mean_error = umbra.value();
  e.penumbra = penumbra.n;
  e.penumbra_mean_error = penumbra.value();
  e.outside_penumbra = outside.n;
  e.outside_penumbra_mean_error = outside.value();
  e.turned_away = away.n;
  e.turned_away_mean_error = away.value();
  // A light without size is its one sample: every pixel exact, no noise.
  e.reference_ci95 = fewest_samples == 0 || reference.hard ? 0.0 : reference_half_width(fewest_samples);
  e.reference_noise = reference.hard ? 0.0 : noise.value();
  return e;
}

SoftFlicker soft_flicker(std::span<const SoftShadowImage> references, std::span<const std::vector<float>> frames) {
  if (references.size() != frames.size())
    throw std::invalid_argument("soft_flicker: " + std::to_string(frames.size()) + " frames for " +
                                std::to_string(references.size()) + " references");
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (references[f].pixels() != references.front().pixels() || references[f].width != references.front().width)
      throw std::invalid_argument("soft_flicker: reference " + std::to_string(f) + " differs in size from the first");
    if (frames[f].size() != references[f].pixels())
      throw std::invalid_argument("soft_flicker: frame " + std::to_string(f) + " is not of its reference's size");
    require_light_values(frames[f], "soft_flicker");
  }
  SoftFlicker flicker;
  Mean method, truth, difference;
  for (std::size_t f = 0; f + 1 < frames.size(); ++f) {
    flicker.frame_pairs += 1;
    const std::vector<float>&m0 = frames[f], &m1 = frames[f + 1];
    const std::vector<float>&r0 = references[f].light, &r1 = references[f + 1].light;
    for (std::size_t p = 0; p < m0.size(); ++p) {
      if (m0[p] < 0.0f || m1[p] < 0.0f || r0[p] < 0.0f || r1[p] < 0.0f) continue;
      const double dm = static_cast<double>(m1[p]) - m0[p], dr = static_cast<double>(r1[p]) - r0[p];
      method.add(std::abs(dm));
      truth.add(std::abs(dr));
      difference.add(std::abs(dm - dr));
    }
  }
  flicker.pixels = method.n;
  flicker.method_change = method.value();
  flicker.reference_change = truth.value();
  flicker.excess = flicker.method_change - flicker.reference_change;
  flicker.change_error = difference.value();
  return flicker;
}

}  // namespace shadowcert
