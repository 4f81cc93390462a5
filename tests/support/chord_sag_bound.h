#pragma once
// A closed-form bound on discrete's contour error (docs/smooth-silhouettes.md, "A bound the
// discrete figures must meet"), independent of the code that measures the error, for the tests
// of pipeline/contour_error.h and of `shadowcert bench --suite analytic`: a uv sphere's polygon
// lies between the sphere and the ball inscribed in its faces, so its shadow's boundary lies
// between the two balls' conics, and its error is at most their distance.
#include <cmath>
#include <numbers>

#include "core/light.h"

namespace shadowcert::test_support {

// A uv sphere of radius r, `slices` around and `stacks` from pole to pole, has its vertices on
// the sphere and is convex, so it lies inside the ball of radius r. Each face is a symmetric
// trapezoid (or a triangle at a pole) spanning 2 pi / slices in longitude and pi / stacks in
// latitude; the plane through it lies at least r cos(pi / slices) cos(pi / (2 stacks)) from the
// centre (for the chord across the equator of one slice: r cos(pi / slices), the chord sag
// r (1 - cos(pi / slices)) of the slice's polygon), so the polyhedron contains the ball of that
// radius.
inline double inscribed_radius(double r, unsigned slices, unsigned stacks) {
  return r * std::cos(std::numbers::pi / slices) * std::cos(std::numbers::pi / (2.0 * stacks));
}

// discrete's boundary on the floor y = floor_height is the polyhedron's shadow's (a convex
// polyhedron lit from outside: its silhouette loop projects onto the boundary of its shadow),
// which lies between the shadows of the inscribed ball (radius r_in) and of the sphere (r),
// both centred at the origin. A point q between two nested convex sets K' in K lies within
// their Hausdorff distance of the outer boundary (separate q from K' by a supporting line of
// normal n: moving along n, q leaves K within h_K(n) - h_K'(n)). That distance, in closed form:
//   sun towards l: the projection along l onto the floor stretches lengths by at most
//     1 / cos(a), a the angle between l and the floor's normal, so the shadows' distance is at
//     most (r - r_in) / cos(a) (times |A| for an ellipsoid x = A u: `matrix_norm`);
//   point light at distance d from the centre and height H over the floor: a point of the outer
//     conic lies on the tangent cone (half angle t = asin(r / d)); turning its ray towards the
//     cone's axis by t - t_in (t_in = asin(r_in / d)) reaches the inner conic, and a ray at
//     distance s from the light turning by dt moves its floor point by at most s^2 dt / H; s is
//     at most H / cos(g + t), g the angle between the axis and the floor's normal. So the
//     distance is at most H (t - t_in) / cos^2(g + t).
// The truth is the conic sampled at 4,096 points (a polygon inside it), whose distance to a
// point inside is no larger than the conic's, and within its sag (about 1e-6) outside.
inline double chord_sag_bound(const Light& light, double r, double r_in, double floor_height,
                              double matrix_norm = 1.0) {
  const double l[3] = {light.position[0], light.position[1], light.position[2]};
  if (light.position[3] == 0.0) {
    const double cos_a = std::abs(l[1]) / std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    return matrix_norm * (r - r_in) / cos_a;
  }
  const double d = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);  // the centre is the origin
  const double height = l[1] - floor_height;
  const double g = std::acos(l[1] / d);  // the axis light -> centre against the floor's downward normal
  const double t = std::asin(r / d);
  return height * (t - std::asin(r_in / d)) / std::pow(std::cos(g + t), 2);
}

}  // namespace shadowcert::test_support
