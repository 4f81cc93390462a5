#pragma once
// The disk light of the exact soft reference (docs/smoothies.md#the-exact-soft-reference): a
// disk of radius R centred on a point light and facing a given point (the centre of the
// scene's bounds), replaced by K stratified sample points on it, each then an ordinary point
// light whose verdicts the exact image decides (reference/soft_shadow_image.h).
//
// Sampling: K = n x n strata of the unit square, one point per stratum at a deterministic
// jitter ((i + u) / n, (j + v) / n) with u, v in [0, 1) from SplitMix64 keyed by (seed, stratum)
// (scene/split_mix_random.h), mapped onto the unit disk by Shirley and Chiu's concentric map
// (1997), which keeps the strata's areas equal, then scaled by R in the disk's plane. The
// sample points are rounded once to doubles: they are the inputs whose verdicts are exact.
//
// Directional lights: R is the tangent of the disk's angular radius (as `render --method pcss
// --light-radius` reads it): the sample directions are l / |l| + R (x e1 + y e2) for the same
// disk points (x, y) and an orthonormal pair e1, e2 perpendicular to l, the disk of radius R at
// distance 1 along l: the limit of a disk light of radius R D facing the scene from a distance
// D along l as D grows (a sun of angular radius atan R).
//
// R = 0 gives one sample, the light itself, bit for bit, whatever K: the exact hard shadow.
#include <array>
#include <cstdint>
#include <vector>

#include "core/light.h"
#include "core/soup.h"

namespace shadowcert {

// The reference takes K >= 64 samples (docs/smoothies.md#the-exact-soft-reference): 8 x 8 strata.
inline constexpr std::uint32_t kReferenceDiskSamples = 64;
inline constexpr std::uint64_t kDefaultDiskSeed = 1;

// How a disk light is sampled.
struct DiskLightSampling {
  // >= 0 and finite. Point light: the disk's radius in world units. Directional light: the
  // tangent of its angular radius.
  double radius = 0.0;
  // K, a perfect square n x n >= 1 (64 is the reference's).
  std::uint32_t samples = kReferenceDiskSamples;
  std::uint64_t seed = kDefaultDiskSeed;  // the jitter's stream
};

// Shirley and Chiu's concentric map of the unit square [0, 1]^2 onto the unit disk: equal
// areas to equal areas, strata to compact pieces (the centre of the square to the centre).
[[nodiscard]] std::array<double, 2> concentric_disk_point(double u, double v);

// The centre of the box of the vertices that `soup`'s triangles use (core/box.h's
// used_vertex_box): the point a point light's disk faces. Throws std::invalid_argument
// ("scene_bounds_centre: ...") for an index out of range.
[[nodiscard]] Vec3 scene_bounds_centre(const Soup& soup);

// The sample lights of the disk around `light` (above): K of them in stratum order (row j of
// strata after row j - 1), or the light alone when sampling.radius == 0. `facing` is the point
// a point light's disk faces (its normal runs from the light to it); unread for a directional
// light, whose disk faces along its direction. Throws std::invalid_argument
// ("disk_light_samples: ...") for a light that is not defined, a radius that is negative or
// not finite, a sample count that is not a perfect square >= 1,
// or, with a radius > 0, a point light at `facing` (the disk's plane is then undefined).
[[nodiscard]] std::vector<Light> disk_light_samples(const Light& light, const Vec3& facing,
                                                    const DiskLightSampling& sampling);

}  // namespace shadowcert
