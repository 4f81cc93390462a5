#pragma once
// Test-only brute force for the orientation predicate of docs/definitions.md#orientation: exact integer
// arithmetic (boost::multiprecision::cpp_int), written independently of exact/ (no CGAL,
// no filter, a different determinant expansion), so that the tests compare two codes.
#include <boost/multiprecision/cpp_int.hpp>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/soup.h"

namespace shadowcert::brute {

using Integer = boost::multiprecision::cpp_int;

// Exact integers for a set of finite doubles: every x = mantissa * 2^exponent is written as
// mantissa * 2^(exponent - E) with E the smallest exponent of the set. The determinants below
// are homogeneous in the coordinates (w stays 0 or 1), so this common positive scale 2^-E
// changes no sign, and integer arithmetic needs no gcd (fast even for 1e-300..1e300).
class ExactScale {
 public:
  template <typename... Arrays>
  explicit ExactScale(const Arrays&... arrays) {
    (note(arrays), ...);
  }
  [[nodiscard]] Integer operator()(double x) const {
    if (x == 0.0) return 0;
    int exponent = 0;
    const double fraction = std::frexp(x, &exponent);  // x = fraction * 2^exponent, 0.5 <= |fraction| < 1
    const auto mantissa = static_cast<long long>(std::ldexp(fraction, 53));  // an integer, exactly
    return Integer(mantissa) << (exponent - 53 - min_exponent_);
  }

 private:
  template <std::size_t N>
  void note(const std::array<double, N>& xs) {
    for (std::size_t k = 0; k < std::min<std::size_t>(N, 3); ++k) {
      if (xs[k] == 0.0) continue;
      int exponent = 0;
      (void)std::frexp(xs[k], &exponent);
      min_exponent_ = std::min(min_exponent_, exponent - 53);
    }
  }
  int min_exponent_ = 0;
};

inline int sign(const Integer& x) { return x > 0 ? 1 : (x < 0 ? -1 : 0); }

using Row = std::array<Integer, 3>;

// Rule of Sarrus (CGAL and the filter use minors; this is deliberately another expansion).
inline Integer det3(const Row& x, const Row& y, const Row& z) {
  return x[0] * y[1] * z[2] + x[1] * y[2] * z[0] + x[2] * y[0] * z[1] - x[2] * y[1] * z[0] - x[1] * y[0] * z[2] -
         x[0] * y[2] * z[1];
}

// sign det[b - a, c - a, l - w a] for l = {x, y, z, w}, w in {0, 1}.
inline int light_orientation(const Vec3& a, const Vec3& b, const Vec3& c, const std::array<double, 4>& l) {
  const ExactScale exact(a, b, c, l);
  Row x, y, z;
  for (int k = 0; k < 3; ++k) {
    x[k] = exact(b[k]) - exact(a[k]);
    y[k] = exact(c[k]) - exact(a[k]);
    z[k] = l[3] == 0.0 ? exact(l[k]) : exact(l[k]) - exact(a[k]);
  }
  return sign(det3(x, y, z));
}

// Minus the sign of the 4x4 determinant of the homogeneous rows p, q, r, s (docs/definitions.md#orientation),
// by Laplace expansion along the last column (w in {0, 1}).
inline int orient4(const std::array<double, 4>& p, const std::array<double, 4>& q, const std::array<double, 4>& r,
                   const std::array<double, 4>& s) {
  const ExactScale exact(p, q, r, s);
  const std::array<const std::array<double, 4>*, 4> rows{&p, &q, &r, &s};
  Integer det = 0;
  for (int i = 0; i < 4; ++i) {
    if ((*rows[i])[3] == 0.0) continue;
    std::array<Row, 3> minor;
    int m = 0;
    for (int j = 0; j < 4; ++j) {
      if (j == i) continue;
      for (int k = 0; k < 3; ++k) minor[m][k] = exact((*rows[j])[k]);
      ++m;
    }
    // Cofactor sign of entry (i, 3) is (-1)^(i + 3); the entry w is 1 here.
    const Integer minor_det = det3(minor[0], minor[1], minor[2]);
    if ((i + 3) % 2 == 0)
      det += minor_det;
    else
      det -= minor_det;
  }
  return -sign(det);
}

}  // namespace shadowcert::brute
