#include "contour/silhouette_loop.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "core/vector3.h"

namespace shadowcert {
namespace {

// Which loop point a piece starts or ends at: a mesh vertex; the one point of a smooth edge (both
// triangles compute it alike); or the point of one side of a crease edge.
struct PointKey {
  enum Kind : std::uint8_t { vertex, smooth_edge, crease_side } kind = vertex;
  std::uint32_t a = 0, b = 0, side = 0;
  auto operator<=>(const PointKey&) const = default;
};

struct Piece {
  PointKey from, to;
};

// The pieces of a silhouette and the points their keys name.
struct Pieces {
  std::vector<Piece> pieces;
  std::map<PointKey, SilhouettePoint> points;

  void add(const PointKey& from, const SilhouettePoint& p, const PointKey& to, const SilhouettePoint& q) {
    if (from == to) return;
    points.emplace(from, p);
    points.emplace(to, q);
    pieces.push_back({from, to});
  }
};

// Chains the pieces head to tail into loops: first from every start no piece ends at (the open
// loops, which end at borders), then the cycles. Where several pieces leave one point (loops
// touching at a vertex), the first unused one in key order is taken: the loops still cover
// every piece once, closed where the boundary is.
std::vector<SilhouetteLoop> chain(const Pieces& all) {
  std::multimap<PointKey, std::size_t> leaving;
  std::map<PointKey, std::size_t> arriving;
  for (std::size_t i = 0; i < all.pieces.size(); ++i) {
    leaving.emplace(all.pieces[i].from, i);
    ++arriving[all.pieces[i].to];
  }
  std::vector<bool> used(all.pieces.size(), false);
  std::vector<SilhouetteLoop> loops;
  const auto trace = [&](std::size_t first) {
    SilhouetteLoop loop;
    const PointKey start = all.pieces[first].from;
    loop.points.push_back(all.points.at(start));
    std::size_t piece = first;
    while (true) {
      used[piece] = true;
      const PointKey at = all.pieces[piece].to;
      if (at == start) {
        loop.closed = true;
        break;
      }
      loop.points.push_back(all.points.at(at));
      std::size_t next = all.pieces.size();
      for (auto [it, end] = leaving.equal_range(at); it != end; ++it)
        if (!used[it->second]) {
          next = it->second;
          break;
        }
      if (next == all.pieces.size()) break;  // a border: the loop ends here
      piece = next;
    }
    loops.push_back(std::move(loop));
  };
  for (std::size_t i = 0; i < all.pieces.size(); ++i)
    if (!used[i] && !arriving.contains(all.pieces[i].from)) trace(i);
  for (std::size_t i = 0; i < all.pieces.size(); ++i)
    if (!used[i]) trace(i);
  return loops;
}

std::size_t corner_index(const Triangle& t, std::uint32_t v) {
  for (std::size_t k = 0; k < 3; ++k)
    if (t[k] == v) return k;
  throw std::logic_error("silhouette: a vertex is not on its triangle");
}

SilhouettePoint vertex_point(const SmoothCaster& c, std::uint32_t t, std::uint32_t v) {
  return {c.vertices[v], c.normals[t][corner_index(c.triangles[t], v)], v, v, 0.0, t};
}

// The accurate point on edge k of triangle t (its two corners have opposite lit states), and its
// key, computed from the edge's lower vertex index to its higher one.
std::pair<PointKey, SilhouettePoint> edge_point(const SmoothCaster& c, const std::vector<std::array<double, 3>>& f,
                                                std::uint32_t t, std::size_t k) {
  const Triangle& tri = c.triangles[t];
  std::size_t ci = k, cj = (k + 1) % 3;
  if (tri[ci] > tri[cj]) std::swap(ci, cj);
  const std::uint32_t i = tri[ci], j = tri[cj];
  const double fi = f[t][ci], fj = f[t][cj];
  const double u = fi / (fi - fj);  // nonzero denominator: the signs differ (0 counts as lit)
  if (u == 0.0) return {{PointKey::vertex, i, i, 0}, vertex_point(c, t, i)};
  if (u == 1.0) return {{PointKey::vertex, j, j, 0}, vertex_point(c, t, j)};
  const Vec3& vi = c.vertices[i];
  const Vec3& vj = c.vertices[j];
  const Vec3& ni = c.normals[t][ci];
  const Vec3& nj = c.normals[t][cj];
  SilhouettePoint p;
  for (std::size_t x = 0; x < 3; ++x) {
    p.position[x] = (1.0 - u) * vi[x] + u * vj[x];
    p.normal[x] = (1.0 - u) * ni[x] + u * nj[x];
  }
  p.normal = normalized(p.normal);
  p.edge_from = i;
  p.edge_to = j;
  p.u = u;
  p.triangle = t;
  const PointKey key = c.crease[t][k] ? PointKey{PointKey::crease_side, i, j, t} : PointKey{PointKey::smooth_edge, i, j, 0};
  return {key, p};
}

bool lit(double f) { return f >= 0.0; }

}  // namespace

std::vector<std::array<double, 3>> corner_light_values(const SmoothCaster& caster, const Light& light) {
  require_defined(light, "corner_light_values");
  const auto& l = light.position;
  std::vector<std::array<double, 3>> f(caster.triangles.size());
  for (std::size_t t = 0; t < f.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& v = caster.vertices[caster.triangles[t][k]];
      const Vec3 towards{l[0] - l[3] * v[0], l[1] - l[3] * v[1], l[2] - l[3] * v[2]};
      f[t][k] = dot(caster.normals[t][k], towards);
    }
  return f;
}

std::vector<SilhouetteLoop> discrete_silhouette(const SmoothCaster& caster, std::span<const std::uint8_t> lit_triangles) {
  if (lit_triangles.size() != caster.triangles.size())
    throw std::invalid_argument("discrete_silhouette: one lit flag per triangle is needed");
  Pieces pieces;
  for (std::uint32_t t = 0; t < caster.triangles.size(); ++t) {
    if (lit_triangles[t] == 0) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t other = caster.across[t][k];
      if (other == kBorder || lit_triangles[other] != 0) continue;
      const std::uint32_t a = caster.triangles[t][k], b = caster.triangles[t][(k + 1) % 3];
      pieces.add({PointKey::vertex, a, a, 0}, vertex_point(caster, t, a), {PointKey::vertex, b, b, 0},
                 vertex_point(caster, t, b));
    }
  }
  return chain(pieces);
}

