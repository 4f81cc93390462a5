#include "reference/ellipsoid_shadow.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/portable_math.h"
#include "core/vector3.h"

namespace shadowcert {
namespace {

Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 scale(const Vec3& v, double s) { return {v[0] * s, v[1] * s, v[2] * s}; }

// A x and A^-1 x for the ellipsoid's axes (columns of A).
Vec3 apply(const Ellipsoid& e, const Vec3& u) {
  return add(add(scale(e.axes[0], u[0]), scale(e.axes[1], u[1])), scale(e.axes[2], u[2]));
}
Vec3 solve(const Ellipsoid& e, const Vec3& x) {  // Cramer's rule
  const double det = det3(e.axes[0], e.axes[1], e.axes[2]);
  if (!(std::abs(det) > 0.0)) throw std::invalid_argument("ellipsoid_shadow_boundary: the axes are dependent");
  return {det3(x, e.axes[1], e.axes[2]) / det, det3(e.axes[0], x, e.axes[2]) / det, det3(e.axes[0], e.axes[1], x) / det};
}

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = difference(b, a), ap = difference(p, a);
  const double l2 = dot(ab, ab);
  const double s = l2 > 0.0 ? std::clamp(dot(ab, ap) / l2, 0.0, 1.0) : 0.0;
  const Vec3 d = difference(ap, scale(ab, s));
  return std::sqrt(dot(d, d));
}

}  // namespace

Vec3 shadow_on_plane(const Vec3& point, const Light& light, const Plane& plane) {
  require_defined(light, "shadow_on_plane");
  const auto& l = light.position;
  // The ray from the point away from the light: direction point - l (point light) or -l.
  const Vec3 away = light.directional() ? Vec3{-l[0], -l[1], -l[2]} : difference(point, {l[0], l[1], l[2]});
  const double along = dot(away, plane.normal);
  if (!(std::abs(along) > 0.0)) throw std::invalid_argument("shadow_on_plane: the ray is parallel to the plane");
  const double s = dot(difference(plane.point, point), plane.normal) / along;
  if (!(s >= 0.0)) throw std::invalid_argument("shadow_on_plane: the plane is not beyond the point");
  return add(point, scale(away, s));
}

std::vector<Vec3> ellipsoid_shadow_boundary(const Ellipsoid& e, const Light& light, const Plane& plane,
                                            std::size_t samples) {
  require_defined(light, "ellipsoid_shadow_boundary");
  if (samples < 3) throw std::invalid_argument("ellipsoid_shadow_boundary: at least 3 samples");
  const auto& l = light.position;
  // The light in the sphere's frame: a point, or a direction (A^-1 of the linear part).
  const Vec3 lu = light.directional() ? solve(e, {l[0], l[1], l[2]}) : solve(e, difference({l[0], l[1], l[2]}, e.centre));
  const double d = std::sqrt(dot(lu, lu));
  if (!light.directional() && !(d > 1.0))
    throw std::invalid_argument("ellipsoid_shadow_boundary: the light is inside the ellipsoid");
  // The tangent circle: centre q along lu, radius r, in the plane spanned by two unit vectors
  // perpendicular to lu.
  const Vec3 axis = scale(lu, 1.0 / d);
  const double offset = light.directional() ? 0.0 : 1.0 / d;
  const double radius = std::sqrt(1.0 - offset * offset);
  const Vec3 helper = std::abs(axis[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 b1 = normalized(cross(axis, helper));
  const Vec3 b2 = cross(axis, b1);
  std::vector<Vec3> boundary;
  boundary.reserve(samples);
  for (std::size_t i = 0; i < samples; ++i) {
    const double angle = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(samples);
    const Vec3 u = add(scale(axis, offset), add(scale(b1, radius * portable::cos(angle)), scale(b2, radius * portable::sin(angle))));
    boundary.push_back(shadow_on_plane(add(e.centre, apply(e, u)), light, plane));
  }
  return boundary;
}

BoundaryDistance boundary_distance(std::span<const Vec3> method, bool closed, std::span<const Vec3> truth,
                                   std::size_t per_segment) {
  if (method.size() < 2 || truth.size() < 3 || per_segment < 2)
    throw std::invalid_argument("boundary_distance: too few points");
  const auto to_truth = [&](const Vec3& p) {
    double best = INFINITY;
    for (std::size_t i = 0; i < truth.size(); ++i)
      best = std::min(best, distance_to_segment(p, truth[i], truth[(i + 1) % truth.size()]));
    return best;
  };
  BoundaryDistance out;
  double weighted = 0.0, length = 0.0;
  const std::size_t segments = closed ? method.size() : method.size() - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    const Vec3& a = method[i];
    const Vec3& b = method[(i + 1) % method.size()];
    const double seg = std::sqrt(dot(difference(b, a), difference(b, a)));
    double sum = 0.0;
    for (std::size_t k = 0; k < per_segment; ++k) {
      const double s = static_cast<double>(k) / static_cast<double>(per_segment - 1);
      const double dist = to_truth(add(a, scale(difference(b, a), s)));
      out.max = std::max(out.max, dist);
      sum += dist;
    }
    weighted += seg * sum / static_cast<double>(per_segment);
    length += seg;
  }
  out.mean = length > 0.0 ? weighted / length : out.max;
  return out;
}

}  // namespace shadowcert
