#pragma once
// The floating-point light-side test that float CPU methods and GL shaders both evaluate,
// written once so that gpu/ can mirror it operation for operation (Milet 2014, Algorithm 4):
//
//   X = C - A;  Y = l - A * w;  N = X x Y;  value = N . (B - A)
//
// which is det[C - A, l - w A, B - A] = det[B - A, C - A, l - w A], the determinant whose
// exact sign is D(A, B, C, L) of docs/definitions.md#orientation. In floating point the value depends on the
// order of A, B, C; only the methods that fix that order (refedge) stay consistent.
// Build with -ffp-contract=off (the project does) so no FMA changes the rounding.
#include <array>

#include "core/light.h"
#include "core/sign.h"
#include "core/soup.h"

namespace shadowcert {

template <typename Real>
using Vec3Of = std::array<Real, 3>;

// Rounds a double input to the working precision, as a vertex buffer upload would.
template <typename Real>
[[nodiscard]] constexpr Vec3Of<Real> to_precision(const Vec3& p) {
  return {static_cast<Real>(p[0]), static_cast<Real>(p[1]), static_cast<Real>(p[2])};
}

// The value whose sign a shader takes for D(a, b, c, L); every operation rounds in Real.
template <typename Real>
[[nodiscard]] constexpr Real light_side_value(const Vec3Of<Real>& a, const Vec3Of<Real>& b, const Vec3Of<Real>& c,
                                              const std::array<Real, 4>& light) {
  const Real x0 = c[0] - a[0], x1 = c[1] - a[1], x2 = c[2] - a[2];
  const Real y0 = light[0] - a[0] * light[3];
  const Real y1 = light[1] - a[1] * light[3];
  const Real y2 = light[2] - a[2] * light[3];
  const Real n0 = x1 * y2 - x2 * y1;
  const Real n1 = x2 * y0 - x0 * y2;
  const Real n2 = x0 * y1 - x1 * y0;
  const Real z0 = b[0] - a[0], z1 = b[1] - a[1], z2 = b[2] - a[2];
  return n0 * z0 + n1 * z1 + n2 * z2;
}

template <typename Real>
[[nodiscard]] constexpr Sign light_side_sign(const Vec3Of<Real>& a, const Vec3Of<Real>& b, const Vec3Of<Real>& c,
                                             const std::array<Real, 4>& light) {
  return sign_of(light_side_value(a, b, c, light));
}

}  // namespace shadowcert
