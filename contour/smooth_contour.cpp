#include "contour/smooth_contour.h"

#include <cmath>
#include <stdexcept>

#include "core/vector3.h"

namespace shadowcert {
namespace {

Vec3 scaled(const Vec3& v, double s) { return {v[0] * s, v[1] * s, v[2] * s}; }
Vec3 sum(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
double length(const Vec3& v) { return std::sqrt(dot(v, v)); }
Vec3 midpoint(const Vec3& a, const Vec3& b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])}; }

std::size_t corner_index(const Triangle& t, std::uint32_t v) {
  for (std::size_t k = 0; k < 3; ++k)
    if (t[k] == v) return k;
  throw std::logic_error("smooth_contour: a loop point's edge is not on its triangle");
}

// Step (b): the loop point moved onto its mesh edge's Hermite curve.
ContourPoint displaced(const SmoothCaster& c, const SilhouettePoint& s) {
  ContourPoint p{s.position, s.normal, s.position, s.edge_from == s.edge_to};
  if (p.at_vertex) return p;  // at a mesh vertex
  const Triangle& t = c.triangles[s.triangle];
  const Vec3& vi = c.vertices[s.edge_from];
  const Vec3& vj = c.vertices[s.edge_to];
  const Vec3& ni = c.normals[s.triangle][corner_index(t, s.edge_from)];
  const Vec3& nj = c.normals[s.triangle][corner_index(t, s.edge_to)];
  p.position = hermite_point(vi, vj, hermite_tangent(vi, vj, ni), hermite_tangent(vi, vj, nj), s.u);
  return p;
}

// A segment's end as its subdivision sees it: at a mesh vertex, with the corner normal of the
// segment's own triangle `t` there (a loop point at a crease vertex belongs to segments of both
// sides, each with its side's normal: the paper's doubled crease point); elsewhere as it is.
ContourPoint segment_end(const SmoothCaster& c, ContourPoint p, const SilhouettePoint& s, std::uint32_t t) {
  if (s.edge_from != s.edge_to || t == kBorder) return p;
  p.normal = c.normals[t][corner_index(c.triangles[t], s.edge_from)];
  return p;
}

// Step (c), Listing 1: the points strictly between a and b, in order, appended to `out`.
void subdivide(const ContourPoint& a, const ContourPoint& b, double epsilon, std::uint32_t depth,
               std::vector<ContourPoint>& out) {
  if (depth == kMaxSubdivisionDepth) return;
  const Vec3 t0 = hermite_tangent(a.position, b.position, a.normal);
  const Vec3 t1 = hermite_tangent(a.position, b.position, b.normal);
  const Vec3 p = hermite_point(a.position, b.position, t0, t1, 0.5);
  if (!(length(difference(p, midpoint(a.position, b.position))) >= epsilon)) return;
  const Vec3 n = sum(a.normal, b.normal);
  const ContourPoint mid{p, dot(n, n) > 0.0 ? normalized(n) : a.normal, midpoint(a.partner, b.partner)};
  subdivide(a, mid, epsilon, depth + 1, out);
  out.push_back(mid);
  subdivide(mid, b, epsilon, depth + 1, out);
}

}  // namespace

Vec3 hermite_point(const Vec3& p0, const Vec3& p1, const Vec3& t0, const Vec3& t1, double u) {
  const double u2 = u * u, u3 = u2 * u;
  const double h00 = 2 * u3 - 3 * u2 + 1, h01 = -2 * u3 + 3 * u2, h10 = u3 - 2 * u2 + u, h11 = u3 - u2;
  Vec3 p{};
  for (std::size_t k = 0; k < 3; ++k) p[k] = h00 * p0[k] + h01 * p1[k] + h10 * t0[k] + h11 * t1[k];
  return p;
}

Vec3 hermite_tangent(const Vec3& p0, const Vec3& p1, const Vec3& n) {
  const Vec3 e = difference(p1, p0);
  const double e_length = length(e);
  const Vec3 t = difference(e, scaled(n, dot(n, e)));
  const double t_length = length(t);
  if (!(e_length > 0.0) || !(t_length > 0.0)) return {0.0, 0.0, 0.0};
  return scaled(t, e_length / t_length);
}

std::vector<SmoothContour> smooth_contour(const SmoothCaster& caster, const std::vector<SilhouetteLoop>& loops,
                                          double epsilon) {
  if (!(epsilon > 0.0) || !std::isfinite(epsilon))
    throw std::invalid_argument("smooth_contour: epsilon must be finite and > 0");
  std::vector<SmoothContour> out;
  out.reserve(loops.size());
  for (const SilhouetteLoop& loop : loops) {
    SmoothContour contour;
    contour.closed = loop.closed;
    std::vector<ContourPoint> moved;
    moved.reserve(loop.points.size());
    for (const SilhouettePoint& s : loop.points) moved.push_back(displaced(caster, s));
    const std::size_t n = moved.size();
    for (std::size_t i = 0; i < n; ++i) {
      contour.loop_points.push_back(contour.points.size());
      contour.points.push_back(moved[i]);
      if (i + 1 < n || loop.closed) {
        const std::size_t j = (i + 1) % n;
        const std::uint32_t t = i < loop.segment_triangles.size() ? loop.segment_triangles[i] : kBorder;
        subdivide(segment_end(caster, moved[i], loop.points[i], t), segment_end(caster, moved[j], loop.points[j], t),
                  epsilon, 0, contour.points);
      }
    }
    out.push_back(std::move(contour));
  }
  return out;
}

}  // namespace shadowcert
