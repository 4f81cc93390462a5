#include "contour/smooth_volume.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "contour/detail/lit_boundary.h"
#include "core/vector3.h"

namespace shadowcert {
namespace {

using detail::PointKey;

// Finite vertices by their exact doubles (two names of one point are one vertex), and their
// far vertices. A cut point set behind the surface is another vertex than the same point on it
// (a contour point without displacement, whose sides stay on the surface).
class VertexTable {
 public:
  explicit VertexTable(double cap_offset) : cap_offset_(cap_offset) {}
  // The vertex named by the point p; a cut point (on a triangle's edge or cut, with its unit
  // normal n; never a mesh vertex) is stored cap_offset behind the surface, at
  // p - cap_offset n (SmoothVolumeOptions).
  std::uint32_t finite(const Vec3& p, const Vec3* cut_normal = nullptr) {
    const bool behind = cut_normal != nullptr && cap_offset_ > 0.0;
    const auto [it, added] = finite_.emplace(std::pair{p, behind}, static_cast<std::uint32_t>(points_.size()));
    if (added) {
      Vec3 stored = p;
      if (behind)
        for (std::size_t k = 0; k < 3; ++k) stored[k] -= cap_offset_ * (*cut_normal)[k];
      points_.push_back(stored);
    }
    return it->second;
  }
  // A contour point's partner: a cut point, unless it is a mesh vertex.
  std::uint32_t partner(const ContourPoint& p) { return finite(p.partner, p.at_vertex ? nullptr : &p.normal); }
  [[nodiscard]] const std::vector<Vec3>& points() const { return points_; }

