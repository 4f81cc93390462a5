#include "reference/detail/ray_hit.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "exact/face_crossing.h"
#include "reference/detail/hit_point_coordinates.h"
#include "exact/light_orientation_filter.h"
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

// A determinant det[x, y, z] of three rows and a certified bound on its evaluation's error:
// the expression and bound of exact/light_orientation_filter.h (CGAL's static filter for
// Orientation_3), for rows x = b - a, y = c - a and z either a difference a - e of doubles or an
// input direction d (no rounding: the bound only over-estimates). nullopt outside the filter's
// magnitude range.
std::optional<BoundedEstimate> bounded_determinant(const std::array<double, 3>& x, const std::array<double, 3>& y,
                                                   const std::array<double, 3>& z) {
  const double max0 = std::max({std::fabs(x[0]), std::fabs(y[0]), std::fabs(z[0])});
  const double max1 = std::max({std::fabs(x[1]), std::fabs(y[1]), std::fabs(z[1])});
  const double max2 = std::max({std::fabs(x[2]), std::fabs(y[2]), std::fabs(z[2])});
  const double smallest = std::min({max0, max1, max2});
  const double largest = std::max({max0, max1, max2});
  if (smallest < kOrientationUnderflowGuard || largest >= kOrientationOverflowGuard) return std::nullopt;
  const double m01 = x[0] * y[1] - y[0] * x[1];
  const double m02 = x[0] * z[1] - z[0] * x[1];
  const double m12 = y[0] * z[1] - z[0] * y[1];
  return BoundedEstimate{m01 * z[2] - m02 * y[2] + m12 * x[2], kOrientationErrorFactor * max0 * max1 * max2};
}

// The semi-static stage of t = N / D (hit_point_coordinates.h), in round-to-nearest doubles
// with no rounding-mode switch: q = fl(N~ / D~) and rho such that t = q (1 + eps), |eps| <= rho.
// With N = N~ (1 + d1), D = D~ (1 + d2), |d1| <= rN = eN / |N~|, |d2| <= rD = eD / |D~|, and
// q = (N~ / D~)(1 + d3), |d3| <= u = 2^-53: t = q (1 + d1) / ((1 + d2)(1 + d3)), whose relative
// deviation is at most (rN + rD + u)(1 + rN) / (1 - rD - u) <= 1.01 (rN + rD + u) when rN, rD
// <= 2^-10; rho = 2 (rN + rD) + 8u covers it, and every rounding of rho's own evaluation (a
// relative 4u at most) with room to spare. nullopt where the filter does not apply (N or D
// within 2^10 of its error, zero, or out of range): the caller takes the interval stage.
struct SemiStaticParameter {
  double q = 0.0;
  double rho = 0.0;
};

inline constexpr double kUnit = 0x1p-53;

std::optional<SemiStaticParameter> semi_static_parameter(const BoundedEstimate& n, const BoundedEstimate& d) {
  constexpr double kRange = 0x1p-10;
  if (!(n.error <= kRange * std::fabs(n.value)) || !(d.error <= kRange * std::fabs(d.value)) || n.value == 0.0 ||
      d.value == 0.0)
    return std::nullopt;
  const double q = n.value / d.value;
  if (!std::isfinite(q)) return std::nullopt;
  return SemiStaticParameter{q, 2.0 * (n.error / std::fabs(n.value) + d.error / std::fabs(d.value)) + 8.0 * kUnit};
}

