#include "contour/detail/lit_boundary.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include "core/vector3.h"

namespace shadowcert::detail {
namespace {

std::size_t corner_index(const Triangle& t, std::uint32_t v) {
  for (std::size_t k = 0; k < 3; ++k)
    if (t[k] == v) return k;
  throw std::logic_error("silhouette: a vertex is not on its triangle");
}

}  // namespace

void LitBoundary::add(const PointKey& from, const SilhouettePoint& p, const PointKey& to, const SilhouettePoint& q,
                      std::uint32_t triangle) {
  if (from == to) return;
  points.emplace(from, p);
  points.emplace(to, q);
  pieces.push_back({from, to, triangle});
}


// Chains the pieces head to tail into loops: first from every start no piece ends at (the open
// loops, which end at borders), then the cycles. Where several pieces leave one point (loops
// touching at a vertex), the first unused one in key order is taken: the loops still cover
// every piece once, closed where the boundary is.
std::vector<KeyedLoop> chain(const LitBoundary& all) {
  std::multimap<PointKey, std::size_t> leaving;
  std::map<PointKey, std::size_t> arriving;
  for (std::size_t i = 0; i < all.pieces.size(); ++i) {
    leaving.emplace(all.pieces[i].from, i);
    ++arriving[all.pieces[i].to];
  }
  std::vector<bool> used(all.pieces.size(), false);
  std::vector<KeyedLoop> loops;
  const auto trace = [&](std::size_t first) {
    KeyedLoop loop;
    const PointKey start = all.pieces[first].from;
    loop.keys.push_back(start);
    std::size_t piece = first;
    while (true) {
      used[piece] = true;
      loop.pieces.push_back(piece);
      const PointKey at = all.pieces[piece].to;
      if (at == start) {
        loop.closed = true;
        break;
      }
      loop.keys.push_back(at);
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

SilhouettePoint vertex_point(const SmoothCaster& c, std::uint32_t t, std::uint32_t v) {
  return {c.vertices[v], c.normals[t][corner_index(c.triangles[t], v)], v, v, 0.0, t};
}

// The accurate point on edge k of triangle t (its two corners have opposite lit states), and its
// key, computed from the edge's lower vertex index to its higher one.
std::pair<PointKey, SilhouettePoint> edge_point(const SmoothCaster& c, const CornerValues& f, std::uint32_t t,
                                                std::size_t k) {
  const Triangle& tri = c.triangles[t];
  std::size_t ci = k, cj = (k + 1) % 3;
  if (tri[ci] > tri[cj]) std::swap(ci, cj);
  const std::uint32_t i = tri[ci], j = tri[cj];
  const std::array<double, 3> ft = f[t];
  const double fi = ft[ci], fj = ft[cj];
  const double u = fi / (fi - fj);  // nonzero denominator: the signs differ (0 counts as lit)
  if (u == 0.0) return {vertex_key(i), vertex_point(c, t, i)};
  if (u == 1.0) return {vertex_key(j), vertex_point(c, t, j)};
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


LitBoundary discrete_boundary(const SmoothCaster& caster, std::span<const std::uint8_t> lit_triangles) {
  LitBoundary pieces;
  for (std::uint32_t t = 0; t < caster.triangles.size(); ++t) {
    if (lit_triangles[t] == 0) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t other = caster.across[t][k];
      if (other == kBorder || lit_triangles[other] != 0) continue;
      const std::uint32_t a = caster.triangles[t][k], b = caster.triangles[t][(k + 1) % 3];
      pieces.add(vertex_key(a), vertex_point(caster, t, a), vertex_key(b), vertex_point(caster, t, b), t);
    }
  }
  return pieces;
}

LitBoundary accurate_boundary(const SmoothCaster& caster, const CornerValues& f) {
  LitBoundary pieces;
  // 1. Inside each triangle: its lit part's boundary runs along the zero segment from the edge
  // where the corners go lit to unlit (in the triangle's order) to the edge where they go back.
  for (std::uint32_t t = 0; t < caster.triangles.size(); ++t) {
    const std::array<double, 3> ft = f[t];
    if (lit(ft[0]) == lit(ft[1]) && lit(ft[1]) == lit(ft[2])) continue;  // no zero set: most triangles
    std::size_t leaving = 3, entering = 3;
    for (std::size_t k = 0; k < 3; ++k) {
      const bool here = lit(ft[k]), next = lit(ft[(k + 1) % 3]);
      if (here && !next) leaving = k;
      if (!here && next) entering = k;
    }
    if (leaving == 3) continue;  // one lit state at every corner: no zero set
    const auto [from_key, from] = edge_point(caster, f, t, leaving);
    const auto [to_key, to] = edge_point(caster, f, t, entering);
    pieces.add(from_key, from, to_key, to, t);
  }
  // 2. Along each crease: the parts of the edge lit on one side only, with the lit side on the
  // left (its own order along the edge), and a zero-length piece where both sides' points
  // coincide with both lit on the same end.
  for (const std::array<std::uint32_t, 2>& crease : caster.crease_edges) {
    {
      // Plain variables, not a structured binding: the lambdas below capture them (clang 14
      // cannot capture a binding).
      const std::uint32_t t = crease[0];
      const std::size_t k = crease[1];
      const std::uint32_t other = caster.across[t][k];
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
        const std::array<double, 3> fx = f[tri];
        x.at_a = lit(fx[corner_a]);
        x.at_b = lit(fx[corner_b]);
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
      const PointKey key_a = vertex_key(a), key_b = vertex_key(b);
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
        if (lit_one) pieces.add(x_key, x, y_key, y, t);  // t's order, a -> b
        else pieces.add(y_key, y, x_key, x, other);      // the other side's order, b -> a
      }
      if (one.s >= 0.0 && one.s == two.s && one.at_a == two.at_a) {
        // Both sides lit on the same end and changing at one point: t's zero segment leaves
        // from its point iff a is lit, and the other side's arrives at its own.
        if (one.at_a) pieces.add(two.key, two.point, one.key, one.point, kBorder);
        else pieces.add(one.key, one.point, two.key, two.point, kBorder);
      }
    }
  }
  return pieces;
}

std::vector<SilhouetteLoop> loops_of(const LitBoundary& boundary, const std::vector<KeyedLoop>& keyed) {
  std::vector<SilhouetteLoop> loops;
  loops.reserve(keyed.size());
  for (const KeyedLoop& k : keyed) {
    SilhouetteLoop loop;
    loop.closed = k.closed;
    for (const PointKey& key : k.keys) loop.points.push_back(boundary.points.at(key));
    for (std::size_t piece : k.pieces) loop.segment_triangles.push_back(boundary.pieces[piece].triangle);
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace shadowcert::detail
