#include "scene/affine_transform.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "core/portable_math.h"

namespace shadowcert {
namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

// cos and sin of an angle in degrees; exact at multiples of 90 (cos(90 deg) in double radians
// is 6e-17, which would tilt an axis-aligned floor off its plane).
std::array<double, 2> cos_sin_degrees(double degrees) {
  const double reduced = std::fmod(degrees, 360.0);  // exact
  const double quarter = reduced / 90.0;
  if (quarter == std::floor(quarter)) {
    const auto k = static_cast<int>(quarter) & 3;  // two's complement: -1 & 3 == 3
    constexpr std::array<std::array<double, 2>, 4> exact{{{1.0, 0.0}, {0.0, 1.0}, {-1.0, 0.0}, {0.0, -1.0}}};
    return exact[static_cast<std::size_t>(k)];
  }
  const double radians = reduced * std::numbers::pi / 180.0;
  return {portable::cos(radians), portable::sin(radians)};
}

Matrix3 multiply(const Matrix3& a, const Matrix3& b) {
  Matrix3 c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  return c;
}

Matrix3 rotation_about(int axis, double degrees) {
  const auto [c, s] = cos_sin_degrees(degrees);
  switch (axis) {
    case 0: return {{{1, 0, 0}, {0, c, -s}, {0, s, c}}};
    case 1: return {{{c, 0, s}, {0, 1, 0}, {-s, 0, c}}};
    default: return {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
  }
}

// Cofactor matrix: inverse transpose times det. Normals are renormalised afterwards, so only
// the sign of det matters, and dividing by a tiny det is avoided.
Matrix3 cofactors(const Matrix3& m) {
  Matrix3 c{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      c[i][j] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
    }
  }
  return c;
}

Vec3 apply(const Matrix3& m, const Vec3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

Normal transform_normal(const Matrix3& inverse_transpose_times_det, double det_sign, const Normal& n) {
  const Vec3 v = apply(inverse_transpose_times_det, {n[0], n[1], n[2]});
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(length > 0.0) || !std::isfinite(length)) return n;  // a zero input normal stays as it was
  const double k = det_sign / length;
  return {static_cast<float>(v[0] * k), static_cast<float>(v[1] * k), static_cast<float>(v[2] * k)};
}

double determinant(const Matrix3& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// A divided by the power of two nearest its largest entry (exact): the determinant's sign
// and the normals' directions are unchanged, and huge scales cannot overflow them.
Matrix3 power_of_two_normalised(const Matrix3& a) {
  double largest = 0.0;
  for (const auto& row : a)
    for (double x : row) largest = std::max(largest, std::fabs(x));
  if (largest == 0.0) return a;
  int exponent = 0;
  std::frexp(largest, &exponent);
  Matrix3 out = a;
  for (auto& row : out)
    for (double& x : row) x = std::ldexp(x, -exponent);
  return out;
}

}  // namespace

AffineTransform compose_trs(const Vec3& translate, const Vec3& scale, const Vec3& rotate_degrees) {
  const Matrix3 scaling{{{scale[0], 0, 0}, {0, scale[1], 0}, {0, 0, scale[2]}}};
  const Matrix3 rotation =
      multiply(rotation_about(2, rotate_degrees[2]),
               multiply(rotation_about(1, rotate_degrees[1]), rotation_about(0, rotate_degrees[0])));
  return {multiply(rotation, scaling), translate};
}

bool is_identity(const AffineTransform& transform) {
  const AffineTransform identity;
  return transform.linear == identity.linear && transform.translation == identity.translation;
}

Soup transformed(const Soup& soup, const AffineTransform& transform) {
  const Matrix3 normalised = power_of_two_normalised(transform.linear);
  const double det = determinant(normalised);
  if (det == 0.0)
    throw std::invalid_argument("transformed: the linear part is singular (a zero scale or a degenerate matrix)");
  Soup out;
  out.vertices.reserve(soup.vertices.size());
  for (const Vec3& p : soup.vertices) {
    const Vec3 q = apply(transform.linear, p);
    out.vertices.push_back({q[0] + transform.translation[0], q[1] + transform.translation[1],
                            q[2] + transform.translation[2]});
  }
  const Matrix3 normal_matrix = cofactors(normalised);
  const double det_sign = det > 0.0 ? 1.0 : -1.0;
  out.normals.reserve(soup.normals.size());
  for (const Normal& n : soup.normals) out.normals.push_back(transform_normal(normal_matrix, det_sign, n));
  out.triangles = soup.triangles;
  if (det < 0.0)
    for (Triangle& t : out.triangles) std::swap(t[1], t[2]);
  return out;
}

Ellipsoid transformed(const Ellipsoid& ellipsoid, const AffineTransform& transform) {
  if (determinant(power_of_two_normalised(transform.linear)) == 0.0)
    throw std::invalid_argument("transformed: the linear part is singular (a zero scale or a degenerate matrix)");
  const Vec3 c = apply(transform.linear, ellipsoid.centre);
  Ellipsoid out;
  out.centre = {c[0] + transform.translation[0], c[1] + transform.translation[1], c[2] + transform.translation[2]};
  for (std::size_t k = 0; k < 3; ++k) out.axes[k] = apply(transform.linear, ellipsoid.axes[k]);
  return out;
}

}  // namespace shadowcert