std::optional<SemiStaticParameter> semi_static_parameter(const PixelRay& ray, const Vec3& a, const Vec3& b,
                                                         const Vec3& c) {
  const std::array<double, 3> x{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const std::array<double, 3> y{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const std::array<double, 3> a_e{a[0] - ray.origin[0], a[1] - ray.origin[1], a[2] - ray.origin[2]};
  const std::array<double, 3> d{ray.direction[0], ray.direction[1], ray.direction[2]};
  const std::optional<BoundedEstimate> n = bounded_determinant(x, y, a_e);
  if (!n) return std::nullopt;
  const std::optional<BoundedEstimate> dd = bounded_determinant(x, y, d);
  if (!dd) return std::nullopt;
  return semi_static_parameter(*n, *dd);
}

// The absolute term of every bound below: far above any underflow error of the few operations
// it covers (each at most 2^-1074).
inline constexpr double kTiny = 0x1p-1000;

// The sign of f(P) = det[x, y, z(P)] for every P in the box lo..hi, when a semi-static bound
// certifies it: f is affine in P with gradient -/+ (a x b) (the caller's rows a, b: inputs or
// rounded differences), evaluated at the box's middle M (a double) with rows x, y, z(M) (inputs
// or rounded differences of doubles). |f~(M) - f(M)| is CGAL's Orientation_3 bound (as in
// bounded_determinant), and |f(P) - f(M)| <= sum_k |(a x b)_k| |P_k - M_k|, where |(a x b)_k|
// <= (|a_k+1| |b_k+2| + |a_k+2| |b_k+1|) (1 + u)^2 on the rounded rows and |P_k - M_k| <=
// hi_k - lo_k + 4u |M_k| (M may round just outside the box). The bound's own evaluation
// rounds by a relative 16u at most, covered by (1 + 2^-40); kTiny covers underflow.
std::optional<Sign> box_filtered_sign(const std::array<double, 3>& x, const std::array<double, 3>& y,
                                      const std::array<double, 3>& z, const std::array<double, 3>& a,
                                      const std::array<double, 3>& b, const Vec3& lo, const Vec3& hi,
                                      const Vec3& middle) {
  const std::optional<BoundedEstimate> f = bounded_determinant(x, y, z);
  if (!f) return std::nullopt;
  double spread = 0.0;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    const double n = std::fabs(a[k1]) * std::fabs(b[k2]) + std::fabs(a[k2]) * std::fabs(b[k1]);
    spread += n * ((hi[k] - lo[k]) + 4.0 * kUnit * std::fabs(middle[k]));
  }
  const double bound = (f->error + spread * (1.0 + 4.0 * kUnit)) * (1.0 + 0x1p-40) + kTiny;
  if (!std::isfinite(bound)) return std::nullopt;
  if (f->value > bound) return Sign::positive;
  if (f->value < -bound) return Sign::negative;
  return std::nullopt;
}

// The box of semi_static_hit_box (below) from the semi-static stage's q and rho on `ray`, into
// `box`; false (`box` unspecified) where a bound is not finite. (Written in place, component by
// component: a local box copied out is read back with wide loads before its stores retire.)
bool hit_box_of(const PixelRay& ray, const SemiStaticParameter& s, std::array<Vec3, 2>& box) {
  // P_k = e_k + t d_k, computed P~ = fl(e_k + y), y = fl(q d_k). t d_k = q d_k (1 + eps), so
  // |t d_k - y| <= |q d_k| (rho + u) <= 1.01 |y| (rho + u), and the sum adds u |P~| / (1 - u):
  // |P~ - P_k| <= 1.01 (|y| (rho + 2u) + u |P~|). The margin m below is twice that, times
  // (1 + 2^-40) for its own roundings (a relative 5u), plus kTiny; forming P~ -+ m rounds by
  // at most u (|P~| + m), which the doubling covers.
  bool finite = true;
  for (int k = 0; k < 3; ++k) {
    const double y = s.q * ray.direction[k];
    const double p = ray.origin[k] + y;
    const double m = (2.0 * std::fabs(y) * (s.rho + 2.0 * kUnit) + 4.0 * kUnit * std::fabs(p)) * (1.0 + 0x1p-40) + kTiny;
    box[0][k] = p - m;
    box[1][k] = p + m;
    finite = finite && std::isfinite(box[0][k]) && std::isfinite(box[1][k]);
  }
  return finite;
}

}  // namespace

std::optional<std::array<Vec3, 2>> semi_static_hit_box(const PixelRay& ray, const std::array<Vec3, 3>& triangle) {
  const std::optional<SemiStaticParameter> s = semi_static_parameter(ray, triangle[0], triangle[1], triangle[2]);
  std::array<Vec3, 2> box;
  if (!s || !hit_box_of(ray, *s, box)) return std::nullopt;
  return box;
}

bool RayParameter::semi_static_hit_box(std::array<Vec3, 2>& box) const {
  return semi_static_ && hit_box_of(ray_, SemiStaticParameter{q_, rho_}, box);
}

RayMeeting ray_meets_triangle(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c) {
  return ray_meets_triangle(ray, a, b, c, KnownRaySigns{});
}

