#include "exact/float_sign_bound.h"

#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace shadowcert {
namespace {

using Interval = CGAL::Interval_nt<false>;

// 12 u of float_sign_bound.h and the underflow allowance's unit, per precision.
struct PrecisionConstants {
  double twelve_u;
  double smallest_normal;
};

PrecisionConstants constants(Precision precision) {
  switch (precision) {
    case Precision::float32:
      return {12.0 * std::ldexp(1.0, -std::numeric_limits<float>::digits),
              static_cast<double>(std::numeric_limits<float>::min())};
    case Precision::float64:
      return {12.0 * std::ldexp(1.0, -std::numeric_limits<double>::digits), std::numeric_limits<double>::min()};
  }
  throw std::invalid_argument("float_sign_is_decided: unknown precision");
}

Interval magnitude(double x) { return Interval(std::fabs(x)); }

// The permanent of the row magnitudes with `a` as the evaluation's first vertex
// (float_sign_bound.h); `scale` gets the largest (1 + X)(1 + Y)(1 + Z) for the underflow
// allowance. `rounded_inputs`: float rounds the double inputs first, so each entry's error
// scales with |c| + |a|; double reads them as they are and only the difference rounds,
// relative to |c - a|.
Interval permanent(const Vec3& a, const Vec3& b, const Vec3& c, const std::array<double, 4>& l, bool rounded_inputs,
                   double& scale) {
  std::array<Interval, 3> x, y, z;
  double xm = 0.0, ym = 0.0, zm = 0.0;
  const Interval w(l[3]);
  for (int i = 0; i < 3; ++i) {
    if (rounded_inputs) {
      x[i] = magnitude(c[i]) + magnitude(a[i]);
      y[i] = magnitude(l[i]) + w * magnitude(a[i]);
      z[i] = magnitude(b[i]) + magnitude(a[i]);
    } else {
      x[i] = Interval(CGAL::abs(Interval(c[i]) - Interval(a[i])).sup());
      y[i] = Interval(CGAL::abs(Interval(l[i]) - w * Interval(a[i])).sup());
      z[i] = Interval(CGAL::abs(Interval(b[i]) - Interval(a[i])).sup());
    }
    xm = std::max(xm, x[i].sup());
    ym = std::max(ym, y[i].sup());
    zm = std::max(zm, z[i].sup());
  }
  scale = std::max(scale, ((1 + Interval(xm)) * (1 + Interval(ym)) * (1 + Interval(zm))).sup());
  return x[0] * (y[1] * z[2] + y[2] * z[1]) + x[1] * (y[0] * z[2] + y[2] * z[0]) + x[2] * (y[0] * z[1] + y[1] * z[0]);
}

}  // namespace

bool float_sign_is_decided(const Vec3& a, const Vec3& b, const Vec3& c, const Light& light, Precision precision) {
  const std::array<double, 4>& l = light.position;
  require_well_formed(light, "float_sign_is_decided");
  const PrecisionConstants k = constants(precision);
  CGAL::Protect_FPU_rounding<true> rounding_up;  // what Interval_nt<false> requires
  // D = det[b - a, c - a, l - w a], enclosed exactly (docs/definitions.md#orientation; no rounded difference).
  std::array<Interval, 3> u, v, d;
  for (int i = 0; i < 3; ++i) {
    u[i] = Interval(b[i]) - Interval(a[i]);
    v[i] = Interval(c[i]) - Interval(a[i]);
    d[i] = Interval(l[i]) - Interval(l[3]) * Interval(a[i]);
  }
  const Interval det =
      u[0] * (v[1] * d[2] - v[2] * d[1]) - u[1] * (v[0] * d[2] - v[2] * d[0]) + u[2] * (v[0] * d[1] - v[1] * d[0]);
  const bool rounded_inputs = precision == Precision::float32;
  double scale = 0.0;
  const double m =
      std::max({permanent(a, b, c, l, rounded_inputs, scale).sup(), permanent(b, c, a, l, rounded_inputs, scale).sup(),
                permanent(c, a, b, l, rounded_inputs, scale).sup()});
  const double bound =
      (Interval(k.twelve_u) * Interval(m) + Interval(16.0 * k.smallest_normal) * Interval(scale)).sup();
  if (!std::isfinite(bound) || !std::isfinite(det.inf()) || !std::isfinite(det.sup())) return false;
  return det.inf() > bound || det.sup() < -bound;
}

}  // namespace shadowcert
