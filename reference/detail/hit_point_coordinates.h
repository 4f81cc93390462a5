#pragma once
// Internal to exact/: the formulas of a ray's meeting with a triangle's plane, written once as
// templates over the number type, so that the interval filters and the exact stages (CGAL's
// Interval_nt and Mpzf, instantiated in exact/*.cpp only) evaluate the same expressions.
//
// Ray e + t d (doubles), triangle abc (doubles):
//   N = det[b - a, c - a, a - e],  D = det[b - a, c - a, d],  t = N / D  (D != 0)
//   P = e + t d = X / W with W = |D| > 0 and X = |D| e + sign(D) N d.
// Every difference is formed in NT from the raw doubles: nothing is rounded before a sign.
#include <array>
#include <utility>

#include "core/pixel_ray.h"
#include "core/sign.h"
#include "core/soup.h"
#include "core/vector3.h"

namespace shadowcert::detail {

template <typename NT>
using VecOf = Vector3<NT>;

template <typename NT>
VecOf<NT> difference(const Vec3& p, const Vec3& q) {
  return {NT(p[0]) - NT(q[0]), NT(p[1]) - NT(q[1]), NT(p[2]) - NT(q[2])};
}

template <typename NT>
VecOf<NT> lift(const Vec3& p) {
  return {NT(p[0]), NT(p[1]), NT(p[2])};
}

// (N, D) for the ray and triangle t.
template <typename NT>
std::pair<NT, NT> plane_parameter(const PixelRay& ray, const std::array<Vec3, 3>& t) {
  const VecOf<NT> u = difference<NT>(t[1], t[0]);
  const VecOf<NT> v = difference<NT>(t[2], t[0]);
  return {det3(u, v, difference<NT>(t[0], ray.origin)), det3(u, v, lift<NT>(ray.direction))};
}

// A point as X / W, W > 0.
template <typename NT>
struct HomogeneousCoordinates {
  VecOf<NT> x;
  NT w;
};

// The hit point's homogeneous coordinates. Precondition: direction_side = sign D != 0.
template <typename NT>
HomogeneousCoordinates<NT> hit_point_coordinates(const PixelRay& ray, const std::array<Vec3, 3>& t,
                                                 Sign direction_side) {
  const auto [n, d] = plane_parameter<NT>(ray, t);
  const bool negative = direction_side == Sign::negative;
  HomogeneousCoordinates<NT> p;
  p.w = negative ? NT(-d) : d;
  const NT m = negative ? NT(-n) : n;
  for (int k = 0; k < 3; ++k) p.x[k] = p.w * NT(ray.origin[k]) + m * NT(ray.direction[k]);
  return p;
}

}  // namespace shadowcert::detail
