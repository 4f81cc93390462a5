#pragma once
// Whether a point lies in an ellipsoid's analytic shadow, decided exactly (the per-pixel truth
// of reference/analytic_shadow_image.h; docs/smooth-silhouettes.md, "Per-pixel error").
//
// The ellipsoid is x = c + A u, |u| <= 1 (core/ellipsoid.h). With M = adj(A) (rows a1 x a2,
// a2 x a0, a0 x a1 of the axes a0, a1, a2) and det = det A, a point x is inside iff
// |M (x - c)|^2 < det^2. Along the segment from P towards the light, x(t) = P + t (L - P),
// t in [0, 1], for a point light L, or x(t) = P + t l, t >= 0, for a directional light towards
// l, that is the quadratic
//   q(t) = |M (P - c) + t v|^2 - det^2 = a t^2 + 2 b t + c0,
//   v = M (L - P) (point) or M l (directional),
// convex (a = |v|^2 >= 0). The occlusion sign is minus the sign of q's minimum over the
// segment: positive when the segment enters the open interior (P is shadowed: the open segment
// P -> light meets the interior, P itself inside included), zero when it touches the surface
// without entering (P on the shadow boundary: a tangent segment, or P on the surface with the
// segment leaving it), negative when it misses the closed ellipsoid. The minimum's sign is a
// sign of c0, of q(1) = a + 2b + c0 (point light), of b and a + b (where the vertex t* = -b/a
// lies), and of a c0 - b^2 (q at the vertex, times a > 0): polynomials in the input doubles,
// evaluated in interval arithmetic and, where an interval contains 0, exactly (CGAL's Mpzf).
// No tolerance: a tangent segment is an exact zero.
#include "core/ellipsoid.h"
#include "core/light.h"
#include "core/sign.h"
#include "core/soup.h"

namespace shadowcert {

// The occlusion sign of `point` by `ellipsoid` for `light` (above). Throws
// std::invalid_argument("ellipsoid_occlusion: ...") for a non-finite point or ellipsoid, axes
// that are exactly dependent (det A = 0), or a light that is not defined (core/light.h).
[[nodiscard]] Sign ellipsoid_occlusion(const Ellipsoid& ellipsoid, const Vec3& point, const Light& light);

// Throws std::invalid_argument("<function>: ...") unless the ellipsoid's centre and axes are
// finite and its axes independent (det A != 0, decided exactly).
void require_proper(const Ellipsoid& ellipsoid, const char* function);

}  // namespace shadowcert
