#include "reference/disk_light.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/box.h"
#include "core/portable_math.h"
#include "core/vector3.h"
#include "scene/split_mix_random.h"

namespace shadowcert {
namespace {

constexpr double kPi = 3.14159265358979323846;

// n with n * n == samples, or 0 when samples is no perfect square.
std::uint32_t strata_side(std::uint32_t samples) {
  auto n = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(samples)));
  while (std::uint64_t{n} * n > samples) --n;
  while (std::uint64_t{n + 1} * (n + 1) <= samples) ++n;
  return std::uint64_t{n} * n == samples ? n : 0;
}

// An orthonormal pair perpendicular to the unit vector `n`: e1 = n x (the axis along which n
// is smallest, the first on ties), e2 = n x e1. Axis-aligned n gives axis-aligned e1, e2.
std::array<Vec3, 2> plane_basis(const Vec3& n) {
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[axis])) axis = k;
  Vec3 a{0.0, 0.0, 0.0};
  a[axis] = 1.0;
  const Vec3 e1 = normalized(cross(n, a));
  return {e1, cross(n, e1)};
}

}  // namespace

std::array<double, 2> concentric_disk_point(double u, double v) {
  const double a = 2.0 * u - 1.0, b = 2.0 * v - 1.0;
  if (a == 0.0 && b == 0.0) return {0.0, 0.0};
  double r = 0.0, phi = 0.0;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = (kPi / 4.0) * (b / a);
  } else {
    r = b;
    phi = kPi / 2.0 - (kPi / 4.0) * (a / b);
  }
  return {r * portable::cos(phi), r * portable::sin(phi)};
}

Vec3 scene_bounds_centre(const Soup& soup) {
  require_indices_in_range(soup, "scene_bounds_centre");
  const Box box = used_vertex_box(soup);
  return {box.lo[0] / 2 + box.hi[0] / 2, box.lo[1] / 2 + box.hi[1] / 2, box.lo[2] / 2 + box.hi[2] / 2};
}

std::vector<Light> disk_light_samples(const Light& light, const Vec3& facing, const DiskLightSampling& sampling) {
  require_defined(light, "disk_light_samples");
  const double radius = sampling.radius;
  if (!std::isfinite(radius) || radius < 0.0)
    throw std::invalid_argument("disk_light_samples: the radius must be finite and >= 0, got " + std::to_string(radius));
  const double angle = sampling.angle_degrees;
  if (!std::isfinite(angle) || angle < 0.0 || !(angle < 90.0))
    throw std::invalid_argument("disk_light_samples: the angle must be in [0, 90) degrees, got " +
                                std::to_string(angle));
  const std::uint32_t side = strata_side(sampling.samples);
  if (side == 0)
    throw std::invalid_argument("disk_light_samples: the sample count must be a perfect square n x n >= 1, got " +
                                std::to_string(sampling.samples));
  // The disk's radius at distance 1 for a directional light, in world units for a point light.
  const double size = light.directional() ? portable::tan(angle * (kPi / 180.0)) : radius;
  if ((light.directional() ? angle : radius) == 0.0) return {light};

  const Vec3 l{light.position[0], light.position[1], light.position[2]};
  Vec3 axis{};  // the disk's normal: from the light to `facing`, or along a directional light
  bool ball = false;
  if (light.directional()) {
    axis = normalized(l);
  } else {
    for (double x : facing)
      if (!std::isfinite(x)) throw std::invalid_argument("disk_light_samples: the facing point must be finite");
    const Vec3 towards = difference(facing, l);
    ball = dot(towards, towards) == 0.0;
    if (!ball) axis = normalized(towards);
  }
  std::array<Vec3, 2> basis{};
  if (!ball) basis = plane_basis(axis);
  const auto& [e1, e2] = basis;
  const Vec3 centre = light.directional() ? axis : l;

  std::vector<Light> samples;
  samples.reserve(sampling.samples);
  for (std::uint32_t j = 0; j < side; ++j)
    for (std::uint32_t i = 0; i < side; ++i) {
      SplitMixRandom random{sampling.seed, std::uint64_t{j} * side + i};
      const double u = (i + random.unit()) / side;
      const double v = (j + random.unit()) / side;
      Light sample{{0.0, 0.0, 0.0, light.position[3]}};
      if (ball) {
        const Vec3 direction = sphere_point(u, v);
        const double r = size * portable::sin(ball_radial_angle(random.unit()));
        for (int k = 0; k < 3; ++k) sample.position[k] = centre[k] + r * direction[k];
      } else {
        const auto [x, y] = concentric_disk_point(u, v);
        for (int k = 0; k < 3; ++k) sample.position[k] = centre[k] + size * (x * e1[k] + y * e2[k]);
      }
      samples.push_back(sample);
    }
  return samples;
}

Vec3 sphere_point(double u, double v) {
  const double z = 1.0 - 2.0 * v;
  const double ring = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPi * u;
  return {ring * portable::cos(phi), ring * portable::sin(phi), z};
}

double ball_radial_angle(double w) {
  // F(t) = (2 t - sin 2t) / pi rises from 0 at t = 0 to 1 at t = pi / 2 (its derivative,
  // 4 sin^2 t / pi, is >= 0): bisection to double precision.
  const double target = std::clamp(w, 0.0, 1.0);
  double lo = 0.0, hi = kPi / 2.0;
  for (int step = 0; step < 64; ++step) {
    const double mid = 0.5 * (lo + hi);
    if ((2.0 * mid - portable::sin(2.0 * mid)) / kPi < target) lo = mid; else hi = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace shadowcert
