#pragma once
// Arithmetic on 3-vectors stored as std::array<T, 3>, written once for every number type the
// project evaluates it in: double (camera frames, generators, pictures), integers (tests'
// references), and CGAL's interval and exact types (exact/ and reference/ instantiate those in
// their .cpp files; this header includes no CGAL). Each function's expression order is part of
// its contract: a filter's error bound is proven for exactly these operations.
#include <array>
#include <cmath>

namespace shadowcert {

template <typename T>
using Vector3 = std::array<T, 3>;

// a - b.
template <typename T>
[[nodiscard]] constexpr Vector3<T> difference(const Vector3<T>& a, const Vector3<T>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// a x b, right-handed.
template <typename T>
[[nodiscard]] constexpr Vector3<T> cross(const Vector3<T>& a, const Vector3<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

template <typename T>
[[nodiscard]] constexpr T dot(const Vector3<T>& a, const Vector3<T>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The determinant of the 3x3 matrix with rows x, y, z, in CGAL::determinant's expression order
// (so that an interval or exact evaluation here matches CGAL's filtered predicates term by term).
template <typename T>
[[nodiscard]] constexpr T det3(const Vector3<T>& x, const Vector3<T>& y, const Vector3<T>& z) {
  const T m01 = x[0] * y[1] - y[0] * x[1];
  const T m02 = x[0] * z[1] - z[0] * x[1];
  const T m12 = y[0] * z[1] - z[0] * y[1];
  return m01 * z[2] - m02 * y[2] + m12 * x[2];
}

// v / |v| in double. Precondition: v != 0 and finite (callers check; 0 gives NaN).
[[nodiscard]] inline Vector3<double> normalized(const Vector3<double>& v) {
  const double inverse_length = 1.0 / std::sqrt(dot(v, v));
  return {v[0] * inverse_length, v[1] * inverse_length, v[2] * inverse_length};
}

}  // namespace shadowcert
