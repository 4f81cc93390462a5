#include "exact/face_crossing.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <optional>
#include <stdexcept>

#include "exact/light_orientation_filter.h"

namespace shadowcert::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Sign from_cgal(CGAL::Orientation o) {
  switch (o) {
    case CGAL::NEGATIVE:
      return Sign::negative;
    case CGAL::ZERO:
      return Sign::zero;
    case CGAL::POSITIVE:
      return Sign::positive;
  }
  throw std::logic_error("fast_orient: CGAL returned no orientation");
}

// orient of exact/light_orientation.h on already validated points (finite coordinates, w in
// {0, 1}, at most one w = 0: the callers' points are soup vertices, sample points and a
// validated light), without the per-call validation that dominates the cost of a crossing
// test. The same reductions and stages: four finite points go to CGAL's filtered
// `orientation`; with one point at infinity, one transposition moves it last and the
// semi-static filter of light_orientation_filter.h decides, else `orient` itself (intervals,
// then exact).
Sign fast_orient(const HomogeneousPoint& p, const HomogeneousPoint& q, const HomogeneousPoint& r,
                 const HomogeneousPoint& s) {
  if (p[3] != 0.0 && q[3] != 0.0 && r[3] != 0.0 && s[3] != 0.0)
    return from_cgal(CGAL::orientation(Kernel::Point_3(p[0], p[1], p[2]), Kernel::Point_3(q[0], q[1], q[2]),
                                       Kernel::Point_3(r[0], r[1], r[2]), Kernel::Point_3(s[0], s[1], s[2])));
  auto xyz = [](const HomogeneousPoint& h) { return Vec3{h[0], h[1], h[2]}; };
  // sign det[b - a, c - a, d] for the direction d: orient(a, b, c, (d, 0)).
  auto last_at_infinity = [&](const HomogeneousPoint& a, const HomogeneousPoint& b, const HomogeneousPoint& c,
                              const HomogeneousPoint& d) {
    if (const std::optional<Sign> quick = semi_static_light_orientation(xyz(a), xyz(b), xyz(c), d)) return *quick;
    return orient(a, b, c, d);
  };
  if (s[3] == 0.0) return last_at_infinity(p, q, r, s);
  if (r[3] == 0.0) return -last_at_infinity(p, q, s, r);
  if (q[3] == 0.0) return -last_at_infinity(p, s, r, q);
  return -last_at_infinity(s, q, r, p);
}

// A boundary line pq of a face's plane and the side of it (sigma(p, q, X), seen from the
// plane's orientation) that the face keeps.
struct BoundaryLine {
  const HomogeneousPoint* p;
  const HomogeneousPoint* q;
  Sign keeps;
};

constexpr FaceMeeting kApart{Meeting::apart, Sign::zero};
constexpr FaceMeeting kTouches{Meeting::touches, Sign::zero};

// Precondition: start_side != end_side, so the line start-end meets the plane in one point X.
// With s = start's side (or minus end's when start lies on the plane),
// orient(start, end, p, q) = -s * sigma(p, q, X) (docs/certificates.md, "crossing test"), so
// X is strictly inside iff every line gives -s * keeps. A zero on a line that keeps X on the
// closed face, or an endpoint on the plane, is a touch: degenerate, never guessed (§4.2).
FaceMeeting classify_through_plane(const HomogeneousPoint& start, const HomogeneousPoint& end, Sign start_side,
                                   Sign end_side, const std::array<BoundaryLine, 3>& lines) {
  const Sign s = start_side != Sign::zero ? start_side : -end_side;
  bool on_boundary = false;
  for (const BoundaryLine& line : lines) {
    switch (fast_orient(start, end, *line.p, *line.q) * -s * line.keeps) {
      case Sign::positive:
        break;
      case Sign::zero:
        on_boundary = true;
        break;
      case Sign::negative:
        return kApart;  // X strictly outside one closed half-plane: outside the closed face
    }
  }
  if (on_boundary || start_side == Sign::zero || end_side == Sign::zero) return kTouches;
  return {Meeting::crosses, start_side};
}