RayMeeting ray_meets_triangle(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c,
                              const KnownRaySigns& known) {
  // The homogeneous points are formed only for a sign the caller does not know (a listed ray
  // usually knows all five: exact_image.cpp's tile filters).
  const auto h = [](const Vec3& p) { return finite_point(p); };
  const HomogeneousPoint d{ray.direction[0], ray.direction[1], ray.direction[2], 0.0};
  RayMeeting m;
  m.eye_side = known.eye_side ? *known.eye_side : orient_unchecked(h(a), h(b), h(c), h(ray.origin));
  m.direction_side = known.direction_side ? *known.direction_side : orient_unchecked(h(a), h(b), h(c), d);
  if (m.direction_side == Sign::zero) {
    // Parallel to the plane: apart when off it; in it, a triangle without area is no surface
    // (docs/definitions.md#orientation), one with area may be met along a segment.
    if (m.eye_side != Sign::zero || spans_no_plane(h(a), h(b), h(c))) return m;
    if (in_plane_meets(ray, a, b, c)) m.contact = RayContact::in_plane;
    return m;
  }
  if (m.eye_side == m.direction_side) return m;  // the plane is behind the eye: t < 0
  // The line meets the plane in one point X (t >= 0). As in exact/face_crossing.h: with s the
  // eye's side (or minus the direction's when e is on the plane), orient(e, d, p, q) =
  // -s * sigma(p, q, X), so X is strictly inside iff every edge line gives -s.
  const Sign s = m.eye_side != Sign::zero ? m.eye_side : -m.direction_side;
  const std::array<std::pair<const Vec3*, const Vec3*>, 3> edges{{{&a, &b}, {&b, &c}, {&c, &a}}};
  const Meeting meeting = fold_boundary_signs([&](int k) {
    const std::optional<Sign>& edge = known.edges[static_cast<std::size_t>(k)];
    if (edge) return *edge * -s;
    const auto& [p, q] = edges[static_cast<std::size_t>(k)];
    return orient_unchecked(h(ray.origin), d, h(*p), h(*q)) * -s;
  });
  if (meeting == Meeting::apart) return m;  // X strictly outside one edge line: outside the closed triangle
  m.contact = meeting == Meeting::touches || m.eye_side == Sign::zero ? RayContact::touches : RayContact::crosses;
  return m;
}

