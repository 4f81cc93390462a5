// soft_shadow_image of reference/soft_shadow_image.h: the sample lights go to exact_image as
// its lights, as many per call as SoftShadowOptions::batch_bytes allows, and each pixel counts its
// defined and lit verdicts over them.
#include "reference/soft_shadow_image.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

namespace shadowcert {
namespace {

using Clock = std::chrono::steady_clock;

// The progress of the samples' counts across the batches: a sample's counts stage begins with
// a report of done 0 (exact_image's Progress), which starts the next sample.
constexpr std::uint64_t kSampleSteps = 1024;

// Samples per exact_image call: the budget over kBatchBytesPerSampleAndTriangle per triangle and
// sample, at least one.
std::size_t batch_size(std::uint64_t budget, std::size_t triangles, std::size_t samples) {
  const std::uint64_t per_sample = kBatchBytesPerSampleAndTriangle * std::max<std::uint64_t>(1, triangles);
  return static_cast<std::size_t>(std::clamp<std::uint64_t>(budget / per_sample, 1, samples));
}

}  // namespace

SoftRegion SoftShadowImage::region(std::size_t pixel) const {
  if (hit_triangles[pixel] == kNoHit) return SoftRegion::none;
  const std::uint32_t defined = defined_samples[pixel], lit = lit_samples[pixel];
  if (defined == 0) return SoftRegion::undefined;
  if (lit == 0) return SoftRegion::umbra;
  return lit == defined ? SoftRegion::lit : SoftRegion::penumbra;
}

SoftShadowImage soft_shadow_image(const Soup& soup, std::span<const Light> samples, const Camera& camera,
                                  const SoftShadowOptions& options) {
  const auto start = Clock::now();
  if (samples.empty()) throw std::invalid_argument("soft_shadow_image: no sample light");
  SoftShadowImage image;
  image.samples.assign(samples.begin(), samples.end());
  image.width = camera.width;
  image.height = camera.height;
  const std::size_t pixels = image.pixels();
  image.defined_samples.assign(pixels, 0);
  image.lit_samples.assign(pixels, 0);
  std::vector<std::uint8_t> behind(pixels, 0);  // some sample is not strictly in front of the hit plane

  // Progress: the first call's hits as they come, then the samples' counts.
  std::size_t batch_first = 0;       // the first sample of the current call
  std::size_t sample_in_batch = 0;   // samples of this call whose counts have begun
  std::size_t batch_length = 0;      // samples in this call
  ExactImageOptions exact_options;
  exact_options.casts = options.casts;
  exact_options.footprints = false;  // only the centres' verdicts are read
  exact_options.light_images = false;  // and only their sums over the samples
  if (options.progress) {
    const std::uint64_t total = samples.size() * kSampleSteps;
    exact_options.progress = [&, total](std::string_view stage, std::uint64_t done, std::uint64_t stage_total) {
      if (stage == kAllLightsCounts) {  // every sample of this call at once
        const std::uint64_t within = stage_total == 0 ? batch_length * kSampleSteps
                                                      : done * batch_length * kSampleSteps / stage_total;
        options.progress("samples", batch_first * kSampleSteps + within, total);
        return;
      }
      if (stage != "counts") {
        if (batch_first == 0) options.progress(stage, done, stage_total);
        return;
      }
      if (done == 0) ++sample_in_batch;
      const std::uint64_t within = stage_total == 0 ? kSampleSteps : done * kSampleSteps / stage_total;
      options.progress("samples", (batch_first + sample_in_batch - 1) * kSampleSteps + within, total);
    };
  }

  const std::size_t batch = batch_size(options.batch_bytes, soup.triangles.size(), samples.size());
  for (; batch_first < samples.size(); batch_first += batch) {
    sample_in_batch = 0;
    const std::span<const Light> lights = samples.subspan(batch_first, std::min(batch, samples.size() - batch_first));
    batch_length = lights.size();
    const ExactImage exact = exact_image(soup, lights, camera, exact_options);
    if (image.hit_triangles.empty()) image.hit_triangles = exact.hit_triangles;
    image.stats.exact_images += 1;
    image.stats.tree_seconds += exact.stats.tree_seconds;
    image.stats.hit_seconds += exact.stats.hit_seconds;
    image.stats.count_seconds += exact.stats.count_seconds;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pixels, 4096), [&](const auto& range) {
      for (std::size_t p = range.begin(); p != range.end(); ++p) {
        image.defined_samples[p] += exact.tally.defined[p];
        image.lit_samples[p] += exact.tally.lit[p];
        behind[p] |= exact.tally.terminator[p];
      }
    });
  }
  // exact_image marks the terminator of every countable hit, defined or not: a sample whose
  // count is undefined at a pixel with some defined sample may still be behind its plane.
  image.light.resize(pixels);
  image.faces_light.resize(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    const std::uint32_t defined = image.defined_samples[p];
    image.light[p] = defined == 0 ? kNoLight
                                  : static_cast<float>(static_cast<double>(image.lit_samples[p]) / defined);
    image.faces_light[p] = defined > 0 && behind[p] == 0 ? 1 : 0;
  }
  image.stats.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return image;
}

SoftShadowImage disk_light_shadow_image(const Soup& soup, const Light& light, const DiskLightSampling& sampling,
                                        const Camera& camera, const SoftShadowOptions& options) {
  const Vec3 facing = light.directional() || sampling.radius == 0.0 ? Vec3{} : scene_bounds_centre(soup);
  const std::vector<Light> samples = disk_light_samples(light, facing, sampling);
  return soft_shadow_image(soup, samples, camera, options);
}

}  // namespace shadowcert