 private:
  double cap_offset_;
  std::map<std::pair<Vec3, bool>, std::uint32_t> finite_;
  std::vector<Vec3> points_;
};

// A point of a cap polygon: its name, where it is, and for a cut point its normal.
struct PolygonPoint {
  PointKey key;
  Vec3 position{};
  std::optional<Vec3> cut_normal;
};

struct Triangles {
  std::vector<std::array<std::uint32_t, 3>> list;
  void add(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (a == b || b == c || c == a) return;  // no area, and its edges cancel among themselves
    list.push_back({a, b, c});
  }
};

// Partner points to put between two boundary points of the lit and unlit parts, by the pair of
// keys (in order) that the piece runs between: from -> to, the points in that order.
struct Insertion {
  PointKey from;
  std::vector<ContourPoint> points;  // their partners are the points to insert
};
using Insertions = std::map<std::pair<PointKey, PointKey>, Insertion>;

// The partners between consecutive polygon points a -> b (reversed when the piece runs b -> a).
const std::vector<ContourPoint>* partners_between(const Insertions& insertions, const PointKey& a, const PointKey& b,
                                                  std::vector<ContourPoint>& reversed) {
  const auto it = insertions.find(a < b ? std::pair{a, b} : std::pair{b, a});
  if (it == insertions.end()) return nullptr;
  if (it->second.from == a) return &it->second.points;
  reversed.assign(it->second.points.rbegin(), it->second.points.rend());
  return &reversed;
}

std::size_t corner_index(const Triangle& t, std::uint32_t v) {
  for (std::size_t k = 0; k < 3; ++k)
    if (t[k] == v) return k;
  throw std::logic_error("smooth_shadow_volume: a vertex is not on its triangle");
}

// Triangle t's lit part (`want_lit`) or unlit part as a polygon (keys and points,
// counter-clockwise in t's order): its corners of that state, its own accurate points and, on a
// crease, the other side's point where it falls inside that part of the edge (a vertex of a
// crease piece).
std::vector<PolygonPoint> part_polygon(const SmoothCaster& c, const detail::CornerValues& f, std::uint32_t t,
                                       bool want_lit) {
  std::vector<PolygonPoint> polygon;
  const Triangle& tri = c.triangles[t];
  for (std::size_t k = 0; k < 3; ++k) {
    const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
    const std::array<double, 3> ft = f[t];
    const bool lit_a = detail::lit(ft[k]), lit_b = detail::lit(ft[(k + 1) % 3]);
    const bool in_a = lit_a == want_lit, in_b = lit_b == want_lit;
    if (in_a) polygon.push_back({detail::vertex_key(a), c.vertices[a], std::nullopt});
    // Parameter s from a to b of the cut points on this edge inside the part.
    std::vector<std::tuple<double, PointKey, SilhouettePoint>> cuts;
    double lo = in_a ? 0.0 : 1.0, hi = in_b ? 1.0 : 0.0;  // the part's interval [lo, hi] of the edge
    if (lit_a != lit_b) {
      const auto [key, p] = detail::edge_point(c, f, t, k);
      const double s = p.edge_from == a ? p.u : 1.0 - p.u;
      (in_a ? hi : lo) = key.kind == PointKey::vertex ? (key.a == a ? 0.0 : 1.0) : s;
      if (key.kind != PointKey::vertex) {
        cuts.emplace_back(s, key, p);
      } else if ((key.a == a && !in_a) || (key.a == b && !in_b)) {
        // The state changes at an end vertex whose own state is the other part's (f = 0 there,
        // lit by the fixed rule): this part still reaches that vertex, which is then a vertex of
        // its polygon, uncut. Without it a triangle lit only at that vertex lost its unlit part.
        cuts.emplace_back(key.a == a ? 0.0 : 1.0, key, detail::vertex_point(c, t, key.a));
      }
    }
    const std::uint32_t other = c.across[t][k];
    if (c.crease[t][k] && other != kBorder) {
      const std::size_t oa = corner_index(c.triangles[other], a), ob = corner_index(c.triangles[other], b);
      const std::array<double, 3> fo = f[other];
      if (detail::lit(fo[oa]) != detail::lit(fo[ob])) {
        const std::size_t k2 = ob;  // the other triangle's edge from b to a starts at its corner b
        const auto [key, p] = detail::edge_point(c, f, other, k2);
        const double s = p.edge_from == a ? p.u : 1.0 - p.u;
        if (key.kind != PointKey::vertex && s > lo && s < hi) cuts.emplace_back(s, key, p);
      }
    }
    std::sort(cuts.begin(), cuts.end(), [](const auto& x, const auto& y) { return std::get<0>(x) < std::get<0>(y); });
    for (const auto& [s, key, p] : cuts)
      polygon.push_back({key, p.position, key.kind == PointKey::vertex ? std::nullopt : std::optional<Vec3>(p.normal)});
  }
  return polygon;
}

}  // namespace

SmoothVolume smooth_shadow_volume(const SmoothCaster& caster, const Light& light, const SmoothVolumeOptions& options,
                                  std::span<const Sign> sides) {
  require_defined(light, "smooth_shadow_volume");
  const bool smooth = options.method == SilhouetteMethod::smooth;
  const bool discrete = options.method == SilhouetteMethod::discrete;
  if (smooth && !(options.epsilon > 0.0 && std::isfinite(options.epsilon)))
    throw std::invalid_argument("smooth_shadow_volume: epsilon must be finite and > 0");
  if (!(options.cap_offset >= 0.0 && std::isfinite(options.cap_offset)))
    throw std::invalid_argument("smooth_shadow_volume: the cap offset must be finite and >= 0");
  if (discrete && sides.size() != caster.triangles.size())
    throw std::invalid_argument("smooth_shadow_volume: discrete needs one light side per caster triangle");
  std::vector<std::uint8_t> lit_triangles;
  for (Sign side : sides) lit_triangles.push_back(side == Sign::positive);

  SmoothVolume volume;
  const detail::CornerValues f(caster, light);
  const detail::LitBoundary boundary =
      discrete ? detail::discrete_boundary(caster, lit_triangles) : detail::accurate_boundary(caster, f);
  const std::vector<detail::KeyedLoop> keyed = detail::chain(boundary);
  volume.loops = detail::loops_of(boundary, keyed);
  if (smooth) volume.contours = smooth_contour(caster, volume.loops, options.epsilon);
  // accurate with its cut caps set behind the surface: its "contour" is the loop itself, on the
  // surface, and a strip of no displacement joins it to the caps, so the shadow's boundary stays
  // the accurate silhouette (offsetting the sides with the caps would shrink the shadow).
  if (options.method == SilhouetteMethod::accurate && options.cap_offset > 0.0)
    for (const SilhouetteLoop& loop : volume.loops) {
      SmoothContour& contour = volume.contours.emplace_back();
      contour.closed = loop.closed;
      for (const SilhouettePoint& s : loop.points) {
        contour.loop_points.push_back(contour.points.size());
        contour.points.push_back({s.position, s.normal, s.position, s.edge_from == s.edge_to});
      }
    }

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
      Insertion& between = insertions[piece.from < piece.to ? std::pair{piece.from, piece.to}
                                                            : std::pair{piece.to, piece.from}];
      between.from = piece.from;
      for (std::size_t k = first; k < last; ++k) between.points.push_back(contour.points[k]);
    }
  }

  VertexTable vertices(options.cap_offset);
  Triangles x;  // the lit part, the unlit part reversed, the gap strip twice
  for (std::uint32_t t = 0; t < caster.triangles.size(); ++t) {
    const Triangle& tri = caster.triangles[t];
    if (discrete) {
      if (sides[t] == Sign::zero) continue;  // in the light's plane: casts nothing
      const std::uint32_t a = vertices.finite(caster.vertices[tri[0]]), b = vertices.finite(caster.vertices[tri[1]]),
                          c = vertices.finite(caster.vertices[tri[2]]);
      if (sides[t] == Sign::positive) x.add(a, b, c);
      else x.add(a, c, b);
      continue;
    }
    // The light in the plane the corner normals describe at every corner (a floor with the light
    // in its plane): as the exact side 0, the triangle casts nothing.
    const std::array<double, 3> ft = f[t];
    if (ft[0] == 0.0 && ft[1] == 0.0 && ft[2] == 0.0) continue;
    for (const bool want_lit : {true, false}) {
      const std::vector<PolygonPoint> polygon = part_polygon(caster, f, t, want_lit);
      std::vector<std::uint32_t> ring;
      std::vector<ContourPoint> reversed;
      for (std::size_t i = 0; i < polygon.size(); ++i) {
        const PolygonPoint& v = polygon[i];
        ring.push_back(vertices.finite(v.position, v.cut_normal ? &*v.cut_normal : nullptr));
        if (const std::vector<ContourPoint>* between =
                partners_between(insertions, v.key, polygon[(i + 1) % polygon.size()].key, reversed))
          for (const ContourPoint& p : *between) ring.push_back(vertices.partner(p));
      }
      ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
      while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
      for (std::size_t i = 1; i + 1 < ring.size(); ++i) {
        if (want_lit) x.add(ring[0], ring[i], ring[i + 1]);
        else x.add(ring[0], ring[i + 1], ring[i]);  // reversed: it faces the light
      }
    }
  }
  for (const SmoothContour& contour : volume.contours) {
    const std::size_t n = contour.points.size();
    for (std::size_t i = 0; i + 1 < n + (contour.closed ? 1 : 0); ++i) {
      const ContourPoint& p = contour.points[i];
      const ContourPoint& q = contour.points[(i + 1) % n];
      const std::uint32_t p0 = vertices.partner(p), q0 = vertices.partner(q);
      const std::uint32_t p1 = vertices.finite(p.position), q1 = vertices.finite(q.position);
      for (int copy = 0; copy < 2; ++copy) {  // once for the lit part, once for the unlit one
        x.add(q0, p0, p1);
        x.add(q0, p1, q1);
      }
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
