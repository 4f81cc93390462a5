#include "exact/face_crossing.h"

#include <array>
#include <optional>
#include <stdexcept>

#include "exact/orient_unchecked.h"

namespace shadowcert::detail {
namespace {

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
// closed face, or an endpoint on the plane, is a touch: degenerate, never guessed (docs/definitions.md#count-certificate).
FaceMeeting classify_through_plane(const HomogeneousPoint& start, const HomogeneousPoint& end, Sign start_side,
                                   Sign end_side, const std::array<BoundaryLine, 3>& lines) {
  const Sign s = start_side != Sign::zero ? start_side : -end_side;
  const Meeting m = fold_boundary_signs([&](int k) {
    const BoundaryLine& line = lines[static_cast<std::size_t>(k)];
    return orient_unchecked(start, end, *line.p, *line.q) * -s * line.keeps;
  });
  if (m == Meeting::apart) return kApart;  // X strictly outside one closed half-plane: outside the closed face
  if (m == Meeting::touches || start_side == Sign::zero || end_side == Sign::zero) return kTouches;
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
    switch (orient_unchecked(p, q, r, x)) {
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
  const Sign start_side = orient_unchecked(ha, hb, hc, start);
  const Sign end_side = orient_unchecked(ha, hb, hc, end);
  return meet_triangle(start, end, start_side, end_side, ha, hb, hc);
}

FaceMeeting segment_meets_triangle(const HomogeneousPoint& start, const HomogeneousPoint& end, Sign end_side,
                                   const Vec3& a, const Vec3& b, const Vec3& c) {
  const HomogeneousPoint ha = finite_point(a), hb = finite_point(b), hc = finite_point(c);
  const Sign start_side = orient_unchecked(ha, hb, hc, start);
  if (start_side == end_side) return kApart;  // end_side != 0 by precondition: same open half-space
  return meet_triangle(start, end, start_side, end_side, ha, hb, hc);
}

FaceMeeting segment_meets_side(const Vec3& start, const Vec3& end, const HomogeneousPoint& light, const Vec3& u,
                               const Vec3& v) {
  const HomogeneousPoint hs = finite_point(start), he = finite_point(end);
  const HomogeneousPoint hu = finite_point(u), hv = finite_point(v);
  const Sign start_side = orient_unchecked(light, hu, hv, hs);
  const Sign end_side = orient_unchecked(light, hu, hv, he);
  // docs/definitions.md#count-certificate: inside the wedge at L (left of Lu, left of vL) and beyond uv (right of uv).
  const std::array<BoundaryLine, 3> lines{
      {{&hu, &hv, Sign::negative}, {&light, &hu, Sign::positive}, {&hv, &light, Sign::positive}}};
  return classify(hs, he, start_side, end_side, lines, [&] { return spans_no_plane(light, hu, hv); });
}

}  // namespace shadowcert::detail
