#pragma once
// The exact orientation predicate of docs/definitions.md#orientation, for double inputs and both light kinds.
// No construction (b - a, a + l, ...) is rounded before the sign is taken: the sign comes
// from an interval filter (CGAL::Interval_nt) with an exact fallback, or from CGAL's filtered
// `orientation` for four finite points.
#include <array>

#include "core/light.h"
#include "core/sign.h"
#include "core/soup.h"

namespace shadowcert {

// A point of the projective space: w = 1 a finite point, w = 0 a direction (a point at
// infinity). Shape: {x, y, z, w} with w in {0, 1}.
using HomogeneousPoint = std::array<double, 4>;

[[nodiscard]] inline HomogeneousPoint finite_point(const Vec3& p) { return {p[0], p[1], p[2], 1.0}; }

// orient(p, q, r, s) = minus the sign of det[p; q; r; s] (rows homogeneous); for four finite
// points sign det[q - p, r - p, s - p], CGAL's `orientation`. At most one argument may have
// w = 0; throws std::invalid_argument("orient: ...") otherwise, or when a w is not 0 or 1
// (or a coordinate is not finite, or a point is (0, 0, 0, 0)).
[[nodiscard]] Sign orient(const HomogeneousPoint& p, const HomogeneousPoint& q, const HomogeneousPoint& r,
                          const HomogeneousPoint& s);

// D(a, b, c, L) = orient(a, b, c, L) = sign det[b - a, c - a, l - w a]: positive when the
// light is on the side that (b - a) x (c - a) points to; zero when the light lies on the
// triangle's plane or the triangle is degenerate (it then casts nothing, docs/definitions.md#orientation).
// Throws std::invalid_argument("light_orientation: ...") when the light has a non-finite
// coordinate, a w other than 0 or 1, or is directional with direction (0, 0, 0).
[[nodiscard]] Sign light_orientation(const Vec3& a, const Vec3& b, const Vec3& c, const Light& light);

}  // namespace shadowcert
