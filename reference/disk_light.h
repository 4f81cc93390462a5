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
// Directional lights: the disk's angular radius theta, in degrees (DiskLightSampling::
// angle_degrees, as `--light-angle` reads it): the sample directions are
// l / |l| + tan(theta) (x e1 + y e2) for the same disk points (x, y) and an orthonormal pair
// e1, e2 perpendicular to l, the disk of radius tan(theta) at distance 1 along l: the limit of
// a disk light of radius D tan(theta) facing the scene from a distance D along l as D grows (a
// sun of angular radius theta, the same whatever the scene's scale).
//
// A point light at the point its disk faces (a lamp at the centre of the scene's bounds) has no
// direction to face: its samples fill the ball of radius R around it with density proportional
// to 1 / sqrt(R^2 - r^2), whose projection along every direction is the uniform disk of radius
// R (the chord through the ball at offset s has length 2 sqrt(R^2 - s^2), and the integral of
// the density along it is pi, whatever s). So every receiver sees the disk of radius R facing
// it, the light the filters model, exactly for a parallel view and nearly from a distance well
// beyond R. Sample k's direction comes from its stratum through the equal-area map
// (z = 1 - 2v, phi = 2 pi u), its distance from a third jittered number w through the radial
// distribution: r = R sin(t) with (2 t - sin 2t) / pi = w (solved by bisection).
//
// R = 0 (theta = 0) gives one sample, the light itself, bit for bit, whatever K: the exact hard
// shadow.
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
  // A point light's disk radius R in world units, >= 0 and finite.
  double radius = 0.0;
  // K, a perfect square n x n >= 1 (64 is the reference's).
  std::uint32_t samples = kReferenceDiskSamples;
  std::uint64_t seed = kDefaultDiskSeed;  // the jitter's stream
  // A directional light's angular radius in degrees, in [0, 90) (a sun; 0: the hard shadow).
  double angle_degrees = 0.0;
};

// Shirley and Chiu's concentric map of the unit square [0, 1]^2 onto the unit disk: equal
// areas to equal areas, strata to compact pieces (the centre of the square to the centre).
[[nodiscard]] std::array<double, 2> concentric_disk_point(double u, double v);

// The unit vector of the equal-area map of [0, 1]^2 onto the sphere: z = 1 - 2v, phi = 2 pi u
// (Archimedes: equal areas of the square to equal areas of the sphere).
[[nodiscard]] Vec3 sphere_point(double u, double v);

// The angle t in [0, pi / 2] with (2 t - sin 2t) / pi = w (w clamped to [0, 1]): R sin(t) is then
// distributed as the distance from the centre of a point of the ball of radius R drawn with
// density proportional to 1 / sqrt(R^2 - r^2) (above), for w uniform in [0, 1].
[[nodiscard]] double ball_radial_angle(double w);

// The centre of the box of the vertices that `soup`'s triangles use (core/box.h's
// used_vertex_box): the point a point light's disk faces. Throws std::invalid_argument
// ("scene_bounds_centre: ...") for an index out of range.
[[nodiscard]] Vec3 scene_bounds_centre(const Soup& soup);

// The sample lights of the disk around `light` (above): K of them in stratum order (row j of
// strata after row j - 1), or the light alone when its size (a point light's sampling.radius,
// a directional light's sampling.angle_degrees) is 0. `facing` is the point a point light's
// disk faces (its normal runs from the light to it; a light at `facing` samples the ball
// above); unread for a directional light, whose disk faces along its direction. Throws
// std::invalid_argument ("disk_light_samples: ...") for a light that is not defined, a radius
// that is negative or not finite, an angle outside [0, 90) degrees, a facing point that is not
// finite, or a sample count that is not a perfect square >= 1.
[[nodiscard]] std::vector<Light> disk_light_samples(const Light& light, const Vec3& facing,
                                                    const DiskLightSampling& sampling);

}  // namespace shadowcert
