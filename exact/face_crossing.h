#pragma once
// Internal to exact/: where a segment (or a ray) meets one planar face of a shadow-volume
// chain or one caster triangle, decided by orientation signs of the input doubles only
// (docs/definitions.md#count-certificate: no intersection point, no far point is ever constructed).
//
// Every face here is a convex region of a plane, the intersection of three closed half-planes:
//   caster or cap triangle abc   : left of ab, bc and ca (seen from (b - a) x (c - a));
//   side face of edge uv, light L: {l + t (x - l): x on [u, v], t >= 1} for a point light,
//                                  {x - t l: x on [u, v], t >= 0} for a directional one,
//                                  left of Lu, left of vL, right of uv in the plane (L, u, v).
// The derivation (docs/certificates.md): for X = AB ∩ plane and a boundary line pq of the
// plane, orient(A, B, p, q) = -s * sigma(p, q, X), where s is A's side of the plane (or -B's
// when A lies on it) and sigma the orientation of (p, q, X) inside the plane. So "X is strictly
// inside" is three orient signs equal to -s times the side each line keeps.
#include <cstdint>

#include "core/sign.h"
#include "core/soup.h"
#include "exact/light_orientation.h"

namespace shadowcert::detail {

enum class Meeting : std::uint8_t {
  apart,    // the closed segment misses the closed face (or the face has no area)
  crosses,  // the open segment passes through the open face, endpoints strictly off its plane
  touches,  // anything else: a zero sign that matters; the caller re-draws (docs/definitions.md#count-certificate)
};

// The crossing rule folded over a face's three boundary lines, for a segment whose line meets
// the face's plane in one point X: line_sign(k) is line k's sign as the rule reads it (positive:
// X strictly on the face's side). Every line positive: X strictly inside (crosses); one negative:
// X outside (apart), whatever the others say; otherwise a zero: X on the boundary (touches).
// Stops at the first negative.
template <typename LineSign>
[[nodiscard]] Meeting fold_boundary_signs(LineSign&& line_sign) {
  bool on_boundary = false;
  for (int k = 0; k < 3; ++k) {
    switch (line_sign(k)) {
      case Sign::positive:
        break;
      case Sign::zero:
        on_boundary = true;
        break;
      case Sign::negative:
        return Meeting::apart;
    }
  }
  return on_boundary ? Meeting::touches : Meeting::crosses;
}

struct FaceMeeting {
  Meeting meeting = Meeting::apart;
  Sign start_side = Sign::zero;  // when crosses: the side of the face's plane the start lies on
};

// Segment start -> end (end may be a direction, w = 0: then the ray from start towards it)
// against triangle abc oriented by its vertex order. A triangle of zero area meets nothing:
// it is no face of any volume (docs/definitions.md#orientation).
[[nodiscard]] FaceMeeting segment_meets_triangle(const HomogeneousPoint& start, const HomogeneousPoint& end,
                                                 const Vec3& a, const Vec3& b, const Vec3& c);

// The same when end's side of the plane, orient(a, b, c, end), is already known and nonzero:
// a caster's light side s(t) (docs/definitions.md#counts) in the occluder count.
[[nodiscard]] FaceMeeting segment_meets_triangle(const HomogeneousPoint& start, const HomogeneousPoint& end,
                                                 Sign end_side, const Vec3& a, const Vec3& b, const Vec3& c);

// Finite segment start -> end against the side face of edge uv for light L (above), whose
// plane is oriented by (L, u, v). A side face of no area (L on the line uv) meets nothing.
[[nodiscard]] FaceMeeting segment_meets_side(const Vec3& start, const Vec3& end, const HomogeneousPoint& light,
                                             const Vec3& u, const Vec3& v);

// True iff p, q, r span no plane (r may be a direction): orient(p, q, r, x) vanishes for all x,
// tested on four affinely independent points (a plane holds at most three of them).
[[nodiscard]] bool spans_no_plane(const HomogeneousPoint& p, const HomogeneousPoint& q, const HomogeneousPoint& r);

}  // namespace shadowcert::detail
