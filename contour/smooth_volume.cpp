#include "contour/smooth_volume.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "contour/detail/lit_boundary.h"
#include "core/vector3.h"

namespace shadowcert {
namespace {

using detail::PointKey;

// Finite vertices by their exact doubles (two names of one point are one vertex), and their
// far vertices.
class VertexTable {
 public:
  std::uint32_t finite(const Vec3& p) {
    const auto [it, added] = finite_.emplace(p, static_cast<std::uint32_t>(points_.size()));
    if (added) points_.push_back(p);
    return it->second;
  }
  [[nodiscard]] const std::vector<Vec3>& points() const { return points_; }

 private:
  std::map<Vec3, std::uint32_t> finite_;
  std::vector<Vec3> points_;
};

struct Triangles {
  std::vector<std::array<std::uint32_t, 3>> list;
  void add(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (a == b || b == c || c == a) return;  // no area, and its edges cancel among themselves
    list.push_back({a, b, c});
  }
};

// Partner points to put between two consecutive boundary points of one triangle's lit part.
using Insertions = std::map<std::tuple<std::uint32_t, PointKey, PointKey>, std::vector<Vec3>>;

std::size_t corner_index(const Triangle& t, std::uint32_t v) {
  for (std::size_t k = 0; k < 3; ++k)
    if (t[k] == v) return k;
  throw std::logic_error("smooth_shadow_volume: a vertex is not on its triangle");
}

// Triangle t's lit part as a polygon (keys and points, counter-clockwise in t's order): its lit
// corners, its own accurate points and, on a crease, the other side's point where it falls
// inside t's lit part of the edge (a vertex of a crease piece).
std::vector<std::pair<PointKey, Vec3>> lit_polygon(const SmoothCaster& c, std::span<const std::array<double, 3>> f,
                                                   std::uint32_t t) {
  std::vector<std::pair<PointKey, Vec3>> polygon;
  const Triangle& tri = c.triangles[t];
  for (std::size_t k = 0; k < 3; ++k) {
    const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
    const bool lit_a = detail::lit(f[t][k]), lit_b = detail::lit(f[t][(k + 1) % 3]);
    if (lit_a) polygon.emplace_back(detail::vertex_key(a), c.vertices[a]);
    // Parameter s from a to b of the cut points on this edge inside t's lit part.
    std::vector<std::tuple<double, PointKey, Vec3>> cuts;
    double lo = lit_a ? 0.0 : 1.0, hi = lit_b ? 1.0 : 0.0;  // t's lit interval [lo, hi]
    if (lit_a != lit_b) {
      const auto [key, p] = detail::edge_point(c, f, t, k);
      const double s = p.edge_from == a ? p.u : 1.0 - p.u;
      (lit_a ? hi : lo) = key.kind == PointKey::vertex ? (key.a == a ? 0.0 : 1.0) : s;
      if (key.kind != PointKey::vertex) cuts.emplace_back(s, key, p.position);
    }
    const std::uint32_t other = c.across[t][k];
    if (c.crease[t][k] && other != kBorder) {
      const std::size_t oa = corner_index(c.triangles[other], a), ob = corner_index(c.triangles[other], b);
      if (detail::lit(f[other][oa]) != detail::lit(f[other][ob])) {
        const std::size_t k2 = ob;  // the other triangle's edge from b to a starts at its corner b
        const auto [key, p] = detail::edge_point(c, f, other, k2);
        const double s = p.edge_from == a ? p.u : 1.0 - p.u;
        if (key.kind != PointKey::vertex && s > lo && s < hi) cuts.emplace_back(s, key, p.position);
      }
    }
    std::sort(cuts.begin(), cuts.end(), [](const auto& x, const auto& y) { return std::get<0>(x) < std::get<0>(y); });
    for (const auto& [s, key, p] : cuts) polygon.emplace_back(key, p);
  }
  return polygon;
}

}  // namespace

SmoothVolume smooth_shadow_volume(const SmoothCaster& caster, const Light& light, const SmoothVolumeOptions& options,
                                  std::span<const std::uint8_t> lit_triangles) {
  require_defined(light, "smooth_shadow_volume");
  const bool smooth = options.method == SilhouetteMethod::smooth;
  const bool discrete = options.method == SilhouetteMethod::discrete;
  if (smooth && !(options.epsilon > 0.0 && std::isfinite(options.epsilon)))
    throw std::invalid_argument("smooth_shadow_volume: epsilon must be finite and > 0");
  if (discrete && lit_triangles.size() != caster.triangles.size())
    throw std::invalid_argument("smooth_shadow_volume: discrete needs one lit flag per caster triangle");

  SmoothVolume volume;
  const std::vector<std::array<double, 3>> f = discrete ? std::vector<std::array<double, 3>>{}
                                                         : corner_light_values(caster, light);
  const detail::LitBoundary boundary =
      discrete ? detail::discrete_boundary(caster, lit_triangles) : detail::accurate_boundary(caster, f);
  const std::vector<detail::KeyedLoop> keyed = detail::chain(boundary);
  volume.loops = detail::loops_of(boundary, keyed);
  if (smooth) volume.contours = smooth_contour(caster, volume.loops, options.epsilon);

  // The partners the subdivision added, by the piece of the lit part's boundary they lie on.
  Insertions insertions;
  for (std::size_t l = 0; l < volume.contours.size(); ++l) {
    const SmoothContour& contour = volume.contours[l];
    const detail::KeyedLoop& loop = keyed[l];
    for (std::size_t i = 0; i < loop.pieces.size(); ++i) {
      const detail::Piece& piece = boundary.pieces[loop.pieces[i]];
      if (piece.triangle == kBorder) continue;  // a crease point's zero-length piece
      const std::size_t first = contour.loop_points[i] + 1;
      const std::size_t last = i + 1 < contour.loop_points.size() ? contour.loop_points[i + 1] : contour.points.size();
      std::vector<Vec3>& between = insertions[{piece.triangle, piece.from, piece.to}];
      for (std::size_t k = first; k < last; ++k) between.push_back(contour.points[k].partner);
    }
  }

  VertexTable vertices;
  Triangles x;  // front cap and gap strip
  for (std::uint32_t t = 0; t < caster.triangles.size(); ++t) {
    if (discrete) {
      if (lit_triangles[t] == 0) continue;
      const Triangle& tri = caster.triangles[t];
      x.add(vertices.finite(caster.vertices[tri[0]]), vertices.finite(caster.vertices[tri[1]]),
            vertices.finite(caster.vertices[tri[2]]));
      continue;
    }
    const std::vector<std::pair<PointKey, Vec3>> polygon = lit_polygon(caster, f, t);
    std::vector<std::uint32_t> ring;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      ring.push_back(vertices.finite(polygon[i].second));
      const auto it = insertions.find({t, polygon[i].first, polygon[(i + 1) % polygon.size()].first});
      if (it != insertions.end())
        for (const Vec3& p : it->second) ring.push_back(vertices.finite(p));
    }
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    for (std::size_t i = 1; i + 1 < ring.size(); ++i) x.add(ring[0], ring[i], ring[i + 1]);
  }
  for (const SmoothContour& contour : volume.contours) {
    const std::size_t n = contour.points.size();
    for (std::size_t i = 0; i + 1 < n + (contour.closed ? 1 : 0); ++i) {
      const ContourPoint& p = contour.points[i];
      const ContourPoint& q = contour.points[(i + 1) % n];
      const std::uint32_t p0 = vertices.finite(p.partner), q0 = vertices.finite(q.partner);
      const std::uint32_t p1 = vertices.finite(p.position), q1 = vertices.finite(q.position);
      x.add(q0, p0, p1);
      x.add(q0, p1, q1);
    }
  }
  volume.cap_triangles = x.list.size();

