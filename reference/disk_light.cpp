#include "reference/disk_light.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/box.h"
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
  return {r * std::cos(phi), r * std::sin(phi)};
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
  const std::uint32_t side = strata_side(sampling.samples);
  if (side == 0)
    throw std::invalid_argument("disk_light_samples: the sample count must be a perfect square n x n >= 1, got " +
                                std::to_string(sampling.samples));
  if (radius == 0.0) return {light};

  const Vec3 l{light.position[0], light.position[1], light.position[2]};
  Vec3 axis{};  // the disk's normal: from the light to `facing`, or along a directional light
  if (light.directional()) {
    axis = normalized(l);
  } else {
    for (double x : facing)
      if (!std::isfinite(x)) throw std::invalid_argument("disk_light_samples: the facing point must be finite");
    const Vec3 towards = difference(facing, l);
    if (dot(towards, towards) == 0.0)
      throw std::invalid_argument("disk_light_samples: the light is at the point its disk faces: no disk plane");
    axis = normalized(towards);
  }
  const auto [e1, e2] = plane_basis(axis);
  const Vec3 centre = light.directional() ? axis : l;

  std::vector<Light> samples;
  samples.reserve(sampling.samples);
  for (std::uint32_t j = 0; j < side; ++j)
    for (std::uint32_t i = 0; i < side; ++i) {
      SplitMixRandom random{sampling.seed, std::uint64_t{j} * side + i};
      const double u = (i + random.unit()) / side;
      const double v = (j + random.unit()) / side;
      const auto [x, y] = concentric_disk_point(u, v);
      Light sample{{0.0, 0.0, 0.0, light.position[3]}};
      for (int k = 0; k < 3; ++k) sample.position[k] = centre[k] + radius * (x * e1[k] + y * e2[k]);
      samples.push_back(sample);
    }
  return samples;
}

}  // namespace shadowcert
