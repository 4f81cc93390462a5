#include "reference/detail/ray_hit.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "exact/face_crossing.h"
#include "reference/detail/hit_point_coordinates.h"
#include "exact/orient_unchecked.h"

namespace shadowcert::detail {
namespace {

using Interval = CGAL::Interval_nt<false>;  // used only under a Protect_FPU_rounding
using Exact = CGAL::Mpzf;                   // exact for sums and products of doubles

template <typename NT>
using Vec = VecOf<NT>;

Sign from_cgal(CGAL::Sign s) {
  switch (s) {
    case CGAL::NEGATIVE:
      return Sign::negative;
    case CGAL::ZERO:
      return Sign::zero;
    case CGAL::POSITIVE:
      return Sign::positive;
  }
  throw std::logic_error("from_cgal: not a sign");
}

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

template <typename K>
typename K::Point_3 point(const Vec3& p) {
  return {p[0], p[1], p[2]};
}

// The ray lies in the plane of abc (which has area): whether it meets the closed triangle.
// CGAL's Ray_3 / Triangle_3 do_intersect is a predicate on the input doubles (filtered, exact),
// coplanar case included.
bool in_plane_meets(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Epick::Ray_3 r(point<Epick>(ray.origin),
                       Epick::Direction_3(ray.direction[0], ray.direction[1], ray.direction[2]));
  return CGAL::do_intersect(r, Epick::Triangle_3(point<Epick>(a), point<Epick>(b), point<Epick>(c)));
}

}  // namespace

RayMeeting ray_meets_triangle(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
  const HomogeneousPoint ha = finite_point(a), hb = finite_point(b), hc = finite_point(c);
  const HomogeneousPoint e = finite_point(ray.origin);
  const HomogeneousPoint d{ray.direction[0], ray.direction[1], ray.direction[2], 0.0};
  RayMeeting m;
  m.eye_side = orient_unchecked(ha, hb, hc, e);
  m.direction_side = orient_unchecked(ha, hb, hc, d);
  if (m.direction_side == Sign::zero) {
    // Parallel to the plane: apart when off it; in it, a triangle without area is no surface
    // (docs/definitions.md#orientation), one with area may be met along a segment.
    if (m.eye_side != Sign::zero || spans_no_plane(ha, hb, hc)) return m;
    if (in_plane_meets(ray, a, b, c)) m.contact = RayContact::in_plane;
    return m;
  }
  if (m.eye_side == m.direction_side) return m;  // the plane is behind the eye: t < 0
  // The line meets the plane in one point X (t >= 0). As in exact/face_crossing.h: with s the
  // eye's side (or minus the direction's when e is on the plane), orient(e, d, p, q) =
  // -s * sigma(p, q, X), so X is strictly inside iff every edge line gives -s.
  const Sign s = m.eye_side != Sign::zero ? m.eye_side : -m.direction_side;
  bool on_boundary = false;
  for (const auto& [p, q] : {std::pair{&ha, &hb}, std::pair{&hb, &hc}, std::pair{&hc, &ha}}) {
    switch (orient_unchecked(e, d, *p, *q) * -s) {
      case Sign::positive:
        break;
      case Sign::zero:
        on_boundary = true;
        break;
      case Sign::negative:
        return m;  // X strictly outside one edge line: outside the closed triangle
    }
  }
  m.contact = on_boundary || m.eye_side == Sign::zero ? RayContact::touches : RayContact::crosses;
  return m;
}

RayParameter::RayParameter(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c, Sign direction_side)
    : ray_(ray), triangle_{a, b, c}, direction_side_(direction_side), lo_(0.0), hi_(0.0) {
  if (direction_side == Sign::zero)
    throw std::invalid_argument("RayParameter: the ray is parallel to the triangle's plane");
  const CGAL::Protect_FPU_rounding<true> protect;
  const auto [n, d] = plane_parameter<Interval>(ray_, triangle_);
  const Interval t = n / d;  // unbounded when d's enclosure contains 0
  lo_ = std::max(t.inf(), 0.0);  // t >= 0 for every meeting ray_meets_triangle reports
  hi_ = t.sup();
}

Sign RayParameter::compare(const RayParameter& other) const {
  if (hi_ < other.lo_) return Sign::negative;
  if (lo_ > other.hi_) return Sign::positive;
  // t1 - t2 = (N1 D2 - N2 D1) / (D1 D2), and the signs of D1, D2 are known exactly.
  const auto [n1, d1] = plane_parameter<Exact>(ray_, triangle_);
  const auto [n2, d2] = plane_parameter<Exact>(other.ray_, other.triangle_);
  return from_cgal(CGAL::sign(n1 * d2 - n2 * d1)) * direction_side_ * other.direction_side_;
}

bool in_plane_contact_before(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c,
                             const RayParameter& bound) {
  // The ray meets the closed triangle in a segment [t_in, t_out] (convex), so it meets it at
  // some t <= bound iff the closed segment e -> P(bound) does. Rational constructions (Epeck).
  const auto [n, d] = plane_parameter<Epeck::FT>(bound.ray_, bound.triangle_);
  const Epeck::Point_3 e = point<Epeck>(ray.origin);
  const Epeck::Point_3 p = e + (n / d) * Epeck::Vector_3(ray.direction[0], ray.direction[1], ray.direction[2]);
  const Epeck::Triangle_3 t(point<Epeck>(a), point<Epeck>(b), point<Epeck>(c));
  if (p == e) return t.has_on(e);
  return CGAL::do_intersect(Epeck::Segment_3(e, p), t);
}

// P = X / W with W = |D| > 0 and X = |D| e + sign(D) N d, exact.
struct HitPoint::Exact {
  Vec<CGAL::Mpzf> x;
  CGAL::Mpzf w;
};

HitPoint::HitPoint(const RayParameter& t) : t_(t) {
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    const auto [n, d] = plane_parameter<Interval>(t_.ray_, t_.triangle_);
    const Interval s = n / d;
    bool bounded = true;
    for (int k = 0; k < 3; ++k) {
      const Interval p = Interval(t_.ray_.origin[k]) + s * t_.ray_.direction[k];
      lo_[k] = p.inf();
      hi_[k] = p.sup();
      bounded = bounded && std::isfinite(lo_[k]) && std::isfinite(hi_[k]);
    }
    if (bounded) return;
  }
  // D's enclosure contains 0 (a ray almost parallel to the plane): enclose the exact point.
  const Exact& p = exact();
  const CGAL::Protect_FPU_rounding<true> protect;
  const Interval w(CGAL::to_interval(p.w));
  for (int k = 0; k < 3; ++k) {
    const Interval x(CGAL::to_interval(p.x[k]));
    const Interval q = x / w;
    lo_[k] = q.inf();
    hi_[k] = q.sup();
  }
}