std::vector<SilhouetteLoop> accurate_silhouette(const SmoothCaster& caster, const Light& light) {
  const std::vector<std::array<double, 3>> f = corner_light_values(caster, light);
  Pieces pieces;
  // 1. Inside each triangle: its lit part's boundary runs along the zero segment from the edge
  // where the corners go lit to unlit (in the triangle's order) to the edge where they go back.
  for (std::uint32_t t = 0; t < caster.triangles.size(); ++t) {
    std::size_t leaving = 3, entering = 3;
    for (std::size_t k = 0; k < 3; ++k) {
      const bool here = lit(f[t][k]), next = lit(f[t][(k + 1) % 3]);
      if (here && !next) leaving = k;
      if (!here && next) entering = k;
    }
    if (leaving == 3) continue;  // one lit state at every corner: no zero set
    const auto [from_key, from] = edge_point(caster, f, t, leaving);
    const auto [to_key, to] = edge_point(caster, f, t, entering);
    pieces.add(from_key, from, to_key, to);
  }
  // 2. Along each crease: the parts of the edge lit on one side only, with the lit side on the
  // left (its own order along the edge), and a zero-length piece where both sides' points
  // coincide with both lit on the same end.
  for (std::uint32_t t = 0; t < caster.triangles.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t other = caster.across[t][k];
      if (!caster.crease[t][k] || other == kBorder || other < t) continue;
      const std::uint32_t a = caster.triangles[t][k], b = caster.triangles[t][(k + 1) % 3];
      const std::size_t k2 = corner_index(caster.triangles[other], b);  // its edge k2 runs b -> a
      // Per side: lit at a, lit at b, and where the state changes (parameter s from a to b).
      struct Side {
        bool at_a = false, at_b = false;
        double s = -1.0;
        PointKey key;
        SilhouettePoint point;
      };
      const auto side = [&](std::uint32_t tri, std::size_t corner_a, std::size_t corner_b, std::size_t edge) {
        Side x;
        x.at_a = lit(f[tri][corner_a]);
        x.at_b = lit(f[tri][corner_b]);
        if (x.at_a != x.at_b) {
          std::tie(x.key, x.point) = edge_point(caster, f, tri, edge);
          x.s = x.point.edge_from == a ? x.point.u : 1.0 - x.point.u;
          if (x.key.kind == PointKey::vertex) x.s = x.key.a == a ? 0.0 : 1.0;
        }
        return x;
      };
      const Side one = side(t, k, (k + 1) % 3, k);
      const Side two = side(other, corner_index(caster.triangles[other], a), k2, k2);
      const auto lit_at = [](const Side& x, double s) {
        if (x.at_a == x.at_b) return x.at_a;
        return x.at_a ? s < x.s : s > x.s;
      };
      const PointKey key_a{PointKey::vertex, a, a, 0}, key_b{PointKey::vertex, b, b, 0};
      // The point at a cut; where both sides change state at one s, the side the piece is lit on.
      const auto at = [&](double s, bool on_one) -> std::pair<PointKey, SilhouettePoint> {
        if (s == 0.0) return {key_a, vertex_point(caster, t, a)};
        if (s == 1.0) return {key_b, vertex_point(caster, t, b)};
        if (s == one.s && (on_one || s != two.s)) return {one.key, one.point};
        return {two.key, two.point};
      };
      std::vector<double> cuts{0.0, 1.0};
      if (one.s >= 0.0) cuts.push_back(one.s);
      if (two.s >= 0.0) cuts.push_back(two.s);
      std::sort(cuts.begin(), cuts.end());
      cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const double mid = 0.5 * (cuts[c] + cuts[c + 1]);
        const bool lit_one = lit_at(one, mid), lit_two = lit_at(two, mid);
        if (lit_one == lit_two) continue;
        const auto [x_key, x] = at(cuts[c], lit_one);
        const auto [y_key, y] = at(cuts[c + 1], lit_one);
        if (lit_one) pieces.add(x_key, x, y_key, y);  // t's order, a -> b
        else pieces.add(y_key, y, x_key, x);          // the other side's order, b -> a
      }
      if (one.s >= 0.0 && one.s == two.s && one.at_a == two.at_a) {
        // Both sides lit on the same end and changing at one point: t's zero segment leaves
        // from its point iff a is lit, and the other side's arrives at its own.
        if (one.at_a) pieces.add(two.key, two.point, one.key, one.point);
        else pieces.add(one.key, one.point, two.key, two.point);
      }
    }
  return chain(pieces);
}

}  // namespace shadowcert