BoundedEstimate plane_numerator_estimate(const Vec3& e, const Vec3& a, const Vec3& b, const Vec3& c) {
  const std::array<double, 3> x{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const std::array<double, 3> y{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const std::array<double, 3> a_e{a[0] - e[0], a[1] - e[1], a[2] - e[2]};
  return bounded_determinant(x, y, a_e).value_or(BoundedEstimate{0.0, std::numeric_limits<double>::infinity()});
}

RayParameter::RayParameter(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c, Sign direction_side)
    : ray_(ray), triangle_{a, b, c}, direction_side_(direction_side), lo_(0.0), hi_(0.0) {
  if (direction_side == Sign::zero)
    throw std::invalid_argument("RayParameter: the ray is parallel to the triangle's plane");
  // From the arguments, not the copies just made (read back with wide loads, they stall).
  if (const std::optional<SemiStaticParameter> s = semi_static_parameter(ray, a, b, c))
    enclose_semi_static(s->q, s->rho);
  else
    enclose_by_intervals();
}

RayParameter::RayParameter(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c, Sign direction_side,
                           const BoundedEstimate& n, const BoundedEstimate& d)
    : ray_(ray), triangle_{a, b, c}, direction_side_(direction_side), lo_(0.0), hi_(0.0) {
  if (direction_side == Sign::zero)
    throw std::invalid_argument("RayParameter: the ray is parallel to the triangle's plane");
  if (const std::optional<SemiStaticParameter> s = semi_static_parameter(n, d))
    enclose_semi_static(s->q, s->rho);
  else if (const std::optional<SemiStaticParameter> own = semi_static_parameter(ray, a, b, c))
    enclose_semi_static(own->q, own->rho);
  else
    enclose_by_intervals();
}

void RayParameter::enclose_semi_static(double q, double rho) {
  semi_static_ = true;
  q_ = q;
  rho_ = rho;
  // t in q (1 -+ rho): the margin doubled covers the roundings of its product and of the
  // sums (each a relative u of a value below 2 |q|; rho >= 8u).
  const double m = 2.0 * std::fabs(q) * rho + kTiny;
  lo_ = std::max(q - m, 0.0);  // t >= 0 for every meeting ray_meets_triangle reports
  hi_ = q + m;
}

void RayParameter::enclose_by_intervals() {
  const CGAL::Protect_FPU_rounding<true> protect;
  const auto [n, d] = plane_parameter<Interval>(ray_, triangle_);
  const Interval t = n / d;  // unbounded when d's enclosure contains 0
  lo_ = std::max(t.inf(), 0.0);  // t >= 0 for every meeting ray_meets_triangle reports
  hi_ = t.sup();
}

RayParameter::RayParameter(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c, Sign direction_side,
                           Unenclosed)
    : ray_(ray), triangle_{a, b, c}, direction_side_(direction_side), lo_(0.0),
      hi_(std::numeric_limits<double>::infinity()) {
  if (direction_side == Sign::zero)
    throw std::invalid_argument("RayParameter: the ray is parallel to the triangle's plane");
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

HitPoint::HitPoint(const RayParameter& t, const std::array<Vec3, 2>& box) : t_(t), lo_(box[0]), hi_(box[1]) {}

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

Vec3 HitPoint::middle() const {
  Vec3 m;
  for (int k = 0; k < 3; ++k) m[k] = lo_[k] / 2 + hi_[k] / 2;
  return m;
}

Sign HitPoint::side(const Vec3& a, const Vec3& b, const Vec3& c) const {
  {
    // Semi-static first (no rounding-mode switch): det[b - a, c - a, P - a], gradient b - a x c - a.
    const Vec3 m = middle();
    const std::array<double, 3> x{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const std::array<double, 3> y{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const std::array<double, 3> z{m[0] - a[0], m[1] - a[1], m[2] - a[2]};
    if (const std::optional<Sign> s = box_filtered_sign(x, y, z, x, y, lo_, hi_, m)) return *s;
  }
  // P lies on the plane of its own triangle: a triangle in that plane (a coplanar neighbour,
  // the other half of a floor quad) has P on its plane, decided here on the input doubles
  // (cheap for axis-aligned planes) rather than on P's exact coordinates; before the intervals,
  // which cannot decide it (the exact value is zero) and cost a rounding-mode switch for every
  // floor point's count.
  const auto& h = t_.triangle_;
  const auto on_hit_plane = [&](const Vec3& x) {
    if (x == h[0] || x == h[1] || x == h[2]) return true;
    return orient_unchecked(finite_point(h[0]), finite_point(h[1]), finite_point(h[2]), finite_point(x)) ==
           Sign::zero;
  };
  if (on_hit_plane(a) && on_hit_plane(b) && on_hit_plane(c) && !spans_no_plane(finite_point(h[0]), finite_point(h[1]),
                                                                                 finite_point(h[2])))
    return Sign::zero;
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    const Vec<Interval> p{Interval(lo_[0], hi_[0]), Interval(lo_[1], hi_[1]), Interval(lo_[2], hi_[2])};
    const Vec<Interval> a_to_p{p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const CGAL::Uncertain<CGAL::Sign> s =
        CGAL::sign(det3(difference<Interval>(b, a), difference<Interval>(c, a), a_to_p));
    if (CGAL::is_certain(s)) return from_cgal(CGAL::get_certain(s));
  }
  // det[b - a, c - a, P - a] = det[b - a, c - a, X - W a] / W with W > 0.
  const Exact& p = exact();
  const Vec<CGAL::Mpzf> a_to_p{p.x[0] - p.w * CGAL::Mpzf(a[0]), p.x[1] - p.w * CGAL::Mpzf(a[1]),
                               p.x[2] - p.w * CGAL::Mpzf(a[2])};
  return from_cgal(CGAL::sign(det3(difference<CGAL::Mpzf>(b, a), difference<CGAL::Mpzf>(c, a), a_to_p)));
}

Sign HitPoint::orient_with(const HomogeneousPoint& light, const Vec3& p, const Vec3& q) const {
  const bool point_light = light[3] != 0.0;
  {
    // Semi-static first. Point light: det[L - P, p - P, q - P] = det[p - L, q - L, L - P]
    // (rows 2 and 3 less row 1, then a cyclic permutation), gradient in P: (p - L) x (q - L).
    // Directional: det[l, p - P, q - P] = det[p - P, q - p, l], gradient (q - p) x l.
    const Vec3 m = middle();
    std::optional<Sign> s;
    if (point_light) {
      const std::array<double, 3> x{p[0] - light[0], p[1] - light[1], p[2] - light[2]};
      const std::array<double, 3> y{q[0] - light[0], q[1] - light[1], q[2] - light[2]};
      const std::array<double, 3> z{light[0] - m[0], light[1] - m[1], light[2] - m[2]};
      s = box_filtered_sign(x, y, z, x, y, lo_, hi_, m);
    } else {
      const std::array<double, 3> x{p[0] - m[0], p[1] - m[1], p[2] - m[2]};
      const std::array<double, 3> y{q[0] - p[0], q[1] - p[1], q[2] - p[2]};
      const std::array<double, 3> z{light[0], light[1], light[2]};
      s = box_filtered_sign(x, y, z, y, z, lo_, hi_, m);
    }
    if (s) return *s;
  }
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