// Both endpoints' plane sides known: equal nonzero sides never reach the plane; both zero
// means the segment lies in the plane, which only a face without area lets pass.
template <typename NoArea>
FaceMeeting classify(const HomogeneousPoint& start, const HomogeneousPoint& end, Sign start_side, Sign end_side,
                     const std::array<BoundaryLine, 3>& lines, NoArea no_area) {
  if (start_side != end_side) return classify_through_plane(start, end, start_side, end_side, lines);
  switch (start_side) {
    case Sign::zero:
      return no_area() ? kApart : kTouches;
    case Sign::positive:
    case Sign::negative:
      return kApart;
  }
  return kTouches;
}

FaceMeeting meet_triangle(const HomogeneousPoint& start, const HomogeneousPoint& end, Sign start_side, Sign end_side,
                          const HomogeneousPoint& a, const HomogeneousPoint& b, const HomogeneousPoint& c) {
  const std::array<BoundaryLine, 3> lines{
      {{&a, &b, Sign::positive}, {&b, &c, Sign::positive}, {&c, &a, Sign::positive}}};
  return classify(start, end, start_side, end_side, lines, [&] { return spans_no_plane(a, b, c); });
}

}  // namespace

bool spans_no_plane(const HomogeneousPoint& p, const HomogeneousPoint& q, const HomogeneousPoint& r) {
  static constexpr std::array<HomogeneousPoint, 4> kProbes{
      {{0.0, 0.0, 0.0, 1.0}, {1.0, 0.0, 0.0, 1.0}, {0.0, 1.0, 0.0, 1.0}, {0.0, 0.0, 1.0, 1.0}}};
  for (const HomogeneousPoint& x : kProbes) {
    switch (fast_orient(p, q, r, x)) {
      case Sign::zero:
        break;
      case Sign::positive:
      case Sign::negative:
        return false;
    }
  }
  return true;
}

FaceMeeting segment_meets_triangle(const HomogeneousPoint& start, const HomogeneousPoint& end, const Vec3& a,
                                   const Vec3& b, const Vec3& c) {
  const HomogeneousPoint ha = finite_point(a), hb = finite_point(b), hc = finite_point(c);
  const Sign start_side = fast_orient(ha, hb, hc, start);
  const Sign end_side = fast_orient(ha, hb, hc, end);
  return meet_triangle(start, end, start_side, end_side, ha, hb, hc);
}

FaceMeeting segment_meets_triangle(const HomogeneousPoint& start, const HomogeneousPoint& end, Sign end_side,
                                   const Vec3& a, const Vec3& b, const Vec3& c) {
  const HomogeneousPoint ha = finite_point(a), hb = finite_point(b), hc = finite_point(c);
  const Sign start_side = fast_orient(ha, hb, hc, start);
  if (start_side == end_side) return kApart;  // end_side != 0 by precondition: same open half-space
  return meet_triangle(start, end, start_side, end_side, ha, hb, hc);
}

FaceMeeting segment_meets_side(const Vec3& start, const Vec3& end, const HomogeneousPoint& light, const Vec3& u,
                               const Vec3& v) {
  const HomogeneousPoint hs = finite_point(start), he = finite_point(end);
  const HomogeneousPoint hu = finite_point(u), hv = finite_point(v);
  const Sign start_side = fast_orient(light, hu, hv, hs);
  const Sign end_side = fast_orient(light, hu, hv, he);
  // DESIGN.md §4.2: inside the wedge at L (left of Lu, left of vL) and beyond uv (right of uv).
  const std::array<BoundaryLine, 3> lines{
      {{&hu, &hv, Sign::negative}, {&light, &hu, Sign::positive}, {&hv, &light, Sign::positive}}};
  return classify(hs, he, start_side, end_side, lines, [&] { return spans_no_plane(light, hu, hv); });
}

}  // namespace shadowcert::detail
