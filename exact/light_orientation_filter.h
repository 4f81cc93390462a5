#pragma once
// Internal to exact/: the first, semi-static stage of the exact predicate of
// exact/light_orientation.h, inline so that loops over a whole soup (exact/edge_multiplicity.cpp)
// pay neither a call nor an FPU rounding-mode switch for the overwhelming majority of
// triangles. Plain doubles only (no CGAL in headers, docs/development.md).
//
// It evaluates det[b - a, c - a, l - w a] (docs/definitions.md#orientation) in doubles with round-to-nearest and
// accepts the sign only when |det| exceeds a *certified* bound on the total rounding error of
// that very evaluation, the differences b - a, c - a, l - a included. This is not a tolerance:
// nothing is ever decided inside the bound; the caller then runs the interval and exact stages.
// The bound and the expression are CGAL's static filter for Orientation_3
// (CGAL/Filtered_kernel/internal/Static_filters/Orientation_3.h, derived by CGAL's FPG tool),
// so for w = 1 this stage answers exactly where CGAL's `orientation` would. For w = 0 the third
// row is l itself, an input with no rounding at all, so the same bound still holds (it only
// over-estimates the error).
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "core/sign.h"
#include "core/soup.h"

namespace shadowcert::detail {

// Certified relative bound of CGAL's Orientation_3 static filter for the determinant of three
// rounded differences of doubles (valid in the magnitude range checked below).
inline constexpr double kOrientationErrorFactor = 5.1107127829973299e-15;
// Below this a product of three column maxima could underflow (cbrt(min_double / factor)),
// above the other the determinant could overflow (cbrt(max_double / 4)): CGAL's guards.
inline constexpr double kOrientationUnderflowGuard = 1e-97;
inline constexpr double kOrientationOverflowGuard = 1e102;

// `light` is {x, y, z, w} with w in {0, 1} (validated by the caller).
// Returns the sign when certified, std::nullopt when the later stages must decide.
[[nodiscard]] inline std::optional<Sign> semi_static_light_orientation(const Vec3& a, const Vec3& b, const Vec3& c,
                                                                       const std::array<double, 4>& light) {
  const double x0 = b[0] - a[0], x1 = b[1] - a[1], x2 = b[2] - a[2];
  const double y0 = c[0] - a[0], y1 = c[1] - a[1], y2 = c[2] - a[2];
  const bool point = light[3] != 0.0;
  const double z0 = point ? light[0] - a[0] : light[0];
  const double z1 = point ? light[1] - a[1] : light[1];
  const double z2 = point ? light[2] - a[2] : light[2];

  double max0 = std::max({std::fabs(x0), std::fabs(y0), std::fabs(z0)});
  double max1 = std::max({std::fabs(x1), std::fabs(y1), std::fabs(z1)});
  double max2 = std::max({std::fabs(x2), std::fabs(y2), std::fabs(z2)});

  // CGAL::determinant(x0, x1, x2, y0, y1, y2, z0, z1, z2), operation for operation.
  const double m01 = x0 * y1 - y0 * x1;
  const double m02 = x0 * z1 - z0 * x1;
  const double m12 = y0 * z1 - z0 * y1;
  const double det = m01 * z2 - m02 * y2 + m12 * x2;
  const double bound = kOrientationErrorFactor * max0 * max1 * max2;

  const double smallest = std::min({max0, max1, max2});
  const double largest = std::max({max0, max1, max2});
  if (smallest < kOrientationUnderflowGuard) {
    // A whole coordinate column is exactly zero (a difference of doubles is zero only when
    // they are equal): the determinant is exactly zero.
    if (smallest == 0.0) return Sign::zero;
    return std::nullopt;
  }
  if (largest < kOrientationOverflowGuard) {
    if (det > bound) return Sign::positive;
    if (det < -bound) return Sign::negative;
  }
  return std::nullopt;
}

}  // namespace shadowcert::detail
