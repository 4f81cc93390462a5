// reference/ellipsoid_occlusion.h and reference/detail/hit_point_occlusion.h: one template of
// the quadratic's coefficients over the number type, evaluated in intervals first and in
// exact binary floats (Mpzf: sums and products of doubles, no division) where a sign stays
// uncertain.
#include "reference/ellipsoid_occlusion.h"

#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/vector3.h"
#include "reference/detail/hit_point_coordinates.h"
#include "reference/detail/hit_point_occlusion.h"

namespace shadowcert {
namespace {

using Interval = CGAL::Interval_nt<false>;  // used only under a Protect_FPU_rounding
using Exact = CGAL::Mpzf;

template <typename NT>
using Vec = Vector3<NT>;

template <typename NT>
Vec<NT> lift(const Vec3& p) {
  return {NT(p[0]), NT(p[1]), NT(p[2])};
}

// q(t) = a t^2 + 2 b t + c (times W^2 when P = X / W).
template <typename NT>
struct Quadratic {
  NT a, b, c;
};

// The quadratic of the segment from X / W (W > 0) towards `light`: y0 = M (X - W c),
// v = M (W L - X) (point light) or M (W l) (directional), D = W det A.
template <typename NT>
Quadratic<NT> segment_quadratic(const Ellipsoid& e, const Vec<NT>& x, const NT& w, const HomogeneousPoint& light) {
  const Vec<NT> a0 = lift<NT>(e.axes[0]), a1 = lift<NT>(e.axes[1]), a2 = lift<NT>(e.axes[2]);
  const Vec<NT> r0 = cross(a1, a2), r1 = cross(a2, a0), r2 = cross(a0, a1);  // the rows of adj(A)
  const NT det = dot(a0, r0);
  const Vec<NT> rel{x[0] - w * NT(e.centre[0]), x[1] - w * NT(e.centre[1]), x[2] - w * NT(e.centre[2])};
  const Vec<NT> dir = light[3] != 0.0
                          ? Vec<NT>{w * NT(light[0]) - x[0], w * NT(light[1]) - x[1], w * NT(light[2]) - x[2]}
                          : Vec<NT>{w * NT(light[0]), w * NT(light[1]), w * NT(light[2])};
  const Vec<NT> y0{dot(r0, rel), dot(r1, rel), dot(r2, rel)};
  const Vec<NT> v{dot(r0, dir), dot(r1, dir), dot(r2, dir)};
  const NT d = w * det;
  return {dot(v, v), dot(y0, v), dot(y0, y0) - d * d};
}

std::optional<Sign> sign_of_nt(const Interval& x) {
  if (x.inf() > 0.0) return Sign::positive;
  if (x.sup() < 0.0) return Sign::negative;
  if (x.inf() == 0.0 && x.sup() == 0.0) return Sign::zero;
  return std::nullopt;  // the enclosure contains 0: undecided
}

std::optional<Sign> sign_of_nt(const Exact& x) {
  switch (CGAL::sign(x)) {
    case CGAL::NEGATIVE: return Sign::negative;
    case CGAL::ZERO: return Sign::zero;
    case CGAL::POSITIVE: break;
  }
  return Sign::positive;
}

// The sign of q's minimum over [0, 1] (point light) or [0, inf) (directional); nullopt when an
// interval cannot tell.
template <typename NT>
std::optional<Sign> minimum_sign(const Quadratic<NT>& q, bool point_light) {
  const std::optional<Sign> at_start = sign_of_nt(q.c);
  if (!at_start) return std::nullopt;
  if (*at_start == Sign::negative) return Sign::negative;  // P inside
  std::optional<Sign> at_end = Sign::positive;
  if (point_light) {
    at_end = sign_of_nt(q.a + NT(2) * q.b + q.c);
    if (!at_end) return std::nullopt;
    if (*at_end == Sign::negative) return Sign::negative;  // the light inside
  }
  const std::optional<Sign> slope = sign_of_nt(q.a);  // a = |v|^2 >= 0
  if (!slope) return std::nullopt;
  if (*slope == Sign::zero) return *at_start;  // v = 0: P = L, q is constant
  // The vertex t* = -b / a lies inside the segment iff b < 0 (and a + b > 0 for [0, 1]); q's
  // minimum is then q(t*) = (a c - b^2) / a, else at an end (both ends >= 0 by now).
  const std::optional<Sign> b = sign_of_nt(q.b);
  if (!b) return std::nullopt;
  bool vertex_inside = *b == Sign::negative;
  if (vertex_inside && point_light) {
    const std::optional<Sign> before_end = sign_of_nt(q.a + q.b);
    if (!before_end) return std::nullopt;
    vertex_inside = *before_end == Sign::positive;
  }
  if (vertex_inside) return sign_of_nt(q.a * q.c - q.b * q.b);
  return *at_start == Sign::zero || *at_end == Sign::zero ? Sign::zero : Sign::positive;
}

bool finite(const Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

}  // namespace

void require_proper(const Ellipsoid& e, const char* function) {
  if (!finite(e.centre) || !finite(e.axes[0]) || !finite(e.axes[1]) || !finite(e.axes[2]))
    throw std::invalid_argument(std::string(function) + ": the ellipsoid's centre and axes must be finite");
  const Vec<Exact> a0 = lift<Exact>(e.axes[0]), a1 = lift<Exact>(e.axes[1]), a2 = lift<Exact>(e.axes[2]);
  if (CGAL::sign(dot(a0, cross(a1, a2))) == CGAL::ZERO)
    throw std::invalid_argument(std::string(function) + ": the ellipsoid's axes are dependent");
}

Sign ellipsoid_occlusion(const Ellipsoid& ellipsoid, const Vec3& point, const Light& light) {
  require_proper(ellipsoid, "ellipsoid_occlusion");
  require_defined(light, "ellipsoid_occlusion");
  if (!finite(point)) throw std::invalid_argument("ellipsoid_occlusion: the point must be finite");
  const bool point_light = !light.directional();
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    const std::optional<Sign> s =
        minimum_sign(segment_quadratic<Interval>(ellipsoid, lift<Interval>(point), Interval(1.0), light.position),
                     point_light);
    if (s) return -*s;
  }
  return -*minimum_sign(segment_quadratic<Exact>(ellipsoid, lift<Exact>(point), Exact(1.0), light.position), point_light);
}

namespace detail {

Sign hit_point_occlusion(const Ellipsoid& ellipsoid, const RayParameter& hit, const HitPoint& point,
                         const HomogeneousPoint& light) {
  const bool point_light = light[3] != 0.0;
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    const Vec<Interval> x{Interval(point.lo()[0], point.hi()[0]), Interval(point.lo()[1], point.hi()[1]),
                          Interval(point.lo()[2], point.hi()[2])};
    const std::optional<Sign> s =
        minimum_sign(segment_quadratic<Interval>(ellipsoid, x, Interval(1.0), light), point_light);
    if (s) return -*s;
  }
  const HomogeneousCoordinates<Exact> p = hit_point_coordinates<Exact>(hit.ray(), hit.triangle(), hit.direction_side());
  return -*minimum_sign(segment_quadratic<Exact>(ellipsoid, p.x, p.w, light), point_light);
}

}  // namespace detail
}  // namespace shadowcert