HitPoint::~HitPoint() = default;
HitPoint::HitPoint(HitPoint&&) noexcept = default;
HitPoint& HitPoint::operator=(HitPoint&&) noexcept = default;

const HitPoint::Exact& HitPoint::exact() const {
  if (!exact_) {
    const HomogeneousCoordinates<CGAL::Mpzf> p = hit_point_coordinates<CGAL::Mpzf>(t_.ray_, t_.triangle_, t_.direction_side_);
    exact_ = std::make_unique<Exact>(Exact{p.x, p.w});
  }
  return *exact_;
}

Sign HitPoint::side(const Vec3& a, const Vec3& b, const Vec3& c) const {
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    const Vec<Interval> p{Interval(lo_[0], hi_[0]), Interval(lo_[1], hi_[1]), Interval(lo_[2], hi_[2])};
    const Vec<Interval> a_to_p{p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const CGAL::Uncertain<CGAL::Sign> s =
        CGAL::sign(det3(difference<Interval>(b, a), difference<Interval>(c, a), a_to_p));
    if (CGAL::is_certain(s)) return from_cgal(CGAL::get_certain(s));
  }
  // P lies on the plane of its own triangle: a triangle in that plane (a coplanar neighbour,
  // the other half of a floor quad) has P on its plane, decided here on the input doubles
  // (cheap for axis-aligned planes) rather than on P's exact coordinates.
  const auto& h = t_.triangle_;
  const auto on_hit_plane = [&](const Vec3& x) {
    if (x == h[0] || x == h[1] || x == h[2]) return true;
    return orient_unchecked(finite_point(h[0]), finite_point(h[1]), finite_point(h[2]), finite_point(x)) ==
           Sign::zero;
  };
  if (on_hit_plane(a) && on_hit_plane(b) && on_hit_plane(c) && !spans_no_plane(finite_point(h[0]), finite_point(h[1]),
                                                                                 finite_point(h[2])))
    return Sign::zero;
  // det[b - a, c - a, P - a] = det[b - a, c - a, X - W a] / W with W > 0.
  const Exact& p = exact();
  const Vec<CGAL::Mpzf> a_to_p{p.x[0] - p.w * CGAL::Mpzf(a[0]), p.x[1] - p.w * CGAL::Mpzf(a[1]),
                               p.x[2] - p.w * CGAL::Mpzf(a[2])};
  return from_cgal(CGAL::sign(det3(difference<CGAL::Mpzf>(b, a), difference<CGAL::Mpzf>(c, a), a_to_p)));
}

Sign HitPoint::orient_with(const HomogeneousPoint& light, const Vec3& p, const Vec3& q) const {
  const bool point_light = light[3] != 0.0;
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    const Vec<Interval> hp{Interval(lo_[0], hi_[0]), Interval(lo_[1], hi_[1]), Interval(lo_[2], hi_[2])};
    const auto from_hit = [&](const Vec3& x) { return Vec<Interval>{x[0] - hp[0], x[1] - hp[1], x[2] - hp[2]}; };
    const Vec<Interval> first = point_light ? from_hit({light[0], light[1], light[2]})
                                            : Vec<Interval>{Interval(light[0]), Interval(light[1]), Interval(light[2])};
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(det3(first, from_hit(p), from_hit(q)));
    if (CGAL::is_certain(s)) return from_cgal(CGAL::get_certain(s));
  }
  // With P = X / W, W > 0: det[W L - X, W p - X, W q - X] = W^3 det[L - P, p - P, q - P] and
  // det[l, W p - X, W q - X] = W^2 det[l, p - P, q - P]: the same signs.
  const Exact& e = exact();
  const auto from_hit = [&](double x, double y, double z) {
    return Vec<CGAL::Mpzf>{e.w * CGAL::Mpzf(x) - e.x[0], e.w * CGAL::Mpzf(y) - e.x[1], e.w * CGAL::Mpzf(z) - e.x[2]};
  };
  const Vec<CGAL::Mpzf> first =
      point_light ? from_hit(light[0], light[1], light[2])
                  : Vec<CGAL::Mpzf>{CGAL::Mpzf(light[0]), CGAL::Mpzf(light[1]), CGAL::Mpzf(light[2])};
  return from_cgal(CGAL::sign(det3(first, from_hit(p[0], p[1], p[2]), from_hit(q[0], q[1], q[2]))));
}

bool HitPoint::equals(const Vec3& x) const {
  for (int k = 0; k < 3; ++k)
    if (x[k] < lo_[k] || x[k] > hi_[k]) return false;
  const Exact& e = exact();
  for (int k = 0; k < 3; ++k)
    if (e.x[k] != e.w * CGAL::Mpzf(x[k])) return false;
  return true;
}

}  // namespace shadowcert::detail
