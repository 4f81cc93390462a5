#pragma once
// Angles at a triangle's normal compared with a threshold, exactly (docs/edge-maps.md#the-exact-ground-truth):
// the bend angle of two triangles on an edge (crease edges, exact/view_edges.h) and the angle
// between a triangle's normal and a view ray (surfaces seen at grazing angles, the scores'
// false edges on grazing planes, reference/edge_ground_truth.h).
//
// The threshold is given by its cosine c, a double: an angle is compared with theta = acos(c)
// (c in [-1, 1]) exactly, with no epsilon. The normals are cross products of differences of
// the input doubles, formed exactly (an interval filter first, CGAL's Mpzf when it cannot
// decide), and "angle > theta" is decided on squared quantities: with d = n1 . n2 and
// q = |n1|^2 |n2|^2 > 0, angle > theta iff d < c sqrt(q), i.e. the signs of d and c and then
// the comparison of d^2 with c^2 q. So an angle exactly equal to the threshold (90 degrees and
// c = 0, or a bend of exactly 60 degrees against c = 0.5) returns Sign::zero, and callers say
// on which side such a tie falls.
#include "core/sign.h"
#include "core/soup.h"

namespace shadowcert {

// cos(degrees) rounded once in double, for degrees in [0, 180]; the values whose cosine is a
// dyadic rational come out exact: 0 -> 1, 60 -> 0.5, 90 -> 0, 120 -> -0.5, 180 -> -1 (so a
// threshold of 90 degrees is exactly the right angle). Throws std::invalid_argument
// ("angle_cosine: ...") outside [0, 180] or for NaN.
[[nodiscard]] double angle_cosine(double degrees);

// sign(bend - theta), cos theta = cosine: the bend angle at edge uv between the triangles
// (u, v, o1) and (v, u, o2), i.e. the angle between n1 = (v - u) x (o1 - u) and
// n2 = (o2 - u) x (v - u), the normals of the two triangles oriented consistently across the
// edge: 0 where they continue each other in one plane, 90 at a cube's edge, 180 where the
// second folds back onto the first. It depends on the positions only, not on how the soup
// wound either triangle (a crease is a crease under face reversal). Preconditions: cosine in
// [-1, 1], both triangles non-degenerate (n1, n2 != 0); throws std::invalid_argument
// ("bend_angle_sign: ...") otherwise (a zero normal is found exactly).
[[nodiscard]] Sign bend_angle_sign(const Vec3& u, const Vec3& v, const Vec3& o1, const Vec3& o2, double cosine);

// sign(incidence - theta), cos theta = cosine: the incidence angle in [0, 90] degrees between
// the line of abc's normal (b - a) x (c - a) and the direction d, whichever side d comes from:
// 0 for a ray hitting the plane head on, 90 for a ray in the plane's direction. A surface is
// seen at a grazing angle where the incidence angle of its pixel ray exceeds the threshold.
// Preconditions: cosine in [-1, 1] (a negative cosine is a threshold above 90: every
// incidence angle is below it), abc non-degenerate, d != 0; throws std::invalid_argument
// ("incidence_angle_sign: ...") otherwise.
[[nodiscard]] Sign incidence_angle_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double cosine);

}  // namespace shadowcert
