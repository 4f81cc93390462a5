#pragma once
// Float ray-traced shadows through Embree (docs/ray-tracing.md): what a user's ray tracer
// answers for the question the exact image answers exactly (reference/exact_image.h), traced
// through the very same pixel rays (core/pixel_ray.h), so that the two can be compared pixel by
// pixel and timed on the same work.
//
// Per pixel, the centre ray's first hit (Embree, float vertices and rays) gives the triangle and
// the hit point P = o + t d (o, d the float ray, t Embree's distance, evaluated in double); per
// light one shadow ray from P towards the light (a point light: the segment P -> l, t in
// [tnear, 1 - tnear]; a directional one: the ray along l, t >= tnear) asks Embree whether any
// CASTING triangle occludes it (rtcOccluded). Lit: the centre ray hits and the shadow ray is not occluded.
// Triangles that only receive (casts[t] == 0, as ExactImageOptions::casts) are seen and hit but
// never occlude: the shadow rays are traced in a second scene of the casting triangles alone.
//
// Self-hits: the shadow ray starts on the hit triangle, where float rounding of P and of the
// vertices puts it a little above or below that triangle's plane; it starts a small distance
// along its direction (kShadowRayOffset and kHitPointErrorUlps below), and a point light's ray
// ends that distance short of the light (a light on a triangle must not shadow itself). A float
// ray tracer's usual answer: it leaks light where a caster touches its receiver within that
// distance, and it still self-shadows ("acne") where the light grazes the surface. The exact
// image has no such tolerance (the hit triangle is excluded exactly): that difference is part
// of rt's measured error.
//
// Soft shadows: K sample lights (the caller's; the exact soft reference's own samples,
// reference/disk_light.h's disk_light_samples, so both integrate the same points) each traced as
// above, the pixel's light lit samples / K.
//
// Parallel over rows with TBB, in an arena of `threads` threads (the BVH builds run there too),
// in packets of `packet` rays (rtcIntersect4/8/16, rtcOccluded4/8/16; 1: one ray at a time).
//
//   raytrace::RayTracedImageOptions options;
//   options.mode = raytrace::BuildMode::robust;
//   raytrace::RayTracedImage rt = raytrace::ray_traced_image(soup, lights, camera, options);
//   rt.lit[0][p] == 255   // pixel p lit by light 0; rt.hit_triangles[p] the soup triangle seen
#include <cstdint>
#include <span>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "raytrace/embree_scene.h"

namespace shadowcert::raytrace {

// hit_triangles where the centre ray meets nothing: the value of reference/exact_image.h's kNoHit.
inline constexpr std::uint32_t kMissed = 0xFFFFFFFFu;
// RayTracedSoftImage::light where the centre ray meets nothing (as reference/soft_shadow_image.h's kNoLight).
inline constexpr float kNoLight = -1.0f;

// The shadow ray's start is the sum of two named tolerances (world units along the ray; a point
// light's ray stops the same distance short of the light):
//   kShadowRayOffset x the diagonal of the soup's bounding box: the vertices' rounding to float
//     (half an ulp of their coordinates) seen at the scene's own scale, with a wide margin: the
//     ray rises offset x sin(angle) off the plane, so it clears a few 1e-7 of the extent where the
//     light is more than ~0.06 degrees above the surface. A caster nearer than 1e-4 of the extent
//     to P is missed (a leak at contact): a tenth of a pixel where the scene spans 1000 pixels.
//   kHitPointErrorUlps float ulps of (the distance the centre ray travelled to P + P's largest
//     coordinate): the error of P itself, from Embree's float hit distance (relative error a few
//     ulps: P moves a few ulps of the distance off the plane) and from P's rounding to the float
//     origin of the shadow ray. It dominates where the eye is far from a small scene
//     (data/scenes/hard/scale_1e-6.json: the eye 2,000 scene sizes away).
inline constexpr double kShadowRayOffset = 1e-4;
inline constexpr double kHitPointErrorUlps = 16.0;

struct RayTracedImageOptions {
  BuildMode mode = BuildMode::fast;
  // Which triangles cast: one flag per soup triangle, 0 for a triangle that only receives;
  // empty: every triangle casts (ExactImageOptions::casts).
  std::vector<std::uint8_t> casts;
  // The TBB arena's threads for the builds and the tracing; 0: TBB's default (every core).
  unsigned threads = 0;
  // Rays per Embree call: 1 (rtcIntersect1/rtcOccluded1), 4, 8 or 16 (packets along a row).
  unsigned packet = 8;
  // Also trace the (width + 1) x (height + 1) pixel-corner rays' first hits (the exact image
  // traces them for its footprints): for benchmarks that time the same rays as exact_image.
  bool corner_rays = false;
  // The scene's part of the shadow ray's start, a fraction of the bounding box's diagonal
  // (kShadowRayOffset), >= 0; the hit point's part (kHitPointErrorUlps) is added to it.
  double shadow_ray_offset = kShadowRayOffset;
};

struct RayTracedStats {
  double build_seconds = 0.0;  // the BVHs: every triangle's, and the casting ones' when some only receive
  double trace_seconds = 0.0;  // every ray: first hits (centres, corners) and shadow rays
  double seconds = 0.0;        // all of it (checks, the Embree device, builds, tracing)
  std::uint64_t rays = 0;         // first-hit rays traced (centres, corners)
  std::uint64_t shadow_rays = 0;  // shadow rays traced (one per hit pixel and light or sample)
};

struct RayTracedImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  // Per pixel, row-major, row 0 at the TOP (as reference/exact_image.h): the centre ray's first
  // hit, a soup triangle index, or kMissed.
  std::vector<std::uint32_t> hit_triangles;
  // With RayTracedImageOptions::corner_rays: corner (i, r) at i + r (width + 1), the same; else empty.
  std::vector<std::uint32_t> corner_hits;
  // Per light, in the given order, per pixel: 255 where the centre ray hits and the shadow ray
  // is not occluded, else 0 (reference/exact_image.h's ExactLightImage::lit convention).
  std::vector<std::vector<std::uint8_t>> lit;
  RayTracedStats stats;
};

struct RayTracedSoftImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t samples = 0;                 // K
  std::vector<std::uint32_t> hit_triangles;  // as RayTracedImage's
  std::vector<std::uint32_t> lit_samples;    // per pixel, the samples whose shadow ray is not occluded
  std::vector<float> light;                  // lit_samples / K, or kNoLight where the centre ray misses
  RayTracedStats stats;
};

// The hard shadows of `soup` (every triangle receives; those options.casts allows cast) for
// `camera` and each of `lights`. Throws std::invalid_argument("ray_traced_image: ...") for a
// vertex index out of range, a non-finite coordinate (or one beyond float's range), a light
// that is not defined (core/light.h), a degenerate camera (core/pixel_ray.h), casts neither
// empty nor one flag per triangle, a packet size not in {1, 4, 8, 16} or a negative or
// non-finite offset; EmbreeError with Embree's message when Embree fails.
[[nodiscard]] RayTracedImage ray_traced_image(const Soup& soup, std::span<const Light> lights, const Camera& camera,
                                              const RayTracedImageOptions& options = {});

// The soft shadows of `soup` for `camera` and the K = samples.size() sample lights (an area
// light's points: reference/disk_light.h's disk_light_samples). Throws as ray_traced_image,
// naming "ray_traced_soft_image", and for no sample.
[[nodiscard]] RayTracedSoftImage ray_traced_soft_image(const Soup& soup, std::span<const Light> samples,
                                                       const Camera& camera, const RayTracedImageOptions& options = {});

}  // namespace shadowcert::raytrace
