#pragma once
// The exact soft reference (docs/smoothies.md#the-exact-soft-reference): how much of
// an area light reaches each receiver pixel, as the mean of exact hard verdicts over sample
// lights on it. Fake soft shadows (PCF, PCSS, smoothies) are measured against it
// (pipeline/soft_shadow_comparison.h).
//
// Per pixel, the centre ray's first exact hit P (reference/exact_image.h, the GL path's own
// rays) and, for every sample light, the exact verdict at P of the pixel protocol
// (docs/definitions.md#pixel-protocol): lit iff n(P) = 0, shadowed iff n(P) > 0, undefined
// where n(P) is (a zero sign: the segment P -> sample touches a casting triangle, or the hit
// itself is degenerate). The pixel's light is the mean over the samples whose verdict is
// defined: lit samples / defined samples; a pixel with no defined sample has no light. As in
// the hard protocol, the hit triangle never shadows its own point: a surface turned away from
// a sample is lit by it unless something else occludes (what a renderer's N.L shading adds is
// no part of the shadow); `faces_light` says where every sample is strictly in front of the
// hit triangle (on the eye's side of its plane).
//
// The samples are lights like any other: every verdict is an exact sign on the input doubles,
// so the image is invariant under vertex relabelling, face reversal, and an exact translation of
// scene, camera and samples. Only where the samples come from is approximate: a disk light's
// points are rounded to doubles once (reference/disk_light.h).
//
// Cost: one exact image with all the samples as its lights, centre rays only
// (ExactImageOptions::footprints false: the first hits shared; light_images false: only each
// pixel's sums over the samples), in batches when the samples' data would exceed
// SoftShadowOptions::batch_bytes. Its samples are counted together at each
// hit point P (reference/exact_image.cpp, beam_counts): one box-tree query along the cone from P
// to the samples, P's side of each candidate's plane once, and each candidate edge's plane
// through P deciding all samples at once where a filter can; the verdicts are each sample's own.
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "reference/disk_light.h"
#include "reference/exact_image.h"

namespace shadowcert {

// SoftShadowImage::light where no light is defined: no hit, or no sample with a verdict. The
// same convention as a renderer's light image (a negative value: no receiver there).
inline constexpr float kNoLight = -1.0f;

// One exact_image call holds, per sample, each triangle's side of it twice (the lights' s(t)
// and the beam's copy in sample order; reference/exact_image.cpp): 2 bytes per triangle and
// sample. The per-pixel memory does not grow with the samples (ExactImageOptions::light_images
// false: each pixel's sums only). More samples than fit in this budget are imaged in several
// calls, each of which traces the first hits again and queries the box tree again at every hit
// point. 384 MiB holds 1,600 samples of a 124K-triangle mesh (ogre) and 48 of 4M triangles.
inline constexpr std::uint64_t kBatchBytesPerSampleAndTriangle = 2;
inline constexpr std::uint64_t kSoftShadowBatchBytes = std::uint64_t{384} << 20;

// What the samples make of a pixel.
enum class SoftRegion : std::uint8_t {
  none,       // the centre ray meets nothing
  undefined,  // it hits, but no sample's verdict is defined there (a degenerate hit, or every
              // segment touches a casting triangle)
  umbra,      // every defined sample is shadowed
  penumbra,   // some defined samples are lit, some shadowed
  lit,        // every defined sample is lit
};

struct SoftShadowStats {
  std::uint64_t exact_images = 0;  // calls of exact_image (batches)
  double tree_seconds = 0.0;       // the exact images' stages, summed over the batches
  double hit_seconds = 0.0;
  double count_seconds = 0.0;
  double seconds = 0.0;            // all of it
};

struct SoftShadowImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<Light> samples;  // the sample lights, in the order their verdicts were counted
  // Per pixel, row-major, row 0 at the TOP (as gpu/image.h):
  std::vector<std::uint32_t> hit_triangles;    // the centre ray's first hit, or kNoHit (exact_image)
  std::vector<std::uint32_t> defined_samples;  // samples whose verdict is defined
  std::vector<std::uint32_t> lit_samples;      // of those, the lit ones
  std::vector<float> light;                    // lit / defined in [0, 1], or kNoLight
  // 1 where some sample's verdict is defined and every sample lies strictly on the eye's side
  // of the hit triangle's plane (none is past its terminator, docs/definitions.md#pixel-protocol).
  std::vector<std::uint8_t> faces_light;
  SoftShadowStats stats;

  [[nodiscard]] std::size_t pixels() const { return std::size_t{width} * height; }
  // A receiver pixel: the centre ray hits a triangle.
  [[nodiscard]] bool receiver(std::size_t pixel) const { return hit_triangles[pixel] != kNoHit; }
  [[nodiscard]] SoftRegion region(std::size_t pixel) const;
};

struct SoftShadowOptions {
  // Called as work advances, from worker threads but never two at once: "hits" (the first
  // exact image's, as exact_image reports them), then "samples", whose total is the number of
  // samples times 1024 and whose progress runs through each sample's counts. Empty: no reports.
  std::function<void(std::string_view stage, std::uint64_t done, std::uint64_t total)> progress;
  // Which triangles cast (ExactImageOptions::casts): one flag per soup triangle, or empty (all).
  std::vector<std::uint8_t> casts;
  // The budget of one exact_image call's per-sample data, in bytes (kBatchBytesPerSampleAndTriangle
  // per triangle and sample; at least one sample per call whatever it is): the image does not
  // depend on it.
  std::uint64_t batch_bytes = kSoftShadowBatchBytes;
};

// The soft image of `soup` (every triangle receives; those options.casts allows cast) for
// `camera` and the given sample lights. Throws std::invalid_argument("soft_shadow_image: ...")
// for no sample, and what exact_image throws (an index out of range, a non-finite coordinate,
// a light that is not defined, a degenerate camera, casts of the wrong size).
[[nodiscard]] SoftShadowImage soft_shadow_image(const Soup& soup, std::span<const Light> samples, const Camera& camera,
                                                const SoftShadowOptions& options = {});

// The reference (docs/smoothies.md#the-exact-soft-reference): the disk light around `light`
// (reference/disk_light.h) facing the centre of the soup's bounds (scene_bounds_centre; a point
// light at that centre: the ball around it), or about a directional light, sampled by
// `sampling`, imaged by soft_shadow_image. A light without size (a point light's
// sampling.radius or a directional light's sampling.angle_degrees 0) gives the exact hard
// shadow (one sample). Throws what disk_light_samples and soft_shadow_image throw.
[[nodiscard]] SoftShadowImage disk_light_shadow_image(const Soup& soup, const Light& light,
                                                      const DiskLightSampling& sampling, const Camera& camera,
                                                      const SoftShadowOptions& options = {});

}  // namespace shadowcert
