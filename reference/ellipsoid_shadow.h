#pragma once
// The analytic shadow of an ellipsoid on a plane: the truth the smooth-silhouette methods'
// shadow boundaries are measured against (docs/smooth-silhouettes.md, "Error against the
// analytic shadow"). An ellipsoid is an affine image of the unit sphere, x = c + A u with
// |u| <= 1 (a uv_sphere or icosphere caster under any affine transform knows its own).
//
// The boundary: in the sphere's frame (u = A^-1 (x - c)) the light's tangent cone touches the
// unit sphere along a circle (for a point light at distance d > 1 from the centre: the circle
// u . l = 1 of radius sqrt(1 - 1 / d^2); for a directional light: the great circle across it).
// Mapped back by A it touches the ellipsoid along an ellipse, whose projection from the light
// onto the receiver plane is the shadow's boundary, a conic.
#include <cstddef>
#include <span>
#include <vector>

#include "core/ellipsoid.h"
#include "core/light.h"
#include "core/soup.h"

namespace shadowcert {

struct Plane {
  Vec3 point{};
  Vec3 normal{0, 1, 0};  // nonzero
};

// The shadow boundary on `plane` as `samples` points (a closed polyline, in order around it),
// the tangent curve sampled at equal angles in the sphere's frame. Throws std::invalid_argument
// ("ellipsoid_shadow_boundary: ...") when the light is inside the ellipsoid or samples < 3, and
// shadow_on_plane's error when a tangent ray never meets the plane (the shadow is no ellipse).
[[nodiscard]] std::vector<Vec3> ellipsoid_shadow_boundary(const Ellipsoid& ellipsoid, const Light& light,
                                                          const Plane& plane, std::size_t samples);

// Where the shadow of `point` falls on `plane`: the line from the light through it (a point
// light), or along -l (a directional light towards l), met with the plane. Throws
// std::invalid_argument("shadow_on_plane: ...") when that line is parallel to the plane or the
// plane is not beyond the point.
[[nodiscard]] Vec3 shadow_on_plane(const Vec3& point, const Light& light, const Plane& plane);

struct BoundaryDistance {
  double max = 0.0;   // the largest distance from the method's boundary to the truth
  double mean = 0.0;  // its mean over the method's boundary (by arc length)
};

// The distance from a method's shadow boundary (a polyline on the plane, `closed` or not) to the
// true one (`truth`, a closed polyline as from ellipsoid_shadow_boundary): every method segment
// sampled at `per_segment` points (its ends included), each point's distance to the nearest
// truth segment. Throws std::invalid_argument on fewer than 2 method points or 3 truth points.
[[nodiscard]] BoundaryDistance boundary_distance(std::span<const Vec3> method, bool closed, std::span<const Vec3> truth,
                                                 std::size_t per_segment = 8);

}  // namespace shadowcert
