#pragma once
// The exact soft reference of a scene (docs/smoothies.md#the-exact-soft-reference): the disk
// light around one of its lights imaged by exact verdicts over K samples (reference/
// soft_shadow_image.h: per pixel an unbiased estimate of the light, whose noise
// pipeline/soft_shadow_comparison.h reports, docs/smoothies.md#the-estimators-noise), plus the
// pixels where the shadow's caster meets its receiver (`contact`), which the leak figure of
// pipeline/soft_shadow_comparison.h looks at. What `shadowcert soft` computes, and what `diff`
// compares the shadow map family's light images with:
//
//   const SoftReference reference = soft_reference(scene, 0, {{radius, 64, seed}});
//   const SoftShadowErrors e = compare_soft_shadow(reference, frame_light);  // one call per method
//
// Contact (approximate: it chooses which pixels one figure covers, and decides no verdict):
// a pixel is a contact pixel when the reference puts it in the umbra, its hit surface faces
// every sample (SoftShadowImage::faces_light), and its hit point P lies within
// `contact_pixels` pixel widths at P (2 D tan(fov_y / 2) / height world units, D P's view
// depth) of a casting triangle that is not the hit triangle and does not lie in its plane.
// Where a caster stands on a receiver the gap between them closes and so does the penumbra:
// those umbra pixels must stay dark right up to the caster, and a shadow map's depth bias
// (peter-panning), a filter's blur or a smoothie's alpha let light in there first. P is the
// centre ray's hit computed in double, the distances in double: a rounding moves a pixel at
// the contact distance in or out, never an exact verdict.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/camera.h"
#include "core/scene.h"
#include "core/soup.h"
#include "reference/disk_light.h"
#include "reference/soft_shadow_image.h"

namespace shadowcert {

// The contact distance in pixel widths at the hit point: a few pixels, so that a method's error
// at the foot of a caster is seen on any image size, and far below a typical penumbra (the
// penumbra at a height g above the receiver is about R g / (H - g) wide, H the light's height).
inline constexpr double kContactPixels = 4.0;

struct SoftReferenceOptions {
  DiskLightSampling sampling;               // radius, K, seed (reference/disk_light.h)
  double contact_pixels = kContactPixels;   // >= 0
  bool progress = false;                    // a progress bar on stderr
};

struct SoftReference {
  SoftShadowImage image;
  // The light has no size (a point light's radius or a directional light's angle 0): its one
  // sample is the light itself, and every pixel's light is exact, with no sampling noise.
  bool hard = false;
  std::vector<std::uint8_t> contact;  // per pixel: 1 at a contact pixel (above)
  double contact_seconds = 0.0;
};

// The contact pixels of `image` (soft_shadow_image of `soup`, those `casts` allows casting, all
// when empty, at `camera`). Throws std::invalid_argument("contact_pixels: ...") when the image is
// not of the camera's size, casts is neither empty nor one flag per triangle, contact_pixels is
// negative or not finite, or a hit triangle is out of range.
[[nodiscard]] std::vector<std::uint8_t> contact_pixels(const Soup& soup, std::span<const std::uint8_t> casts,
                                                       const Camera& camera, const SoftShadowImage& image,
                                                       double contact_pixels = kContactPixels);

// The soft reference of light number `light` of `scene` at its camera (every mesh receives, the
// meshes that cast cast; world space, as the exact image of `diff`): disk_light_shadow_image
// with options.sampling, then the contact pixels. Throws std::invalid_argument
// ("soft_reference: ...") for a light out of range, and what disk_light_shadow_image and
// contact_pixels throw.
[[nodiscard]] SoftReference soft_reference(const Scene& scene, std::size_t light, const SoftReferenceOptions& options);

}  // namespace shadowcert