  // X's boundary: its directed edges less the reversed ones.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : x.list)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (a < b) ++edges[{a, b}];
      else --edges[{b, a}];
    }

  // Homogeneous vertices: [0, n) finite, then far ones (n + i for finite i; the one point n for
  // a directional light), every difference taken in double and rounded once.
  const std::vector<Vec3>& points = vertices.points();
  const auto n = static_cast<std::uint32_t>(points.size());
  const auto& l = light.position;
  HomogeneousMesh& mesh = volume.mesh;
  for (const Vec3& p : points)
    mesh.vertices.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]), 1.0f});
  if (light.directional()) {
    mesh.vertices.push_back({static_cast<float>(-l[0]), static_cast<float>(-l[1]), static_cast<float>(-l[2]), 0.0f});
  } else {
    for (const Vec3& p : points)
      mesh.vertices.push_back({static_cast<float>(p[0] - l[0]), static_cast<float>(p[1] - l[1]),
                               static_cast<float>(p[2] - l[2]), 0.0f});
  }
  const auto far = [&](std::uint32_t v) { return light.directional() ? n : n + v; };
  mesh.triangles = x.list;
  for (const auto& [edge, net] : edges) {
    const auto [lo, hi] = edge;
    const std::uint32_t a = net > 0 ? lo : hi, b = net > 0 ? hi : lo;  // the boundary runs a -> b
    for (int m = 0; m < std::abs(net); ++m) {
      mesh.triangles.push_back({b, a, far(a)});
      if (!light.directional()) mesh.triangles.push_back({b, far(a), far(b)});
    }
  }
  volume.side_triangles = mesh.triangles.size() - x.list.size();
  if (!light.directional())
    for (const auto& t : x.list) mesh.triangles.push_back({far(t[0]), far(t[2]), far(t[1])});
  return volume;
}

}  // namespace shadowcert
