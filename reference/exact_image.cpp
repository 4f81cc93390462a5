// exact_image of reference/exact_image.h, in passes over the pixel grid (docs/definitions.md#pixel-protocol):
//   1. hits: every centre ray and every corner ray is followed to its first hit with the box
//      tree's nearest-first query and exact ray/triangle tests (reference/detail/ray_hit.h);
//   2. footprints: where a pixel's five rays agree on one triangle, nothing else may be seen
//      over its footprint (reference/detail/pixel_footprint.h, the eye pyramid), nor, with a depth band,
//      within the band of its centre (another surface);
//   3. counts, per light: n(P) at every centre hit, and at the corner hits that can still
//      decide a pixel (a pixel whose footprint already sees two triangles, or whose hit
//      triangle is a terminator, is ambiguous whatever its corners count);
//   4. per pixel and light: the lit mask and the ambiguity bits, the light pyramid over the
//      footprint (silhouette edges) and, with a depth band, the volume faces near P.
// With ExactImageOptions::footprints false, only the centre rays are traced and counted, and
// steps 2 and 4's footprint, pyramid and band tests are skipped.
// Every decision is an exact sign; the only doubles that are not inputs are interval bounds
// that enclose exact values (filters and box-tree queries), never a decision by themselves,
// and the depth band's end points, which its caller's model defines.
#include "reference/exact_image.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "core/box.h"
#include "core/huge_page_advice.h"
#include "core/pixel_ray.h"
#include "exact/box_tree.h"
#include "exact/edge_multiplicity.h"
#include "exact/face_crossing.h"
#include "exact/light_orientation.h"
#include "exact/light_orientation_filter.h"
#include "exact/orient_unchecked.h"
#include "reference/detail/eye_blocks.h"
#include "reference/detail/eye_tile.h"
#include "reference/detail/hit_point_boxes.h"
#include "reference/detail/light_grid.h"
#include "reference/detail/plane_through_filter.h"
#include "reference/detail/pixel_footprint.h"
#include "reference/detail/ray_hit.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"

namespace shadowcert {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// A ray's first hit. `degenerate`: the first contact is at a zero sign (an edge, a vertex, the
// eye on the triangle, a tie between triangles, a contact along the ray in a triangle's plane).
struct RayHit {
  std::uint32_t triangle = kNoHit;
  bool degenerate = false;
  Sign eye_side = Sign::zero;        // orient(h, e): nonzero for a non-degenerate hit
  Sign direction_side = Sign::zero;  // orient(h, (d, 0)): nonzero for a non-degenerate hit
};

[[nodiscard]] bool countable(const RayHit& hit) { return hit.triangle != kNoHit && !hit.degenerate; }

// Every ray's first hit, indexed as RayGrid numbers the rays.
using RayHits = HugePageBuffer<RayHit>;

// A box enclosing a ray's hit point ({lo, hi}: detail::semi_static_hit_box's, else HitPoint's
// own; every test on P is exact whatever the box, which only filters), computed once per ray for
// every countable hit and kept in detail::HitPointBoxes: the centre's count, and each corner's
// count and its four pixels' eye and light pyramids read it (was recomputed for each, up to nine
// times per ray).
using PointBox = detail::HitPointBoxes::Box;

// A light's silhouette edges: the edges of nonzero multiplicity (docs/definitions.md#counts), whose side
// faces are the shadow volume chain's only finite faces besides the casters themselves.
struct Silhouette {
  std::vector<std::array<Vec3, 2>> edges;
  detail::BoxTree tree;
};

// What every ray is tested against: the soup, its box tree, and per light the exact s(t) and
// the silhouette.
struct ImageGeometry {
  const Soup& soup;
  std::span<const std::uint8_t> casts;  // ExactImageOptions::casts: per triangle, or empty (all cast)
  std::vector<HomogeneousPoint> lights;
  std::vector<std::vector<Sign>> light_sides;  // [light][triangle]: s(t) of docs/definitions.md#orientation
  std::vector<std::unique_ptr<Silhouette>> silhouettes;  // of the casting triangles
  std::vector<std::unique_ptr<Silhouette>> casting_edges;  // with a depth band: every edge of a caster
  const detail::BoxTree& tree;

  [[nodiscard]] const Vec3& vertex(std::uint32_t triangle, int k) const {
    return soup.vertices[soup.triangles[triangle][static_cast<std::size_t>(k)]];
  }
  [[nodiscard]] bool casting(std::uint32_t triangle) const { return casts.empty() || casts[triangle] != 0; }
};

void validate(const Soup& soup, std::span<const Light> lights, const ExactImageOptions& options) {
  require_indices_in_range(soup, "exact_image");
  require_finite_vertices(soup, "exact_image");
  if (soup.triangles.size() >= kUndefinedCount) throw std::invalid_argument("exact_image: too many triangles");
  for (const Light& light : lights) require_defined(light, "exact_image");
  if (!options.casts.empty() && options.casts.size() != soup.triangles.size())
    throw std::invalid_argument("exact_image: casts has " + std::to_string(options.casts.size()) + " flags for " +
                                std::to_string(soup.triangles.size()) + " triangles");
}

// The casting triangles of `soup` alone, in order, on all of its vertices.
Soup casting_soup(const Soup& soup, std::span<const std::uint8_t> casts) {
  Soup out;
  out.vertices = soup.vertices;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (casts[t] != 0) out.triangles.push_back(soup.triangles[t]);
  return out;
}

// The entries of `sides` (one per soup triangle) of the casting triangles, in order.
std::vector<Sign> casting_sides(const std::vector<Sign>& sides, std::span<const std::uint8_t> casts) {
  if (casts.empty()) return sides;
  std::vector<Sign> out;
  for (std::size_t t = 0; t < sides.size(); ++t)
    if (casts[t] != 0) out.push_back(sides[t]);
  return out;
}

std::vector<Sign> light_sides(const Soup& soup, const Light& light) {
  std::vector<Sign> sides(soup.triangles.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sides.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Triangle& t = soup.triangles[i];
      sides[i] = light_orientation(soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]], light);
    }
  });
  return sides;
}

// The edges of `table` that `keep` selects, with a box tree over them.
template <typename Keep>
std::unique_ptr<Silhouette> edge_set(const Soup& canonical, const EdgeTable& table, Keep keep) {
  std::vector<std::array<Vec3, 2>> edges;
  std::vector<Box> boxes;
  for (std::size_t e = 0; e < table.size(); ++e) {
    if (!keep(e)) continue;
    const Vec3& u = canonical.vertices[table.edges[e][0]];
    const Vec3& v = canonical.vertices[table.edges[e][1]];
    edges.push_back({u, v});
    Box b{u, u};
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = std::min(u[k], v[k]);
      b.hi[k] = std::max(u[k], v[k]);
    }
    boxes.push_back(b);
  }
  return std::unique_ptr<Silhouette>(new Silhouette{std::move(edges), detail::BoxTree(boxes, detail::LeafTest::exact)});
}

std::unique_ptr<Silhouette> silhouette(const Soup& canonical, const EdgeTable& table, const Light& light) {
  const EdgeMultiplicities m = exact_multiplicities(canonical, table, light);
  return edge_set(canonical, table, [&](std::size_t e) { return m.multiplicity[e] != 0; });
}

// Every edge with a casting triangle on it (canonical triangles keep the casting soup's order,
// which `sides` follows).
std::unique_ptr<Silhouette> casting_edges(const Soup& canonical, const EdgeTable& table, const std::vector<Sign>& sides) {
  return edge_set(canonical, table, [&](std::size_t e) {
    for (std::uint32_t k = table.first_opposite[e]; k < table.first_opposite[e + 1]; ++k)
      if (sides[table.opposite_triangle[k]] != Sign::zero) return true;
    return false;
  });
}

// A listed candidate's estimates of N and D in t = N / D (RayParameter's estimates
// constructor): N the tile's, D its direction filter's value and bound for this ray.
struct ParameterEstimates {
  detail::BoundedEstimate n;
  detail::BoundedEstimate d;
};

// The first hit of `ray` (exact). `in_plane` is scratch space for contacts along the ray.
// `candidates`: a list holding every triangle the ray can meet (its tile's, TileCandidates), or
// nullptr: the box tree's nearest-first query. The answer is a function of the set of
// triangles the ray meets (the nearest meeting; at a tie or an in-plane contact before it, the
// least id), so both give the same hit.
// With a list: `scan` holds the indices k into it of the candidates to test, ascending (all of
// them, or those the ray's block of pixels may meet: RayBlocks), and
// known(k, signs, estimates) fills the signs of ray_meets_triangle for candidate k
// that the tile's filters certify for this ray and the estimates of its parameter's N and D,
// and returns false where they show it apart (skipped).
// `near` (or nullptr): per candidate, ascending, a lower bound on its distance from the ray's
// origin; the scan stops at the first candidate that can only be met beyond the best meeting's
// parameter (t >= near / |d|), as the walk prunes its boxes, so the answer is the same;
// `direction_length` >= |d| (1 + 2^-41) bounds the ray's |d| for that test (the list's rays
// share one: direction_length_bound), 0 for none (no candidate is skipped).
// `best`: the nearest meeting's parameter (of the hit triangle where the hit is countable).
template <typename Known>
RayHit first_hit(const ImageGeometry& g, const PixelRay& ray, std::vector<std::uint32_t>& in_plane,
                 const std::vector<std::uint32_t>* candidates, std::span<const std::uint32_t> scan,
                 const double* near, double direction_length, Known&& known,
                 std::optional<detail::RayParameter>& best) {
  in_plane.clear();
  best.reset();
  RayHit hit;
  double bound = std::numeric_limits<double>::infinity();
  const detail::KnownRaySigns* known_signs = nullptr;  // the visited candidate's, when known
  const ParameterEstimates* estimates = nullptr;      // the visited candidate's N and D, when known
  const auto visit = [&](std::uint32_t id) {
    const Vec3 &a = g.vertex(id, 0), &b = g.vertex(id, 1), &c = g.vertex(id, 2);
    std::optional<detail::RayMeeting> from_signs;
    if (known_signs != nullptr) from_signs = detail::meeting_from_signs(*known_signs);
    const detail::RayMeeting m = from_signs                ? *from_signs
                                 : known_signs != nullptr ? detail::ray_meets_triangle(ray, a, b, c, *known_signs)
                                                          : detail::ray_meets_triangle(ray, a, b, c);
    switch (m.contact) {
      case detail::RayContact::apart:
        return true;
      case detail::RayContact::in_plane:
        in_plane.push_back(id);  // no single parameter: resolved once the first crossing is known
        return true;
      case detail::RayContact::crosses:
      case detail::RayContact::touches:
        break;
    }
    const bool touch = m.contact == detail::RayContact::touches;
    const auto parameter = [&](std::optional<detail::RayParameter>& slot) -> detail::RayParameter& {
      return estimates != nullptr ? slot.emplace(ray, a, b, c, m.direction_side, estimates->n, estimates->d)
                                  : slot.emplace(ray, a, b, c, m.direction_side);
    };
    if (!best) {  // the first meeting: built in place (a parameter is 160 bytes)
      bound = parameter(best).upper();
      hit = {id, touch, m.eye_side, m.direction_side};
      return true;
    }
    std::optional<detail::RayParameter> candidate;
    const detail::RayParameter& t = parameter(candidate);
    switch (t.compare(*best)) {
      case Sign::negative:  // nearer than every meeting so far
        best = t;
        hit = {id, touch, m.eye_side, m.direction_side};
        bound = t.upper();
        break;
      case Sign::zero:  // a tie: P lies on two triangles (a zero sign, docs/definitions.md#pixel-protocol)
        hit.degenerate = true;
        hit.triangle = std::min(hit.triangle, id);
        break;
      case Sign::positive:
        break;
    }
    return true;
  };
  if (candidates != nullptr) {
    // A candidate is met, if at all, at t >= near / |d|; the scan stops where that exceeds
    // bound, tested without a division: length >= |d| (1 + 2^-41), so near > fl(bound *
    // length) + 2^-1000 (the product's rounding,
    // relative 2^-53, and its underflow, 2^-1074 at most, absorbed) gives near > bound |d|. An
    // infinite bound prunes nothing. Without a usable |d| no candidate is skipped.
    const double length = direction_length;
    const bool prune = near != nullptr && length > 0x1p-500 && std::isfinite(length);
    detail::KnownRaySigns signs;
    ParameterEstimates candidate_estimates;
    known_signs = &signs;
    estimates = &candidate_estimates;
    for (const std::uint32_t k : scan) {
      if (prune && near[k] > bound * length + 0x1p-1000) break;
      if (known(k, signs, candidate_estimates)) visit((*candidates)[k]);
    }
  } else {
    g.tree.nearest_first_ray_query(ray.origin, ray.direction, &bound, visit);
  }
  for (std::uint32_t id : in_plane) {
    if (best && !detail::in_plane_contact_before(ray, g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2), *best))
      continue;  // met only beyond the first hit
    hit.degenerate = true;
    hit.triangle = std::min(hit.triangle, id);
  }
  return hit;
}

// n(P) for P = the hit point of a countable hit, light number `light` (docs/definitions.md#counts, docs/definitions.md#pixel-protocol): the
// casting triangles other than the hit one that the open segment P -> light crosses;
// kUndefinedCount when it touches one (P on a volume boundary).
// `box`: P's enclosure as HitPoint computes it (the per-ray cache, point_boxes below).
// `candidates`: a list holding every casting triangle the segment can meet (its tile's,
// light_tile_candidates), or nullptr: the box tree's query. The count is a function of the set
// of triangles the segment crosses or touches, so both give it.
std::uint32_t count_at(const ImageGeometry& g, std::size_t light, const PixelRay& ray, const RayHit& hit,
                       const PointBox& box, const std::vector<std::uint32_t>* candidates = nullptr) {
  const std::uint32_t h = hit.triangle;
  const detail::HitPoint p(detail::RayParameter(ray, g.vertex(h, 0), g.vertex(h, 1), g.vertex(h, 2), hit.direction_side,
                                                detail::RayParameter::Unenclosed{}),
                           box);
  const HomogeneousPoint& l = g.lights[light];
  const std::vector<Sign>& sides = g.light_sides[light];
  std::uint32_t n = 0;
  bool touched = false;
  const auto classify = [&](std::uint32_t id) {
    if (id == h) return true;  // the triangle that contains P (docs/definitions.md#pixel-protocol)
    if (!g.casting(id)) return true;  // receives only: in no volume
    const Sign s = sides[id];
    if (s == Sign::zero) return true;  // casts nothing (docs/definitions.md#orientation)
    const Vec3 &a = g.vertex(id, 0), &b = g.vertex(id, 1), &c = g.vertex(id, 2);
    // P and the light on one side: the open segment never reaches the plane. P on the plane:
    // the open segment leaves it at once towards the light (s != 0), so it misses the closed
    // triangle; P itself is on no other triangle, or the hit would be degenerate.
    const Sign start = p.side(a, b, c);
    if (start == Sign::zero || start == s) return true;
    // The segment crosses the plane in one point X; exact/face_crossing.h's rule: X strictly
    // inside iff orient(P, L, p, q) = -start for every edge pq, outside if one has +start.
    const std::array<std::pair<const Vec3*, const Vec3*>, 3> edges{{{&a, &b}, {&b, &c}, {&c, &a}}};
    switch (detail::fold_boundary_signs([&](int k) {
      const auto& [u, v] = edges[static_cast<std::size_t>(k)];
      return p.orient_with(l, *u, *v) * -start;
    })) {
      case detail::Meeting::apart:
        return true;
      case detail::Meeting::touches:
        touched = true;
        return false;
      case detail::Meeting::crosses:
        break;
    }
    ++n;
    return true;
  };
  if (candidates != nullptr) {
    if (l[3] != 0.0 && p.equals({l[0], l[1], l[2]})) return 0;  // the open segment is empty
    for (std::uint32_t id : *candidates)
      if (!classify(id)) break;
    return touched ? kUndefinedCount : n;
  }
  // The query starts from a double point of P's enclosure and is dilated by the enclosure's
  // size, so the exact segment's candidates are all visited (exact/box_tree.h).
  Vec3 from = p.lo(), slack{};
  {
    for (int k = 0; k < 3; ++k) {
      const double mid = p.lo()[k] / 2 + p.hi()[k] / 2;
      from[k] = std::clamp(mid, p.lo()[k], p.hi()[k]);
      slack[k] = std::nextafter(std::max(p.hi()[k] - from[k], from[k] - p.lo()[k]),
                                std::numeric_limits<double>::infinity());
    }
  }
  if (l[3] == 0.0) {
    g.tree.dilated_ray_query(from, {l[0], l[1], l[2]}, slack, classify);
  } else {
    const Vec3 target{l[0], l[1], l[2]};
    if (p.equals(target)) return 0;  // the open segment is empty
    if (from == target) {            // P is within its enclosure of the light: start from a corner
      from = p.lo();
      for (int k = 0; k < 3; ++k)
        slack[k] = std::nextafter(p.hi()[k] - p.lo()[k], std::numeric_limits<double>::infinity());
      if (from == target) from = p.hi();
    }
    g.tree.dilated_segment_query(from, target, slack, classify);
  }
  return touched ? kUndefinedCount : n;
}

// ---- Counts for many point lights at once (the soft reference's samples) -------------------
// With footprints off and several point lights, each centre hit P is counted for every light in
// one pass: one box-tree query whose dilation holds every segment P -> L (the beam), P's side of
// each candidate's plane once for all lights, and each edge's sign orient(P, L, p, q) for every
// light from one plane through P, p and q (EdgePlaneFilter). Every verdict is the exact one
// count_at gives light by light (docs/definitions.md#counts): the beam's candidates include each
// light's, and a candidate that no segment crosses or touches changes no count.

// The signs orient(P, L, p, q) = det[L - P, p - P, q - P] = (L - P) . n(P), n(P) = (p - P) x
// (q - P), of one edge pq for the point lights L with |L_i - m_i| <= W_i, where P lies in the box
// [lo, hi] and m is its middle: a semi-static filter in round-to-nearest doubles. With
// P = m + e, |e_i| <= r_i: n(P) = n(m) + e x (p - q), so
//   (L - P) . n(P) = (L - m) . n(m) + e . ((p - q) x (L - m)) - e . n(m),
// and the computed v = fl(fl(L - m) . fl(n(m))) is within
//   B = sum W_i (5u |n_i| + 2 E_i) + sum r_i (|n_i| + E_i) + sum r_i (|d_j| W_k + |d_k| W_j)
// of it (cyclic i, j, k; u = 2^-53; E_i >= 4.1u (|a_j b_k| + |a_k b_j|), a = fl(p - m),
// b = fl(q - m), bounds n_i's rounding; d = fl(p - q)), as in exact/light_orientation_filter.h.
// B is formed from rounded values, so it is taken times (1 + 2^-20), plus an absolute 2^-800
// for underflow (every magnitude is kept within 2^200, so no product overflows and no
// underflowed operation errs by more than 2^-1074 times 2^400). |v| > B decides the sign;
// otherwise the caller asks HitPoint::orient_with.
//
// For all the lights at once (they lie in the box c +- half): v ranges over
// (c - m) . n +- sum half_i |n_i|; computing that rounds by no more than another B (its terms
// are those of B's first sum), so a range beyond 2B decides every light's sign together.
class EdgePlaneFilter {
 public:
  // `m` and `r`: P's box middle and a bound on |P - m| per axis; `W`: a bound on |L - m| per
  // axis over the lights this filter serves.
  EdgePlaneFilter(const Vec3& m, const Vec3& r, const Vec3& W, const Vec3& p, const Vec3& q) : m_(m) {
    const Terms t = terms(m, r, W, p, q);
    n_ = t.n;
    bound_ = t.bound;
    usable_ = std::isfinite(bound_);
    norm_ = std::sqrt(n_[0] * n_[0] + n_[1] * n_[1] + n_[2] * n_[2]);
  }

  // The sign of d . n(m) = det[d, p - m, q - m] for an exact vector d with |d_i| <= W_i and
  // r = 0 (m itself: a point of the plane): orient(m, d, p, q) with d a direction (w = 0).
  // Its rounding is within B: fl(L - m) above is d here, with no rounding of its own.
  [[nodiscard]] std::optional<Sign> sign_along(const Vec3& d) const {
    if (!usable_) return std::nullopt;
    const double v = d[0] * n_[0] + d[1] * n_[1] + d[2] * n_[2];
    if (v > bound_) return Sign::positive;
    if (v < -bound_) return Sign::negative;
    return std::nullopt;
  }

  // The filter's normal n(m) and bound B (+infinity where it is not usable), without the rest
  // of it (|n|, m): what a caller that filters many directions keeps (r = 0): sign_along(d) is
  // positive where fl(d . n) > B, negative where fl(d . n) < -B, the dot product summed in axis
  // order.
  struct Terms {
    Vec3 n;
    double bound;
  };
  [[nodiscard]] static Terms terms(const Vec3& m, const Vec3& r, const Vec3& W, const Vec3& p, const Vec3& q) {
    constexpr double u = 0x1p-53, kTame = 0x1p200;
    const Vec3 a = difference(p, m), b = difference(q, m), d = difference(p, q);
    const detail::RoundedCross cross = detail::rounded_cross(a, b);
    double bound = 0.0;
    bool tame = true;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      const double e = cross.e[i];
      bound += W[i] * (5.0 * u * std::fabs(cross.n[i]) + 2.0 * e) + r[i] * (std::fabs(cross.n[i]) + e) +
               r[i] * (std::fabs(d[j]) * W[k] + std::fabs(d[k]) * W[j]);
      for (const double x : {a[i], b[i], d[i], W[i], r[i]}) tame = tame && std::fabs(x) <= kTame;
    }
    bound = bound * (1.0 + 0x1p-20) + 0x1p-800;
    return {cross.n, tame && std::isfinite(bound) ? bound : std::numeric_limits<double>::infinity()};
  }

  // The sign for light L (|L - m| <= W), or nullopt where the filter cannot decide.
  [[nodiscard]] std::optional<Sign> sign(const HomogeneousPoint& light) const {
    if (!usable_) return std::nullopt;
    const double v = (light[0] - m_[0]) * n_[0] + (light[1] - m_[1]) * n_[1] + (light[2] - m_[2]) * n_[2];
    if (v > bound_) return Sign::positive;
    if (v < -bound_) return Sign::negative;
    return std::nullopt;
  }

  // For lights k of xs, ys, zs (each within W of m): above[k] = 1 where the sign is certainly
  // `side`, below[k] = 1 where it is certainly -side (neither: the filter cannot decide, or it
  // is not usable). One pass over the lights the compiler vectorises.
  void classify(std::span<const double> xs, std::span<const double> ys, std::span<const double> zs, Sign side,
                std::uint8_t* above, std::uint8_t* below) const {
    const std::size_t n = xs.size();
    if (!usable_) {
      std::fill(above, above + n, std::uint8_t{0});
      std::fill(below, below + n, std::uint8_t{0});
      return;
    }
    const double flip = side == Sign::negative ? -1.0 : 1.0;
    const double n0 = n_[0] * flip, n1 = n_[1] * flip, n2 = n_[2] * flip, m0 = m_[0], m1 = m_[1], m2 = m_[2];
    const double bound = bound_;
    for (std::size_t k = 0; k < n; ++k) {
      const double v = (xs[k] - m0) * n0 + (ys[k] - m1) * n1 + (zs[k] - m2) * n2;
      above[k] = static_cast<std::uint8_t>(v > bound);
      below[k] = static_cast<std::uint8_t>(v < -bound);
    }
  }

  // common_sign times `side` for the boxes (cx[g], cy[g], cz[g]) +- (hx[g], hy[g], hz[g]):
  // above[g] = 1 where certainly positive, below[g] = 1 where certainly negative. Vectorised.
  void classify_boxes(const double* cx, const double* cy, const double* cz, const double* hx, const double* hy,
                      const double* hz, std::size_t boxes, Sign side, std::uint8_t* above, std::uint8_t* below) const {
    if (!usable_) {
      std::fill(above, above + boxes, std::uint8_t{0});
      std::fill(below, below + boxes, std::uint8_t{0});
      return;
    }
    const double flip = side == Sign::negative ? -1.0 : 1.0;
    const double n0 = n_[0] * flip, n1 = n_[1] * flip, n2 = n_[2] * flip, m0 = m_[0], m1 = m_[1], m2 = m_[2];
    const double a0 = std::fabs(n_[0]), a1 = std::fabs(n_[1]), a2 = std::fabs(n_[2]), bound = 2.0 * bound_;
    for (std::size_t g = 0; g < boxes; ++g) {
      const double v = (cx[g] - m0) * n0 + (cy[g] - m1) * n1 + (cz[g] - m2) * n2;
      const double spread = hx[g] * a0 + hy[g] * a1 + hz[g] * a2;
      above[g] = static_cast<std::uint8_t>(v - spread > bound);
      below[g] = static_cast<std::uint8_t>(v + spread < -bound);
    }
  }

  // The sign shared by every light within `radius` of `centre` (Euclidean; within W of m), or
  // nullopt: v = (centre - m) . n ranges over +- radius |n|, whose rounding (|n|'s square root
  // and products, a relative 8u) the factor (1 + 2^-40) covers; v's own rounding is within the
  // second B, as in common_sign.
  [[nodiscard]] std::optional<Sign> common_sign_ball(const Vec3& centre, double radius) const {
    if (!usable_) return std::nullopt;
    const double v = (centre[0] - m_[0]) * n_[0] + (centre[1] - m_[1]) * n_[1] + (centre[2] - m_[2]) * n_[2];
    const double spread = radius * norm_ * (1.0 + 0x1p-40);
    if (v - spread > 2.0 * bound_) return Sign::positive;
    if (v + spread < -2.0 * bound_) return Sign::negative;
    return std::nullopt;
  }

  // The sign shared by every light in the box centre +- half (within W of m), or nullopt.
  [[nodiscard]] std::optional<Sign> common_sign(const Vec3& centre, const Vec3& half) const {
    if (!usable_) return std::nullopt;
    const double v = (centre[0] - m_[0]) * n_[0] + (centre[1] - m_[1]) * n_[1] + (centre[2] - m_[2]) * n_[2];
    const double spread = half[0] * std::fabs(n_[0]) + half[1] * std::fabs(n_[1]) + half[2] * std::fabs(n_[2]);
    if (v - spread > 2.0 * bound_) return Sign::positive;
    if (v + spread < -2.0 * bound_) return Sign::negative;
    return std::nullopt;
  }

 private:
  Vec3 m_;
  Vec3 n_{};
  double norm_ = 0.0;  // |n|, rounded (common_sign_ball's factor covers it)
  double bound_ = 0.0;
  bool usable_ = false;
};

// The fewest lights counted together: one light is counted as with footprints.
inline constexpr std::size_t kBeamMinLights = 2;

// s(t) of every triangle for several point lights at once (light_sides' signs, light by light):
// per triangle one plane through its vertices, orient(a, b, c, L) = (L - a) . ((b - a) x (c - a))
// for every light a dot product with one normal under EdgePlaneFilter's bound (a in P's place,
// exactly: r = 0), light_orientation where the bound cannot decide. For 64 samples of ogre's
// 124K triangles, a sixth of the time of 64 light_sides calls.
std::vector<std::vector<Sign>> point_light_sides(const Soup& soup, std::span<const Light> lights) {
  const std::size_t count = lights.size(), triangles = soup.triangles.size();
  std::vector<std::vector<Sign>> sides(count);
  for (auto& s : sides) s.resize(triangles);
  std::vector<double> xs(count), ys(count), zs(count);
  Vec3 lo{}, hi{};
  for (std::size_t k = 0; k < count; ++k) {
    const HomogeneousPoint& l = lights[k].position;
    xs[k] = l[0];
    ys[k] = l[1];
    zs[k] = l[2];
    for (int a = 0; a < 3; ++a) {
      lo[a] = k == 0 ? l[a] : std::min(lo[a], l[a]);
      hi[a] = k == 0 ? l[a] : std::max(hi[a], l[a]);
    }
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles, 1024), [&](const auto& r) {
    std::vector<std::uint8_t> above(count), below(count);
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      const Triangle& tri = soup.triangles[t];
      const Vec3 &a = soup.vertices[tri[0]], &b = soup.vertices[tri[1]], &c = soup.vertices[tri[2]];
      Vec3 reach{};  // |L - a| per axis over the lights
      for (int axis = 0; axis < 3; ++axis)
        reach[axis] = std::max(std::fabs(hi[axis] - a[axis]), std::fabs(lo[axis] - a[axis])) * (1.0 + 0x1p-50);
      EdgePlaneFilter(a, Vec3{}, reach, b, c).classify(xs, ys, zs, Sign::positive, above.data(), below.data());
      for (std::size_t k = 0; k < count; ++k)
        sides[k][t] = above[k] != 0   ? Sign::positive
                      : below[k] != 0 ? Sign::negative
                                      : light_orientation(a, b, c, lights[k]);
    }
  });
  return sides;
}
// The lights are split into groups of at most this many neighbours, which an edge's plane
// decides together where it passes beside their box (EdgePlaneFilter::common_sign).
inline constexpr std::size_t kBeamGroup = 8;

// What the beam counts share across pixels. The lights are held in slots, neighbours in
// consecutive slots (a median split along the longest axis of their box, down to groups of
// kBeamGroup); light order[slot] sits in each slot. Per slot: its coordinates, and per triangle
// its s(t) (sides[t * lights + slot]), with a summary per triangle (the sign every light
// shares, or kMixedSides).
struct BeamLights {
  static constexpr std::int8_t kMixedSides = 2;
  struct Group {
    std::size_t first = 0, last = 0;  // slots [first, last)
    Vec3 centre{}, half{};             // a box holding its lights
    double radius = 0.0;               // and a ball around the same centre
  };
  std::size_t count = 0;
  std::vector<std::size_t> order;
  std::vector<double> x, y, z;
  std::vector<Group> groups;
  std::array<std::vector<double>, 3> group_centre, group_half;  // the groups' boxes, axis by axis
  Vec3 lo{}, hi{};  // every light's box
  Vec3 ball_centre{};  // and a ball around its middle holding every light
  double ball = 0.0;
  std::vector<Sign> sides;
  std::vector<std::int8_t> summary;

  explicit BeamLights(const ImageGeometry& g) : count(g.lights.size()), order(count) {
    std::iota(order.begin(), order.end(), std::size_t{0});
    split(g, 0, count);
    for (const std::size_t k : order) {
      x.push_back(g.lights[k][0]);
      y.push_back(g.lights[k][1]);
      z.push_back(g.lights[k][2]);
    }
    box_of(0, count, lo, hi);
    for (int a = 0; a < 3; ++a) ball_centre[a] = std::clamp(lo[a] / 2 + hi[a] / 2, lo[a], hi[a]);
    ball = ball_radius(g, 0, count, ball_centre);
    for (const Group& group : groups)
      for (int a = 0; a < 3; ++a) {
        group_centre[a].push_back(group.centre[a]);
        group_half[a].push_back(group.half[a]);
      }
    const std::size_t triangles = g.soup.triangles.size();
    sides.resize(triangles * count);
    summary.resize(triangles);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles, 4096), [&](const auto& r) {
      for (std::size_t t = r.begin(); t != r.end(); ++t) {
        Sign* row = sides.data() + t * count;
        bool alike = true;
        for (std::size_t slot = 0; slot < count; ++slot) {
          row[slot] = g.light_sides[order[slot]][t];
          alike = alike && row[slot] == row[0];
        }
        summary[t] = alike ? static_cast<std::int8_t>(row[0]) : kMixedSides;
      }
    });
  }

 private:
  void box_of(std::size_t first, std::size_t last, Vec3& l, Vec3& h) const {
    for (std::size_t slot = first; slot < last; ++slot) {
      const Vec3 v{x[slot], y[slot], z[slot]};
      for (int a = 0; a < 3; ++a) {
        l[a] = slot == first ? v[a] : std::min(l[a], v[a]);
        h[a] = slot == first ? v[a] : std::max(h[a], v[a]);
      }
    }
  }
  // A bound on |L - centre| over the lights of slots [first, last) (each distance's rounding,
  // a relative 4u, covered by 1 + 2^-40).
  double ball_radius(const ImageGeometry& g, std::size_t first, std::size_t last, const Vec3& centre) const {
    double squared = 0.0;
    for (std::size_t slot = first; slot < last; ++slot) {
      const HomogeneousPoint& l = g.lights[order[slot]];
      const Vec3 d{l[0] - centre[0], l[1] - centre[1], l[2] - centre[2]};
      squared = std::max(squared, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    return std::sqrt(squared) * (1.0 + 0x1p-40);
  }
  // Orders slots [first, last) of `order` into groups (before x, y, z are filled).
  void split(const ImageGeometry& g, std::size_t first, std::size_t last) {
    Vec3 l{}, h{};
    for (std::size_t slot = first; slot < last; ++slot)
      for (int a = 0; a < 3; ++a) {
        const double v = g.lights[order[slot]][a];
        l[a] = slot == first ? v : std::min(l[a], v);
        h[a] = slot == first ? v : std::max(h[a], v);
      }
    if (last - first <= kBeamGroup) {
      Group group{first, last, {}, {}};
      for (int a = 0; a < 3; ++a) {
        group.centre[a] = std::clamp(l[a] / 2 + h[a] / 2, l[a], h[a]);
        group.half[a] = std::max(h[a] - group.centre[a], group.centre[a] - l[a]) * (1.0 + 0x1p-50);
      }
      group.radius = ball_radius(g, first, last, group.centre);
      groups.push_back(group);
      return;
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (h[a] - l[a] > h[axis] - l[axis]) axis = a;
    const std::size_t middle = first + (last - first) / 2;
    std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(first), order.begin() + static_cast<std::ptrdiff_t>(middle),
                     order.begin() + static_cast<std::ptrdiff_t>(last), [&](std::size_t a, std::size_t b) {
                       return g.lights[a][axis] < g.lights[b][axis] ||
                              (g.lights[a][axis] == g.lights[b][axis] && a < b);
                     });
    split(g, first, middle);
    split(g, middle, last);
  }
};

// Per-thread scratch of the beam counts.
struct BeamScratch {
  std::vector<std::uint32_t> candidates;
  std::vector<std::uint32_t> seen;  // per triangle: the generation that collected it
  std::uint32_t generation = 0;
  std::vector<std::uint32_t> n;        // per pixel (of a tile) and slot: the segments crossed so far
  std::vector<std::uint8_t> touched;   // per pixel and slot: a segment touches a casting triangle
  std::vector<std::uint8_t> alone;     // per slot: counted by count_at (P within rounding of the light)
  std::vector<std::uint32_t> result;   // per pixel and slot: n(P) or kUndefinedCount
  std::array<std::array<std::uint8_t, kBeamGroup>, 3> above{}, below{};  // per open edge, a group's lights
  std::array<std::uint8_t, kBeamGroup> undecided{};  // a group's lights left to the exact test
};

// A box holding hit points (one P's enclosure, or a tile's: BeamTile) as the beam's filters
// read it: its middle m, per axis the bounds r >= |P - m| and W >= |L - m| (every light of the
// beam), and its half-size.
struct BeamFrame {
  Vec3 m{}, r{}, W{}, half{};
};

BeamFrame beam_frame(const BeamLights& beam, const Vec3& lo, const Vec3& hi) {
  BeamFrame f;
  for (int a = 0; a < 3; ++a) {
    f.m[a] = std::clamp(lo[a] / 2 + hi[a] / 2, lo[a], hi[a]);
    f.half[a] = std::max(hi[a] - f.m[a], f.m[a] - lo[a]) * (1.0 + 0x1p-50);
    f.r[a] = (hi[a] - lo[a]) * (1.0 + 0x1p-50) + 0x1p-1000;  // |P - m| <= hi - lo: m lies in the box
    f.W[a] = std::max(std::fabs(beam.hi[a] - f.m[a]), std::fabs(beam.lo[a] - f.m[a])) * (1.0 + 0x1p-50);
  }
  return f;
}

// The lights a beam query aims at: the middle and half-size of their box [lo, hi].
struct BeamTarget {
  Vec3 to{}, half{};
};

BeamTarget beam_target(const Vec3& lo, const Vec3& hi) {
  BeamTarget t;
  for (int a = 0; a < 3; ++a) {
    t.to[a] = std::clamp(lo[a] / 2 + hi[a] / 2, lo[a], hi[a]);
    t.half[a] = std::max(hi[a] - t.to[a], t.to[a] - lo[a]) * (1.0 + 0x1p-50);
  }
  return t;
}

// The beam's query is cut at these fractions of the way from P to the lights: the segments
// from P spread by at most the lights' half-size times the fraction reached, so each piece is
// dilated only by its own far end's spread (a cone, not a cylinder of the lights' width).
inline constexpr std::array<double, 8> kBeamCuts{0.0, 1.0 / 64, 1.0 / 32, 1.0 / 16, 1.0 / 8, 1.0 / 4, 1.0 / 2, 1.0};

// Into scratch.candidates: every casting triangle other than `h` (kNoHit: none excluded) with
// lights on both sides or on its plane that a segment from a point of `frame`'s box to a light
// of `target`'s box can meet. From the box's middle m to the lights' middle: at parameter t such
// a segment lies within (1 - t) half + t target.half of m + t (to - m), axis by axis. Each piece
// [t0, t1] of it is dilated by half + t1 target.half, plus the rounding of its end points (a
// few ulps of the coordinates).
void beam_candidates(const ImageGeometry& g, const BeamLights& beam, const BeamFrame& frame, const BeamTarget& target,
                     std::uint32_t h, BeamScratch& scratch) {
  if (scratch.seen.size() != g.soup.triangles.size()) scratch.seen.assign(g.soup.triangles.size(), 0);
  if (++scratch.generation == 0) {
    std::fill(scratch.seen.begin(), scratch.seen.end(), 0u);
    scratch.generation = 1;
  }
  scratch.candidates.clear();
  const auto collect = [&](std::uint32_t id) {
    if (scratch.seen[id] == scratch.generation) return true;
    scratch.seen[id] = scratch.generation;
    if (id != h && g.casting(id) && beam.summary[id] != 0) scratch.candidates.push_back(id);
    return true;
  };
  const Vec3 &m = frame.m, &to = target.to;
  const auto at = [&](double t) {
    return Vec3{m[0] + t * (to[0] - m[0]), m[1] + t * (to[1] - m[1]), m[2] + t * (to[2] - m[2])};
  };
  for (std::size_t piece = 0; piece + 1 < kBeamCuts.size(); ++piece) {
    const double t1 = kBeamCuts[piece + 1];
    const Vec3 from = at(kBeamCuts[piece]), end = at(t1);
    Vec3 slack{};
    for (int a = 0; a < 3; ++a)
      slack[a] = std::nextafter((frame.half[a] + t1 * target.half[a]) * (1.0 + 0x1p-50) +
                                    0x1p-50 * (std::fabs(m[a]) + std::fabs(to[a])) + 0x1p-1000,
                                std::numeric_limits<double>::infinity());
    g.tree.dilated_segment_query(from, end, slack, collect);  // from == end: the box around it
  }
}

// The candidate triangle `id` counted for P (frame: P's own box) and every light of the beam
// not marked in `alone` (nullptr: none): n[slot] += 1 where light slot's open segment crosses
// it, touched[slot] = 1 where it touches it (count_at's test, light by light).
void count_candidate(const ImageGeometry& g, const BeamLights& beam, const detail::HitPoint& p, const BeamFrame& frame,
                     const BeamTarget& target, std::uint32_t id, std::uint32_t* n, std::uint8_t* touched,
                     const std::uint8_t* alone, BeamScratch& scratch) {
  const std::size_t lights = beam.count;
  const Sign* sides = beam.sides.data() + std::size_t{id} * lights;
  const std::int8_t summary = beam.summary[id];
  const Vec3 &a = g.vertex(id, 0), &b = g.vertex(id, 1), &c = g.vertex(id, 2);
  const Sign start = p.side(a, b, c);
  // count_at's tests for light k: s(t) != 0 and P strictly on its other side (start != s).
  if (start == Sign::zero || summary == static_cast<std::int8_t>(start)) return;
  // Light k's segment can cross only where s(t) = -start (nonzero, P on the other side);
  // then it crosses iff each edge's sign orient(P, L, p, q) times -start is positive.
  const Sign crossing_side = -start;
  const std::array<std::pair<const Vec3*, const Vec3*>, 3> edges{{{&a, &b}, {&b, &c}, {&c, &a}}};
  std::array<std::optional<EdgePlaneFilter>, 3> filters;
  // Each edge's sign for all the beam's lights at once where the filter knows it: one
  // certainly negative edge puts every segment outside the triangle.
  std::array<std::optional<Sign>, 3> common;
  bool all_outside = false, all_inside = true;
  for (std::size_t e = 0; e < 3 && !all_outside; ++e) {
    filters[e].emplace(frame.m, frame.r, frame.W, *edges[e].first, *edges[e].second);
    std::optional<Sign> o = filters[e]->common_sign(target.to, target.half);
    if (!o) o = filters[e]->common_sign_ball(beam.ball_centre, beam.ball);
    if (o) common[e] = *o * crossing_side;
    all_outside = common[e] == Sign::negative;
    all_inside = all_inside && common[e] == Sign::positive;
  }
  if (all_outside) return;
  const auto counted = [&](std::size_t slot) {
    return sides[slot] == crossing_side && (alone == nullptr || alone[slot] == 0);
  };
  const auto add_inside = [&](std::size_t first, std::size_t last) {
    for (std::size_t slot = first; slot < last; ++slot) n[slot] += counted(slot) ? 1 : 0;
  };
  if (all_inside) {
    add_inside(0, lights);
    return;
  }
  // Group by group, the edges still open: first for the group's box, then light by light.
  for (const BeamLights::Group& group : beam.groups) {
    std::array<std::size_t, 3> open{};
    std::size_t opens = 0;
    bool group_outside = false;
    for (std::size_t e = 0; e < 3 && !group_outside; ++e) {
      if (common[e]) continue;  // positive for every light
      std::optional<Sign> o = filters[e]->common_sign(group.centre, group.half);
      if (!o) o = filters[e]->common_sign_ball(group.centre, group.radius);
      if (!o) {
        open[opens++] = e;
        continue;
      }
      group_outside = *o * crossing_side == Sign::negative;
    }
    if (group_outside) continue;
    if (opens == 0) {
      add_inside(group.first, group.last);
      continue;
    }
    // Every light of the group at once, in passes the compiler vectorises: each open edge's
    // certain signs; per light `in` (every open edge certainly on the crossing side; the others
    // are, for the whole group) and `out` (one certainly not); lights neither in nor out get the
    // exact test after.
    const std::size_t size = group.last - group.first;
    static constexpr std::array<std::uint8_t, kBeamGroup> kYes = [] {
      std::array<std::uint8_t, kBeamGroup> yes{};
      yes.fill(1);
      return yes;
    }();
    static constexpr std::array<std::uint8_t, kBeamGroup> kNo{};
    std::array<const std::uint8_t*, 3> up{kYes.data(), kYes.data(), kYes.data()};
    std::array<const std::uint8_t*, 3> down{kNo.data(), kNo.data(), kNo.data()};
    for (std::size_t i = 0; i < opens; ++i) {
      filters[open[i]]->classify({beam.x.data() + group.first, size}, {beam.y.data() + group.first, size},
                                 {beam.z.data() + group.first, size}, crossing_side, scratch.above[i].data(),
                                 scratch.below[i].data());
      up[i] = scratch.above[i].data();
      down[i] = scratch.below[i].data();
    }
    const Sign* group_sides = sides + group.first;
    const std::uint8_t* group_alone = alone != nullptr ? alone + group.first : kNo.data();
    std::uint32_t* group_n = n + group.first;
    std::uint8_t* undecided = scratch.undecided.data();
    std::uint8_t any_undecided = 0;
    for (std::size_t j = 0; j < size; ++j) {
      const auto is_counted = static_cast<std::uint8_t>((group_sides[j] == crossing_side) & (group_alone[j] == 0));
      const auto in = static_cast<std::uint8_t>(up[0][j] & up[1][j] & up[2][j]);
      const auto out = static_cast<std::uint8_t>(down[0][j] | down[1][j] | down[2][j]);
      group_n[j] += is_counted & in;
      undecided[j] = static_cast<std::uint8_t>(is_counted & (in ^ 1u) & (out ^ 1u));
      any_undecided |= undecided[j];
    }
    if (any_undecided == 0) continue;
    for (std::size_t j = 0; j < size; ++j) {
      if (undecided[j] == 0) continue;
      const std::size_t slot = group.first + j;
      // Some open edge undecided for this light: its exact sign (count_at's test); an open edge
      // the filter put on the crossing side counts as positive.
      const HomogeneousPoint& l = g.lights[beam.order[slot]];
      const detail::Meeting meeting = detail::fold_boundary_signs([&](int k) {
        const auto i = static_cast<std::size_t>(k);
        if (i >= opens || scratch.above[i][j] != 0) return Sign::positive;
        const std::size_t e = open[i];
        return p.orient_with(l, *edges[e].first, *edges[e].second) * crossing_side;
      });
      if (meeting == detail::Meeting::apart) continue;
      if (meeting == detail::Meeting::touches)
        touched[slot] = 1;
      else
        ++n[slot];
    }
  }
}

// A centre ray's countable hit, as the beam counts read it.
struct BeamPixel {
  PixelRay ray;
  RayHit hit;
  PointBox box;
};

detail::HitPoint beam_hit_point(const ImageGeometry& g, const BeamPixel& pixel) {
  const std::uint32_t h = pixel.hit.triangle;
  return detail::HitPoint(detail::RayParameter(pixel.ray, g.vertex(h, 0), g.vertex(h, 1), g.vertex(h, 2),
                                               pixel.hit.direction_side, detail::RayParameter::Unenclosed{}),
                          pixel.box);
}

// Whether the beam's lights' box meets `box` (a light there may be P itself).
bool lights_near(const BeamLights& beam, const PointBox& box) {
  bool near = true;
  for (int a = 0; a < 3; ++a) near = near && beam.lo[a] <= box[1][a] && box[0][a] <= beam.hi[a];
  return near;
}

// n(P) for every light of `beam` at one countable centre hit (count_at's answers), into
// result[slot] for the light in each slot.
void beam_counts(const ImageGeometry& g, const BeamLights& beam, const BeamPixel& pixel, BeamScratch& scratch,
                 std::uint32_t* result) {
  const std::size_t lights = beam.count;
  const detail::HitPoint p = beam_hit_point(g, pixel);
  scratch.n.assign(lights, 0);
  scratch.touched.assign(lights, 0);
  scratch.alone.assign(lights, 0);
  // A light within P's box may be P itself (count_at's empty segment): counted alone (where the
  // lights' box meets P's box at all); the query aims at the others' box.
  std::size_t beam_lights = lights;
  bool any_alone = false;
  Vec3 lo = beam.lo, hi = beam.hi;
  if (lights_near(beam, pixel.box)) {
    beam_lights = 0;
    for (std::size_t slot = 0; slot < lights; ++slot) {
      const Vec3 l{beam.x[slot], beam.y[slot], beam.z[slot]};
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside = inside && l[a] >= p.lo()[a] && l[a] <= p.hi()[a];
      if (inside) {
        scratch.alone[slot] = 1;
        any_alone = true;
        result[slot] = count_at(g, beam.order[slot], pixel.ray, pixel.hit, pixel.box);
        continue;
      }
      for (int a = 0; a < 3; ++a) {
        lo[a] = beam_lights > 0 ? std::min(lo[a], l[a]) : l[a];
        hi[a] = beam_lights > 0 ? std::max(hi[a], l[a]) : l[a];
      }
      ++beam_lights;
    }
  }
  if (beam_lights == 0) return;
  const BeamFrame frame = beam_frame(beam, p.lo(), p.hi());
  const BeamTarget target = beam_target(lo, hi);
  beam_candidates(g, beam, frame, target, pixel.hit.triangle, scratch);
  for (const std::uint32_t id : scratch.candidates)
    count_candidate(g, beam, p, frame, target, id, scratch.n.data(), scratch.touched.data(),
                    any_alone ? scratch.alone.data() : nullptr, scratch);
  for (std::size_t slot = 0; slot < lights; ++slot)
    if (scratch.alone[slot] == 0) result[slot] = scratch.touched[slot] != 0 ? kUndefinedCount : scratch.n[slot];
}

// Neighbouring pixels (a tile of two in a row) share their cone query where their hit points lie close:
// one query from the box around them all, whose candidates each pixel then counts as
// beam_counts does (deciding a candidate for the whole tile at once, with the tile's box in the
// filters, almost never succeeded on ogre: the plane through P and a nearby edge turns too much
// across a tile). The tree's traversal was a sixth of the soft reference's time. Ogre at
// 1024x768, K = 64, paired runs: counts 1.73 s with 2 x 1 tiles, 1.77 s with 2 x 2 (each pixel
// gets more candidates to reject), 1.89 s with none.
inline constexpr std::uint32_t kBeamTileWidth = 2, kBeamTileHeight = 1;
inline constexpr std::size_t kBeamTile = kBeamTileWidth * kBeamTileHeight;
// A tile shares its query only where its hit points' box is at most this fraction of the way to
// the lights in every axis: a wider box (a depth step between the pixels) would widen the cone
// and give each pixel more candidates to reject. Speed only.
inline constexpr double kBeamTileSpread = 1.0 / 16;

// n(P) for every light at each of `pixels` (countable centre hits, at most kBeamTile), into
// scratch.result[k * lights + slot] for pixel k and the light in each slot.
void beam_counts_tile(const ImageGeometry& g, const BeamLights& beam, std::span<const BeamPixel> pixels,
                      BeamScratch& scratch) {
  const std::size_t lights = beam.count;
  scratch.result.resize(pixels.size() * lights);
  Vec3 lo = pixels[0].box[0], hi = pixels[0].box[1];
  bool together = pixels.size() > 1;
  for (const BeamPixel& pixel : pixels) {
    together = together && !lights_near(beam, pixel.box);
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], pixel.box[0][a]);
      hi[a] = std::max(hi[a], pixel.box[1][a]);
    }
  }
  const BeamTarget target = beam_target(beam.lo, beam.hi);
  for (int a = 0; a < 3 && together; ++a)
    together = hi[a] - lo[a] <= kBeamTileSpread * std::max(std::fabs(target.to[a] - lo[a]), std::fabs(target.to[a] - hi[a]));
  if (!together) {
    for (std::size_t k = 0; k < pixels.size(); ++k) beam_counts(g, beam, pixels[k], scratch, &scratch.result[k * lights]);
    return;
  }
  std::array<std::optional<detail::HitPoint>, kBeamTile> points;
  std::array<BeamFrame, kBeamTile> frames;
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    points[k].emplace(beam_hit_point(g, pixels[k]));
    frames[k] = beam_frame(beam, pixels[k].box[0], pixels[k].box[1]);
  }
  scratch.n.assign(pixels.size() * lights, 0);
  scratch.touched.assign(pixels.size() * lights, 0);
  // Every pixel's candidates are among the tile's (its cone lies in the tile's); its own hit
  // triangle is skipped below.
  beam_candidates(g, beam, beam_frame(beam, lo, hi), target, kNoHit, scratch);
  for (const std::uint32_t id : scratch.candidates)
    for (std::size_t k = 0; k < pixels.size(); ++k)
      if (pixels[k].hit.triangle != id)
        count_candidate(g, beam, *points[k], frames[k], target, id, &scratch.n[k * lights],
                        &scratch.touched[k * lights], nullptr, scratch);
  for (std::size_t i = 0; i < pixels.size() * lights; ++i)
    scratch.result[i] = scratch.touched[i] != 0 ? kUndefinedCount : scratch.n[i];
}

// Progress of one stage, reported about once per percent, one report at a time, in increasing
// order: a thread that took its share before another but reaches the lock after it reports
// nothing (its count is already covered), so the reports never go back and the last is the
// total (the sanitizer suite's timing once let a late 6706 of 9216 follow the final report).
class Progress {
 public:
  Progress(const ExactImageOptions& options, std::string_view stage, std::uint64_t total)
      : report_(options.progress), stage_(stage), total_(total), step_(std::max<std::uint64_t>(1, total / 100)) {
    if (report_) report_(stage_, 0, total_);
  }
  void advance(std::uint64_t amount) {
    if (!report_) return;
    const std::uint64_t before = done_.fetch_add(amount);
    const std::uint64_t after = before + amount;
    if (after / step_ == before / step_ && after != total_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    const std::uint64_t done = std::min(after, total_);
    if (done <= reported_) return;
    reported_ = done;
    report_(stage_, done, total_);
  }

 private:
  const std::function<void(std::string_view, std::uint64_t, std::uint64_t)>& report_;
  std::string_view stage_;
  std::uint64_t total_;
  std::uint64_t step_;
  std::atomic<std::uint64_t> done_{0};
  std::mutex mutex_;
  std::uint64_t reported_ = 0;  // the last count reported (under mutex_)
};

// Pixel rays and corner rays in one index space: centre (i, r) is r * width + i, corner
// (i, r) (image point (i, r)) is centres + r * (width + 1) + i.
// Each ray is pixel_ray's, from the image plane coordinates a of its column and b of its row
// (core/pixel_ray.h), kept per column and row: the same doubles, without two divisions a ray.
struct RayGrid {
  CameraFrame frame;
  std::uint32_t width;
  std::uint32_t height;
  // [column] a, [row] b: of the centres (x = i + 0.5, y = r + 0.5) and of the corners (x = i, y = r).
  std::vector<double> centre_a, centre_b, corner_a, corner_b;

  RayGrid(const CameraFrame& f, std::uint32_t w, std::uint32_t h) : frame(f), width(w), height(h) {
    for (std::uint32_t i = 0; i <= width; ++i) {
      if (i < width) centre_a.push_back(pixel_ray_a(frame, i + 0.5));
      corner_a.push_back(pixel_ray_a(frame, i));
    }
    for (std::uint32_t r = 0; r <= height; ++r) {
      if (r < height) centre_b.push_back(pixel_ray_b(frame, r + 0.5));
      corner_b.push_back(pixel_ray_b(frame, r));
    }
  }

  [[nodiscard]] std::size_t centres() const { return std::size_t{width} * height; }
  [[nodiscard]] std::size_t size() const { return centres() + std::size_t{width + 1} * (height + 1); }
  [[nodiscard]] std::size_t corner(std::uint32_t i, std::uint32_t r) const {
    return centres() + std::size_t{r} * (width + 1) + i;
  }
  // pixel_ray(frame, i + 0.5, r + 0.5) and pixel_ray(frame, i, r).
  [[nodiscard]] PixelRay centre_ray(std::uint32_t i, std::uint32_t r) const {
    return pixel_ray_through(frame, centre_a[i], centre_b[r]);
  }
  [[nodiscard]] PixelRay corner_ray(std::uint32_t i, std::uint32_t r) const {
    return pixel_ray_through(frame, corner_a[i], corner_b[r]);
  }
  [[nodiscard]] PixelRay ray(std::size_t index) const {
    if (index < centres())
      return centre_ray(static_cast<std::uint32_t>(index % width), static_cast<std::uint32_t>(index / width));
    const std::size_t c = index - centres();
    return corner_ray(static_cast<std::uint32_t>(c % (width + 1)), static_cast<std::uint32_t>(c / (width + 1)));
  }
  // The footprint of pixel (i, r): its centre and four corners.
  [[nodiscard]] std::array<std::size_t, 5> footprint(std::uint32_t i, std::uint32_t r) const {
    return {std::size_t{r} * width + i, corner(i, r), corner(i + 1, r), corner(i, r + 1), corner(i + 1, r + 1)};
  }
};

// ---- Tiles of the window that share their box-tree queries --------------------------------
// The window is cut into tiles of kTileSize x kTileSize pixels. A tile's rays (its centres and
// the corners it owns) and its pixels' eye pyramids lie in one cone (reference/detail/eye_tile.h):
// one query of the tree for that cone lists every triangle any of them can meet, and where the
// list is short each of them tests the list instead of walking the tree (the answers are
// those of the walk: first_hit, footprint_sees_more). docs/diff.md#tiles-coherent-rays-share-their-queries.
inline constexpr std::uint32_t kTileSize = 8;
// Beyond this many triangles a tile's rays walk the tree themselves: each ray would test every
// candidate, where its own walk visits a few leaves.
inline constexpr std::size_t kTileCandidates = 24;
// The eye tiles' lists for the first hits: sorted nearest first, each ray stops its scan behind
// its first hit, and the per-tile sign filters (CandidateRaySigns) skip most of what it scans,
// so a longer list pays; the footprints test the list only up to kTileCandidates.
inline constexpr std::size_t kEyeTileCandidates = 128;
// The count tiles of a point light: each hit point tests every candidate through its filters
// (a few dot products, SegmentCrossingFilter), so a longer list still costs less than a walk.
inline constexpr std::size_t kFilteredCountCandidates = 128;
// Groups of hit points with too many candidates are halved down to this many (fewer: each walks
// the tree).
inline constexpr std::size_t kLeastCountGroup = 4;
// A light grid is built where there are at least this many traced rays (centres and corners,
// each of which may be counted) per listed triangle. Its build costs about 70 ns a triangle and
// its lists 30-40 bytes (ogre: 124K triangles, 8 ms); on ogre over a floor at 1024x768 (12.7
// traced rays a triangle, 910K of 1.57M counted) it saved about 37 ns a counted ray over the
// tree's walks. The 1M-triangle sphere grid at 1920x1080 (4.1 rays a triangle) gained 3-5% for
// 82 MB more at its peak, at 1024x768 (1.6) nothing: they walk the tree (docs/diff.md, "The
// light grid").
inline constexpr std::size_t kGridRaysPerTriangle = 5;
// With a light grid, groups whose box meets more cells than this are halved (down to
// kLeastCountGroup): their filters would be drawn for hit points far apart.
inline constexpr std::size_t kGridGroupCells = 256;

// The tiles of `window`, row-major. Tile t covers pixels [x0, x1) x [y0, y1) and owns the
// corners [x0, cx1) x [y0, cy1): its pixels' upper-left corners, and the window's last corner
// column and row in the tiles at its right and bottom ends.
struct TileGrid {
  PixelWindow window;
  std::uint32_t columns = 0, rows = 0;

  explicit TileGrid(const PixelWindow& w)
      : window(w), columns((w.width + kTileSize - 1) / kTileSize), rows((w.height + kTileSize - 1) / kTileSize) {}
  [[nodiscard]] std::uint32_t count() const { return columns * rows; }
  [[nodiscard]] std::uint32_t of(std::uint32_t i, std::uint32_t r) const {
    return (r - window.y) / kTileSize * columns + (i - window.x) / kTileSize;
  }
  struct Bounds {
    std::uint32_t x0, x1, y0, y1, cx1, cy1;
  };
  // Where a tile's quarters divide its columns [lo, hi) (or rows): [lo, m) and [m, hi) (a tile
  // one pixel wide or high has two empty quarters).
  [[nodiscard]] static std::uint32_t middle(std::uint32_t lo, std::uint32_t hi) { return lo + (hi - lo + 1) / 2; }
  [[nodiscard]] Bounds bounds(std::uint32_t t) const {
    Bounds b{};
    b.x0 = window.x + t % columns * kTileSize;
    b.y0 = window.y + t / columns * kTileSize;
    b.x1 = std::min(b.x0 + kTileSize, window.x + window.width);
    b.y1 = std::min(b.y0 + kTileSize, window.y + window.height);
    b.cx1 = b.x1 + (b.x1 == window.x + window.width ? 1 : 0);
    b.cy1 = b.y1 + (b.y1 == window.y + window.height ? 1 : 0);
    return b;
  }
};

// A tile's list: every triangle that one of its rays or eye pyramids can meet, when there are
// at most kTileCandidates of them (and the cone could be bounded); otherwise no list.
struct TileCandidates {
  std::vector<std::uint32_t> ids;
  bool listed = false;
  [[nodiscard]] const std::vector<std::uint32_t>* list() const { return listed ? &ids : nullptr; }
};

struct SegmentCrossingFilter;

// Per-thread scratch of the tiles.
struct TileScratch {
  std::vector<std::uint32_t> seen;  // per triangle: the generation that collected it
  std::uint32_t generation = 0;
  std::vector<std::uint32_t> in_plane;  // first_hit's
  std::optional<detail::RayParameter> best;  // first_hit's nearest meeting
  std::vector<double> near;  // per candidate of the eye tile, a lower bound on its distance from the eye
  // The count tiles': per candidate its filters, per ray its box middle and the candidates the
  // filters leave; P's side of the candidates' planes that hit triangle side_of decides (side_beside).
  std::vector<SegmentCrossingFilter> crossing;
  std::vector<Vec3> middles;
  std::vector<std::uint32_t> undecided;
  std::uint32_t side_of = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::pair<std::uint32_t, std::int8_t>> side_known;
  // The last candidate side_beside found in side_of's plane (or kNoHit), passed by before its
  // filter: a floor's other half, for each of its hit points (ogre at 1024x768: 786K visits).
  std::uint32_t in_plane_of_side_of = kNoHit;
  // The grid counts': per triangle its filter's index in `crossing` (where `seen` holds this
  // generation), per filter its triangle, and one hit point's filters.
  std::vector<std::uint32_t> slot;
  std::vector<std::uint32_t> crossing_ids;
  std::vector<std::uint32_t> point_slots;
  std::vector<std::pair<float, std::uint32_t>> cell_slots;  // one cell's entries: key, filter
  // Pairs (h, t) of triangles found in one plane (t's vertices on h's plane), for the count
  // groups whose only candidates are big()'s: a floor's two halves.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> in_plane_pairs;
  // RayBlocks': per block of an eye tile, the indices into its list its rays scan.
  std::vector<std::uint32_t> block_scan;
  std::vector<std::uint32_t> block_begin;
  std::vector<std::uint32_t> block_misses;  // per candidate, the blocks whose rays all miss it

  // A fresh generation of `seen` (and `slot`), each sized `ids`: no id is marked in it.
  std::uint32_t next_generation(std::size_t ids) {
    if (seen.size() != ids) {
      seen.assign(ids, 0);
      slot.assign(ids, 0);
    }
    if (++generation == 0) {
      std::fill(seen.begin(), seen.end(), 0u);
      generation = 1;
    }
    return generation;
  }
};

// Per candidate of a tile's list, ray_meets_triangle's signs as far as the tile knows them: the
// eye's side of its plane (exact, one eye for every ray), and for a ray's direction d, with
// |d_i| <= W_i over the tile, filters of orient(a, b, c, d) = d . ((b - a) x (c - a)) and of
// orient(e, d, p, q) = d . ((p - e) x (q - e)) per edge (EdgePlaneFilter::sign_along): one dot
// product each per ray, the exact sign where they cannot decide.
// Each filter is kept as its normal and bound alone (32 bytes, not EdgePlaneFilter's 80): the
// scan reads a candidate's four per ray, and decides "apart" without a branch per sign.
struct CandidateRaySigns {
  // Plane 0 the triangle's (the direction's side), planes 1-3 its edges' through the eye.
  struct Plane {
    Vec3 n;
    double bound;  // EdgePlaneFilter::terms' bound
  };
  Sign eye_side;
  double side;  // eye_side as -1, 0 or +1
  std::array<Plane, 4> planes;
  // N = det[b - a, c - a, a - e] of the candidate's ray parameters t = N / D, one for the tile's
  // rays (their eye): with plane 0's fl(d . n) and bound as D's estimate, a listed ray's
  // parameter costs a division (RayParameter's estimates constructor).
  detail::BoundedEstimate numerator;

  // fl(d . n) of plane p, as EdgePlaneFilter::sign_along forms it.
  [[nodiscard]] double along(std::size_t p, const Vec3& d) const {
    return d[0] * planes[p].n[0] + d[1] * planes[p].n[1] + d[2] * planes[p].n[2];
  }
  // The sign the filter certifies from v = along(p, d), or nullopt.
  [[nodiscard]] std::optional<Sign> sign_of(std::size_t p, double v) const {
    if (v > planes[p].bound) return Sign::positive;
    if (v < -planes[p].bound) return Sign::negative;
    return std::nullopt;
  }
};

std::vector<CandidateRaySigns> candidate_ray_signs(const ImageGeometry& g, const std::vector<std::uint32_t>& ids,
                                                   const Vec3& eye, const Vec3& W) {
  std::vector<CandidateRaySigns> out;
  out.reserve(ids.size());
  // The filters' terms alone (no |n|, no middle): they are read as normals and bounds.
  const auto plane = [&W](const Vec3& m, const Vec3& p, const Vec3& q) {
    const EdgePlaneFilter::Terms t = EdgePlaneFilter::terms(m, Vec3{}, W, p, q);
    return CandidateRaySigns::Plane{t.n, t.bound};
  };
  for (std::uint32_t id : ids) {
    const Vec3 &a = g.vertex(id, 0), &b = g.vertex(id, 1), &c = g.vertex(id, 2);
    const Sign eye_side = detail::orient_unchecked(finite_point(a), finite_point(b), finite_point(c), finite_point(eye));
    out.push_back({eye_side,
                   eye_side == Sign::zero ? 0.0 : eye_side == Sign::positive ? 1.0 : -1.0,
                   {plane(a, b, c), plane(eye, a, b), plane(eye, b, c), plane(eye, c, a)},
                   detail::plane_numerator_estimate(eye, a, b, c)});
  }
  return out;
}

// Sorts `ids` by their triangles' distance from `eye`, nearest first, into `near`: per
// candidate a lower bound on the distance from the eye to its bounding box (each gap to the box,
// its square, the sum and the root a few roundings of relative 2^-53; 2^-40 taken off; 0
// where it overflows). first_hit stops its scan of the list at the first that lies beyond its
// best meeting.
void order_by_distance(const ImageGeometry& g, const Vec3& eye, std::vector<std::uint32_t>& ids,
                       std::vector<double>& near) {
  std::vector<std::pair<double, std::uint32_t>> order;
  order.reserve(ids.size());
  for (std::uint32_t id : ids) {
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double a = g.vertex(id, 0)[k], b = g.vertex(id, 1)[k], c = g.vertex(id, 2)[k];
      const double lo = std::min({a, b, c}), hi = std::max({a, b, c});
      const double gap = std::max({lo - eye[k], eye[k] - hi, 0.0});
      sum += gap * gap;
    }
    const double distance = std::sqrt(sum) * (1.0 - 0x1p-40);
    order.emplace_back(std::isfinite(distance) ? distance : 0.0, id);
  }
  std::sort(order.begin(), order.end());
  near.resize(ids.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    near[k] = order[k].first;
    ids[k] = order[k].second;
  }
}

// The candidates each ray of a traced eye tile (or quarter) scans: blocks of kRayBlock x
// kRayBlock pixels (reference/detail/eye_blocks.h) share a list, the tile's without the
// candidates that every ray of the block certainly misses (on ogre's dense tiles a triangle
// covers a few pixels: most of a long list misses most blocks). A block holds the image points
// of its pixels' centres and of the corners on its closed square, and each ray reads the block
// holding its own point. Lists shorter than kRayBlockMinCandidates are scanned whole. The
// scans are ascending indices, so first_hit's nearest-first pruning holds.
inline constexpr std::uint32_t kRayBlock = 2;
static_assert((kTileSize + kRayBlock - 1) / kRayBlock * ((kTileSize + kRayBlock - 1) / kRayBlock) <=
              detail::EyeBlocks::kMaskBlocks);
inline constexpr std::size_t kRayBlockMinCandidates = 8;

class RayBlocks {
 public:
  RayBlocks(const CameraFrame& frame, const TileGrid::Bounds& b, const std::vector<CandidateRaySigns>& signs,
            TileScratch& scratch)
      : scan_(scratch.block_scan), begin_(scratch.block_begin) {
    scan_.clear();
    begin_.assign(1, 0);
    if (signs.size() < kRayBlockMinCandidates) {
      for (std::uint32_t k = 0; k < signs.size(); ++k) scan_.push_back(k);
      begin_.push_back(static_cast<std::uint32_t>(scan_.size()));
      return;
    }
    blocks_.emplace(frame, b.x0, b.x1, b.y0, b.y1, kRayBlock);
    const detail::EyeBlocks& blocks = *blocks_;
    // Per candidate, whether each block's rays all miss it: its plane behind the eye, or an
    // edge line with the crossing outside, for every ray of the block (ray_meets_triangle's
    // own verdicts; the eye on the plane leaves each ray to decide). A filter's bound B
    // covers twice the normal's rounding at every direction of the tile (EdgePlaneFilter):
    // the normal's error is B / 2.
    const std::uint32_t count = blocks.columns() * blocks.rows();
    std::vector<std::uint32_t>& misses = scratch.block_misses;  // per candidate, a bit per block
    misses.assign(signs.size(), 0);
    for (std::size_t k = 0; k < signs.size(); ++k) {
      const CandidateRaySigns& f = signs[k];
      if (f.eye_side == Sign::zero) continue;
      std::array<detail::EyeBlocks::Plane, 4> planes;
      for (std::size_t p = 0; p < 4; ++p) planes[p] = blocks.plane(f.planes[p].n, 0.5 * f.planes[p].bound);
      misses[k] = blocks.blocks_decided(planes[0]) &
                  (blocks.blocks_on_side(planes[0], f.eye_side) | blocks.blocks_on_side(planes[1], f.eye_side) |
                   blocks.blocks_on_side(planes[2], f.eye_side) | blocks.blocks_on_side(planes[3], f.eye_side));
    }
    scan_.resize(std::size_t{count} * signs.size());
    std::size_t size = 0;
    for (std::uint32_t block = 0; block < count; ++block) {
      for (std::uint32_t k = 0; k < signs.size(); ++k) {  // without a branch per candidate
        scan_[size] = k;
        size += (misses[k] >> block & 1u) ^ 1u;
      }
      begin_.push_back(static_cast<std::uint32_t>(size));
    }
  }

  // The scan of the ray through image point (x, y) (a corner) or (x + 0.5, y + 0.5) (a
  // centre) of the tile: x up to the tile's x1, y up to its y1.
  [[nodiscard]] std::span<const std::uint32_t> scan(std::uint32_t x, std::uint32_t y) const {
    const std::size_t block =
        blocks_ ? std::size_t{blocks_->row_of(y)} * blocks_->columns() + blocks_->column_of(x) : 0;
    return {scan_.data() + begin_[block], begin_[block + 1] - begin_[block]};
  }

 private:
  std::optional<detail::EyeBlocks> blocks_;
  std::vector<std::uint32_t>& scan_;
  std::vector<std::uint32_t>& begin_;
};

// An upper bound on |d| (1 + 2^-41) for every direction d with |d_i| <= W_i (the sum's and the
// root's few roundings, a relative 2^-53 each, 2^-40 added): first_hit's pruning length for the
// rays of an eye tile, W its eye_tile_direction_bound.
double direction_length_bound(const Vec3& W) {
  return std::sqrt(W[0] * W[0] + W[1] * W[1] + W[2] * W[2]) * (1.0 + 0x1p-40);
}

// The list the footprint tests read: the eye tile's, where it holds at most kTileCandidates.
const std::vector<std::uint32_t>* footprint_list(const TileCandidates& tile) {
  const std::vector<std::uint32_t>* list = tile.list();
  return list != nullptr && list->size() <= kTileCandidates ? list : nullptr;
}

TileCandidates tile_candidates(const ImageGeometry& g, const std::optional<detail::EyeTileCone>& cone,
                               TileScratch& scratch) {
  TileCandidates out;
  if (!cone) return out;
  const std::uint32_t generation = scratch.next_generation(g.soup.triangles.size());
  bool overflow = false;
  const auto collect = [&](std::uint32_t id) {
    if (scratch.seen[id] == generation) return true;
    scratch.seen[id] = generation;
    out.ids.push_back(id);
    overflow = out.ids.size() > kEyeTileCandidates;
    return !overflow;
  };
  for (const detail::DilatedSegment& piece : *cone) {
    g.tree.dilated_segment_query(piece.from, piece.to, piece.slack, collect);
    if (overflow) return {};
  }
  out.listed = true;
  return out;
}

// Calls visit(id) for every box of `tree` that a segment from a point of [lo, hi] (a box of
// hit points) to the light l can meet (for a directional light, the ray from it along l), until
// visit returns false. For a point light the segments from P = m + e (m the box's middle,
// |e_i| <= half_i) reach m + t (L - m) + (1 - t) e at parameter t: pieces [t0, t1] of the
// segment m -> L dilated by (1 - t0) half (a cone narrowing to the light), plus the rounding of
// their end points. For a directional light, the ray from m along it dilated by half.
inline constexpr std::array<double, 5> kLightTileCuts{0.0, 0.25, 0.5, 0.75, 1.0};

template <typename Visit>
void light_cone_query(const detail::BoxTree& tree, const HomogeneousPoint& l, const Vec3& lo, const Vec3& hi,
                      Visit&& visit) {
  bool stopped = false;
  const auto until_stopped = [&](std::uint32_t id) { return !(stopped = !visit(id)); };
  Vec3 m{}, half{};
  for (int a = 0; a < 3; ++a) {
    m[a] = std::clamp(lo[a] / 2 + hi[a] / 2, lo[a], hi[a]);
    half[a] = std::max(hi[a] - m[a], m[a] - lo[a]) * (1.0 + 0x1p-50);
  }
  const Vec3 to{l[0], l[1], l[2]};
  if (l[3] == 0.0) {
    Vec3 slack{};
    for (int a = 0; a < 3; ++a) slack[a] = std::nextafter(half[a] + 0x1p-1000, std::numeric_limits<double>::infinity());
    tree.dilated_ray_query(m, to, slack, until_stopped);
    return;
  }
  const auto at = [&](double t) {
    return Vec3{m[0] + t * (to[0] - m[0]), m[1] + t * (to[1] - m[1]), m[2] + t * (to[2] - m[2])};
  };
  for (std::size_t piece = 0; piece + 1 < kLightTileCuts.size() && !stopped; ++piece) {
    const double t0 = kLightTileCuts[piece];
    Vec3 slack{};
    for (int a = 0; a < 3; ++a)
      slack[a] = std::nextafter((1.0 - t0) * half[a] * (1.0 + 0x1p-50) +
                                    0x1p-50 * (std::fabs(m[a]) + std::fabs(to[a])) + 0x1p-1000,
                                std::numeric_limits<double>::infinity());
    tree.dilated_segment_query(at(t0), at(kLightTileCuts[piece + 1]), slack, until_stopped);
  }
}

// The ids light_cone_query reports that `keep` keeps, each once, when there are at most `cap`
// of them (`ids`: the number of boxes of the tree).
template <typename Keep>
TileCandidates light_cone_candidates(const detail::BoxTree& tree, std::size_t ids, const HomogeneousPoint& l,
                                     const Vec3& lo, const Vec3& hi, Keep&& keep, TileScratch& scratch,
                                     std::size_t cap = kTileCandidates) {
  TileCandidates out;
  const std::uint32_t generation = scratch.next_generation(ids);
  bool overflow = false;
  light_cone_query(tree, l, lo, hi, [&](std::uint32_t id) {
    if (scratch.seen[id] == generation) return true;
    scratch.seen[id] = generation;
    if (!keep(id)) return true;
    out.ids.push_back(id);
    overflow = out.ids.size() > cap;
    return !overflow;
  });
  if (overflow) return {};
  out.listed = true;
  return out;
}

// Whether triangle `id` can change a count for a light whose sides are `sides`: a caster
// (`casts` empty: every triangle) that the light is off the plane of; count_at passes the rest
// by (docs/definitions.md#orientation).
bool countable_caster(std::span<const std::uint8_t> casts, const std::vector<Sign>& sides, std::uint32_t id) {
  return (casts.empty() || casts[id] != 0) && sides[id] != Sign::zero;
}

// A tile's list for light number `light` (count_at's candidates): every casting triangle that
// the light does not lie on and that a segment from [lo, hi] (the box of the tile's hit points
// to count) to the light can meet.
TileCandidates light_tile_candidates(const ImageGeometry& g, std::size_t light, const Vec3& lo, const Vec3& hi,
                                     TileScratch& scratch, std::size_t cap) {
  return light_cone_candidates(
      g.tree, g.soup.triangles.size(), g.lights[light], lo, hi,
      [&](std::uint32_t id) { return countable_caster(g.casts, g.light_sides[light], id); }, scratch, cap);
}

// count_at's test of one candidate, filtered for a tile's hit points towards a point light L:
// P's side of the candidate's plane, orient(a, b, c, P) (`plane`, through a), and per edge uv
// orient(P, L, u, v) = -sign((P - L) . ((u - L) x (v - L))) (`edges`, through L). `side`: the
// light's side of the plane (nonzero: light_tile_candidates keeps no other).
struct SegmentCrossingFilter {
  detail::PlaneThroughFilter plane;
  std::array<detail::PlaneThroughFilter, 3> edges;
  int side = 0;

  SegmentCrossingFilter() = default;
  // Triangle abc on its side `light_side` of the point light L, for points x with |x - a| <= W
  // per axis (WL from L) within R of their box middles; every member built in place.
  SegmentCrossingFilter(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& W, const Vec3& L, const Vec3& WL,
                        const Vec3& R, int light_side)
      : plane(a, b, c, W, R),
        edges{detail::PlaneThroughFilter(L, a, b, WL, R), detail::PlaneThroughFilter(L, b, c, WL, R),
              detail::PlaneThroughFilter(L, c, a, WL, R)},
        side(light_side) {}
};

// What the filters say of the open segment P -> L and one candidate: apart, crosses, or
// undecided (count_at decides). `x`: P's box middle.
enum class FilteredCrossing : std::uint8_t { apart, crosses, undecided };
// With P's side of the plane known (`start`, nonzero).
// The three edges' signs are all taken before any verdict, and combined without a branch per
// sign: they vary from point to point, and a mispredicted branch costs more than the two dot
// products an early "apart" would save.
FilteredCrossing filtered_crossing(const SegmentCrossingFilter& f, const Vec3& x, int start) {
  // exact/face_crossing.h's rule as count_at: crossing X strictly inside iff orient(P, L, u, v)
  // = -start for every edge, outside if one has +start; orient = -(filter's sign), so
  // w = -orient * start is the filter's sign times start.
  const int w0 = f.edges[0].sign(x) * start, w1 = f.edges[1].sign(x) * start, w2 = f.edges[2].sign(x) * start;
  const bool outside = (w0 < 0) | (w1 < 0) | (w2 < 0);
  if ((start == f.side) | outside) return FilteredCrossing::apart;  // P and L on one side, or X outside
  return (w0 > 0) & (w1 > 0) & (w2 > 0) ? FilteredCrossing::crosses : FilteredCrossing::undecided;
}

FilteredCrossing filtered_crossing(const SegmentCrossingFilter& f, const Vec3& x) {
  const int start = f.plane.sign(x);
  if (start == 0) return FilteredCrossing::undecided;
  return filtered_crossing(f, x, start);
}

// P's side of the plane of triangle `id`, orient(a, b, c, P), for P strictly inside triangle h
// (a countable hit), where h alone decides it: 0 when id lies in h's plane (its three vertices
// on it; count_at then passes it by), and where id shares an edge uv with h (equal
// coordinates) the sign of orient(a, b, c, x) for h's third vertex x: orient(a, b, c, .) is
// affine and zero at u and v, and P = alpha u + beta v + gamma x with gamma > 0 (P is off the
// edge), so its sign at P is gamma times that at x. This settles the triangles that are in h's
// plane up to the rounding of their vertices (the two halves of a UV sphere's planar quads),
// where the filters cannot. kUnknownSide otherwise. Remembered in `known` for this h.
inline constexpr int kUnknownSide = 2;
int side_beside(const ImageGeometry& g, std::uint32_t h, std::uint32_t id,
                std::vector<std::pair<std::uint32_t, std::int8_t>>& known) {
  for (const auto& [other, side] : known)
    if (other == id) return side;
  const std::array<Vec3, 3> hv{g.vertex(h, 0), g.vertex(h, 1), g.vertex(h, 2)};
  const HomogeneousPoint a = finite_point(hv[0]), b = finite_point(hv[1]), c = finite_point(hv[2]);
  int side = kUnknownSide;
  if (std::all_of(g.soup.triangles[id].begin(), g.soup.triangles[id].end(), [&](std::uint32_t v) {
        return detail::orient_unchecked(a, b, c, finite_point(g.soup.vertices[v])) == Sign::zero;
      })) {
    side = 0;
  } else {
    const std::array<Vec3, 3> tv{g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2)};
    int shared = 0, third = -1;
    for (int i = 0; i < 3; ++i) {
      const bool in = std::find(tv.begin(), tv.end(), hv[static_cast<std::size_t>(i)]) != tv.end();
      shared += in;
      if (!in) third = i;
    }
    // Two shared vertices: x is off id's plane, or id would lie in h's plane.
    if (shared == 2)
      side = static_cast<int>(detail::orient_unchecked(finite_point(tv[0]), finite_point(tv[1]), finite_point(tv[2]),
                                                       finite_point(hv[static_cast<std::size_t>(third)])));
  }
  known.emplace_back(id, static_cast<std::int8_t>(side));
  return side;
}

// count_at's count for one hit point P of a filtered count group (candidates(visit) calls
// visit(id, filter) for each candidate of P, a list holding every casting triangle P's segment
// can meet, with its filter; `middle`: P's box middle): the crossings the filters certify, P's
// side taken from the hit triangle where it decides (side_beside), plus count_rest(candidates
// left), count_at's verdict on them, called only when some are left (P's ray and box are built
// there: at most a few hundred of ogre's 910K hit points need them). local.side_of/side_known
// must hold the answers for this hit's triangle.
template <typename Candidates, typename CountRest>
std::uint32_t filtered_count(const ImageGeometry& g, const RayHit& hit, Candidates&& candidates, const Vec3& middle,
                             TileScratch& local, CountRest&& count_rest) {
  const std::uint32_t h = hit.triangle;
  std::uint32_t crossed = 0;
  local.undecided.clear();
  candidates([&](std::uint32_t id, const SegmentCrossingFilter& filter) {
    if (id == h || id == local.in_plane_of_side_of) return;
    FilteredCrossing verdict = filtered_crossing(filter, middle);
    if (verdict == FilteredCrossing::undecided) {
      const int start = side_beside(g, h, id, local.side_known);
      if (start == 0) {  // in h's plane: count_at passes it by
        local.in_plane_of_side_of = id;
        return;
      }
      if (start != kUnknownSide) verdict = filtered_crossing(filter, middle, start);
    }
    if (verdict == FilteredCrossing::crosses) ++crossed;
    if (verdict == FilteredCrossing::undecided) local.undecided.push_back(id);
  });
  if (local.undecided.empty()) return crossed;
  const std::uint32_t more = count_rest(local.undecided);
  return more == kUndefinedCount ? kUndefinedCount : crossed + more;
}

// What the filters of one group of hit points share: the point light L, the box [lo, hi] of the
// points' box middles and the radius R around them, and the bound on |x - L| over that box.
struct CrossingFrame {
  Vec3 L, lo, hi, R, WL;
  CrossingFrame(const HomogeneousPoint& l, const Vec3& middles_lo, const Vec3& middles_hi, const Vec3& radius)
      : L{l[0], l[1], l[2]}, lo(middles_lo), hi(middles_hi), R(radius), WL(reach(L)) {}
  // |x - o| <= max(|lo - o|, |hi - o|) per axis, rounded up, for every x in [lo, hi].
  [[nodiscard]] Vec3 reach(const Vec3& o) const {
    Vec3 w{};
    for (int a = 0; a < 3; ++a) w[a] = std::max(std::fabs(lo[a] - o[a]), std::fabs(hi[a] - o[a])) * (1.0 + 0x1p-50);
    return w;
  }
};

// The filters of candidate `id` for light number `light` in `frame`, built in place (a
// filter is 232 bytes: a copy read back before its stores retire stalls).
void add_segment_crossing_filter(const ImageGeometry& g, std::size_t light, std::uint32_t id,
                                 const CrossingFrame& frame, std::vector<SegmentCrossingFilter>& filters) {
  const Vec3 &a = g.vertex(id, 0), &b = g.vertex(id, 1), &c = g.vertex(id, 2);
  filters.emplace_back(a, b, c, frame.reach(a), frame.L, frame.WL, frame.R, static_cast<int>(g.light_sides[light][id]));
}

// The light-independent ambiguity of a pixel: a zero sign on a footprint ray, or footprint
// rays that see different triangles (or not all a triangle).
std::uint8_t footprint_ambiguity(const RayHits& hits, const std::array<std::size_t, 5>& rays) {
  std::uint8_t bits = 0;
  for (std::size_t ray : rays) {
    if (hits[ray].degenerate) bits |= kZeroSign;
    if (hits[ray].triangle != hits[rays[0]].triangle) bits |= kFootprintTriangles;
  }
  return bits;
}

[[nodiscard]] bool terminator(const ImageGeometry& g, std::size_t light, const RayHit& hit) {
  return g.light_sides[light][hit.triangle] != hit.eye_side;  // includes s = 0: the light on the plane
}

// Where pixel (i, r)'s corner rays meet its hit triangle's plane (all four see it,
// non-degenerately), in cyclic order.
struct CornerHits {
  std::array<detail::RayParameter, 4> parameters;
  detail::FootprintPolytope::CornerBoxes boxes;  // their HitPoint boxes, from the cache
};

CornerHits corner_hits(const ImageGeometry& g, const RayGrid& grid, const RayHits& hits,
                       const detail::HitPointBoxes& point_boxes, std::uint32_t i, std::uint32_t r) {
  const std::array<std::size_t, 4> corners{grid.corner(i, r), grid.corner(i + 1, r), grid.corner(i + 1, r + 1),
                                           grid.corner(i, r + 1)};
  const std::array<std::array<std::uint32_t, 2>, 4> at_corner{{{i, r}, {i + 1, r}, {i + 1, r + 1}, {i, r + 1}}};
  const auto at = [&](std::size_t k) {
    const RayHit& hit = hits[corners[k]];
    const std::uint32_t h = hit.triangle;
    return detail::RayParameter(grid.corner_ray(at_corner[k][0], at_corner[k][1]), g.vertex(h, 0), g.vertex(h, 1),
                                g.vertex(h, 2), hit.direction_side, detail::RayParameter::Unenclosed{});
  };
  return {{at(0), at(1), at(2), at(3)},
          {point_boxes[corners[0]], point_boxes[corners[1]], point_boxes[corners[2]], point_boxes[corners[3]]}};
}

// The boxes HitPoint computes for four parameters (the backdrop's corners, not cached).
CornerHits with_boxes(const std::array<detail::RayParameter, 4>& parameters) {
  CornerHits out{parameters, {}};
  for (std::size_t k = 0; k < 4; ++k) {
    const detail::HitPoint p(parameters[k]);
    out.boxes[k] = {p.lo(), p.hi()};
  }
  return out;
}

// A plane beyond every vertex, facing the eye: the far end of the eye pyramid over a pixel whose
// five rays see nothing (footprint_sees_more with no hit triangle). Its triangle spans
// eye + D (forward, forward + right, forward + up) with D twice the largest distance from the
// eye to a vertex plus 1, so every vertex lies strictly between the eye and the plane (the
// rounding of its points tilts it by a relative 2^-52 at most).
struct Backdrop {
  std::array<Vec3, 3> triangle{};

  // std::nullopt when a corner ray would not meet the plane in front of the eye (the caller
  // then calls the pixel ambiguous; not seen for any finite scene).
  static std::optional<Backdrop> behind(const Soup& soup, const CameraFrame& frame) {
    double farthest = 0.0;
    for (const Vec3& v : soup.vertices) {
      const Vec3 d = difference(v, frame.eye);
      farthest = std::max(farthest, std::sqrt(dot(d, d)));
    }
    const double depth = 2.0 * farthest + 1.0;
    if (!std::isfinite(depth)) return std::nullopt;
    Backdrop b;
    for (std::size_t k = 0; k < 3; ++k) {
      b.triangle[0][k] = frame.eye[k] + depth * frame.forward[k];
      b.triangle[1][k] = b.triangle[0][k] + depth * frame.right[k];
      b.triangle[2][k] = b.triangle[0][k] + depth * frame.up[k];
    }
    return b;
  }

  // Where pixel (i, r)'s corner rays meet the plane, in corner_hits' cyclic order.
  [[nodiscard]] std::array<detail::RayParameter, 4> corners(const RayGrid& grid, std::uint32_t i,
                                                            std::uint32_t r) const {
    const std::array<std::size_t, 4> rays{grid.corner(i, r), grid.corner(i + 1, r), grid.corner(i + 1, r + 1),
                                          grid.corner(i, r + 1)};
    const auto at = [&](std::size_t k) {
      const PixelRay ray = grid.ray(rays[k]);
      const detail::RayMeeting m = detail::ray_meets_triangle(ray, triangle[0], triangle[1], triangle[2]);
      if (m.direction_side == Sign::zero || m.eye_side != -m.direction_side)
        throw std::logic_error("exact_image: a corner ray misses the backdrop plane");
      return detail::RayParameter(ray, triangle[0], triangle[1], triangle[2], m.direction_side);
    };
    return {at(0), at(1), at(2), at(3)};
  }
};

// Whether something besides triangle h is seen inside the footprint: an edge of another
// triangle crosses the eye pyramid over it (reference/detail/pixel_footprint.h).
// sign det[x, y, z] of three rows, each an input vector or a rounded difference of doubles,
// when the semi-static filter of exact/light_orientation_filter.h certifies it (CGAL's static
// filter for Orientation_3: an exact row only makes its bound an over-estimate); nullopt
// otherwise. Round-to-nearest, no rounding-mode switch.
std::optional<Sign> filtered_det_sign(const Vec3& x, const Vec3& y, const Vec3& z) {
  const double max0 = std::max({std::fabs(x[0]), std::fabs(y[0]), std::fabs(z[0])});
  const double max1 = std::max({std::fabs(x[1]), std::fabs(y[1]), std::fabs(z[1])});
  const double max2 = std::max({std::fabs(x[2]), std::fabs(y[2]), std::fabs(z[2])});
  if (std::min({max0, max1, max2}) < detail::kOrientationUnderflowGuard ||
      std::max({max0, max1, max2}) >= detail::kOrientationOverflowGuard)
    return std::nullopt;
  const double m01 = x[0] * y[1] - y[0] * x[1];
  const double m02 = x[0] * z[1] - z[0] * x[1];
  const double m12 = y[0] * z[1] - z[0] * y[1];
  const double det = m01 * z[2] - m02 * y[2] + m12 * x[2];
  const double bound = detail::kOrientationErrorFactor * max0 * max1 * max2;
  if (det > bound) return Sign::positive;
  if (det < -bound) return Sign::negative;
  return std::nullopt;
}

// Which triangles lie in the plane of a hit triangle h, beside it as the eye sees it (a
// property of h, the triangle and the eye alone, whatever pixel is asked: a tile caches it).
class HitPlaneNeighbours {
 public:
  HitPlaneNeighbours(const Vec3& eye, const std::array<Vec3, 3>& h) : eye_(eye), h_(h) {
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& w = h[(k + 2) % 3];
      h_side_[k] = detail::semi_static_light_orientation(eye, h[k], h[(k + 1) % 3], {w[0], w[1], w[2], 1.0})
                       .value_or(Sign::zero);  // zero: this edge line is not used
    }
  }

  // Whether triangle abc lies in h's plane and outside h. For a pixel whose five rays cross h
  // (not at a zero sign) its eye pyramid meets that plane in R alone, and R lies strictly
  // inside h (its corners are crossings of h), so an abc with every
  // vertex on the closed far side of one of h's edge lines misses R, and so does each of its
  // edges. In h's plane the side of the line uv is the side of the plane through the eye, u
  // and v (the eye is off h's plane). The other half of a floor quad, every floor pixel's
  // candidate, is caught here.
  [[nodiscard]] bool beside_in_plane(const Vec3& a, const Vec3& b, const Vec3& c) const {
    const auto in_plane = [&](const Vec3& v) {
      const std::optional<Sign> s = detail::semi_static_light_orientation(h_[0], h_[1], h_[2], {v[0], v[1], v[2], 1.0});
      return s && *s == Sign::zero;  // the filter says zero only for an exactly zero determinant
    };
    if (!in_plane(a) || !in_plane(b) || !in_plane(c)) return false;
    for (std::size_t k = 0; k < 3; ++k) {
      if (h_side_[k] == Sign::zero) continue;
      const Vec3& u = h_[k];
      const Vec3& v = h_[(k + 1) % 3];
      const auto far_or_on = [&](const Vec3& w) {
        if (w == u || w == v) return true;  // on the line (a shared vertex: the filter cannot say zero)
        const std::optional<Sign> s = detail::semi_static_light_orientation(eye_, u, v, {w[0], w[1], w[2], 1.0});
        return s && *s != h_side_[k];
      };
      if (far_or_on(a) && far_or_on(b) && far_or_on(c)) return true;
    }
    return false;
  }

 private:
  Vec3 eye_;
  std::array<Vec3, 3> h_;
  std::array<Sign, 3> h_side_{};  // h's side of the plane through the eye and each of its edges
};

// The eye pyramid hull{e, R} over a pixel lies in five closed half-spaces known without its hit
// points: beside each face through the eye and two neighbouring corner rays (d_k, d_k+1), on the
// side of the next corner ray (the corner rays span a convex cone, R lies in it), and on the
// eye's side of h's plane (R lies in it). A triangle each of whose edges has both ends
// certainly strictly outside one of them (or each end beyond h's plane or at a vertex of h:
// outcode's bit 5) has no edge in the pyramid: the exact answer of
// FootprintPolytope::meets_an_edge_of, found with a few filtered determinants of input doubles
// (most candidates are h's neighbours beside R or triangles behind h's plane). Where a filter
// is unsure, the polytope decides as before.
class EyePyramidFilter {
 public:
  EyePyramidFilter(const Vec3& eye, const CornerHits& corners, const std::array<Vec3, 3>& h, Sign eye_side)
      : eye_(eye), h_(h), eye_side_(eye_side), neighbours_(eye, h) {
    std::array<Vec3, 4> directions;
    for (std::size_t k = 0; k < 4; ++k) directions[k] = corners.parameters[k].ray().direction;
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec3 &a = directions[k], &b = directions[(k + 1) % 4];
      const std::optional<Sign> s = filtered_det_sign(a, b, directions[(k + 2) % 4]);
      inside_[k] = s.value_or(Sign::zero);  // zero: this face is not used
      // The face's normal and its bound's coefficients (FaceFilter); an untame or non-finite
      // face is not used either.
      const detail::RoundedCross cross = detail::rounded_cross(a, b);
      FaceFilter& f = faces_[k];
      f.n = cross.n;
      bool usable = true;
      for (std::size_t i = 0; i < 3; ++i) {
        f.c[i] = 4.02 * 0x1p-53 * std::fabs(cross.n[i]) + 1.0001 * cross.e[i];
        usable = usable && std::fabs(a[i]) <= kTameFace && std::fabs(b[i]) <= kTameFace && std::isfinite(f.c[i]);
      }
      if (!usable) inside_[k] = Sign::zero;
    }
  }

  // HitPlaneNeighbours::beside_in_plane (an abc there has no edge in the pyramid).
  [[nodiscard]] bool beside_in_plane(const Vec3& a, const Vec3& b, const Vec3& c) const {
    return neighbours_.beside_in_plane(a, b, c);
  }

  // Whether no edge of triangle abc meets the pyramid: each edge has both ends certainly
  // strictly outside one common half-space (bits 0-4 of outcode()), or both beyond h's plane
  // or at a vertex of h (bit 5).
  [[nodiscard]] bool separates(const Vec3& a, const Vec3& b, const Vec3& c) const {
    const unsigned oa = outcode(a);
    if (oa == 0) return false;
    const unsigned ob = outcode(b);
    if ((oa & ob) == 0) return false;
    const unsigned oc = outcode(c);
    return (ob & oc) != 0 && (oc & oa) != 0;
  }


 private:
  // Bit k (k < 4): v certainly strictly outside the face through corner rays k, k + 1; bit 4:
  // certainly strictly beyond h's plane; bit 5: that, or v is a vertex of h (equal coordinates).
  // Bit 5 is no half-space, but an edge with it at both ends misses the pyramid all the same:
  // the pyramid lies on the eye's side of h's plane and meets that plane in R alone, strictly
  // inside h, so an edge beyond the plane but for an end at a vertex of h, or an edge of h
  // itself, misses it (the neighbours of h behind its plane, on a convex patch all of them).
  [[nodiscard]] unsigned outcode(const Vec3& v) const {
    unsigned code = v == h_[0] || v == h_[1] || v == h_[2] ? 32u : 0u;
    const std::optional<Sign> beyond = detail::semi_static_light_orientation(h_[0], h_[1], h_[2], {v[0], v[1], v[2], 1.0});
    if (beyond && *beyond == -eye_side_) code |= 16u | 32u;
    const Vec3 z = difference(v, eye_);
    const Vec3 m{std::fabs(z[0]), std::fabs(z[1]), std::fabs(z[2])};
    if (!(std::max({m[0], m[1], m[2]}) <= kTameFace)) return code;  // no face bit (a NaN declines too)
    for (std::size_t k = 0; k < 4; ++k) {
      if (inside_[k] == Sign::zero) continue;
      const FaceFilter& f = faces_[k];
      const double value = f.n[0] * z[0] + f.n[1] * z[1] + f.n[2] * z[2];
      const double bound = (m[0] * f.c[0] + m[1] * f.c[1] + m[2] * f.c[2]) * (1.0 + 0x1p-20) + 0x1p-800;
      const int sign = static_cast<int>(value > bound) - static_cast<int>(value < -bound);
      if (sign == -static_cast<int>(inside_[k])) code |= 1u << k;
    }
    return code;
  }

  // The sign of det[d_k, d_k+1, v - e] = N . Z (N = d_k x d_k+1 and Z = v - e, exact) from
  // n = fl(d_k x d_k+1) (detail::rounded_cross: |n_i - N_i| <= e_i) and z = fl(v - e), one dot
  // product per vertex instead of a determinant per vertex and face (the outcodes were most of
  // a footprint test's time). |fl(n . z) - N . Z| <= sum_i |z_i| (4.02 u |n_i| + 1.0001 e_i):
  // the dot product's three roundings (3.01 u |n_i z_i|), z's own (u |n_i| |Z_i|) and n's
  // (e_i |Z_i|), with |Z_i| <= |z_i| / (1 - u). The bound's own evaluation is widened by 2^-20
  // relative and 2^-800 absolute (underflow), as PlaneThroughFilter's; inputs beyond
  // kTameFace decline (no product can overflow, no underflow error reach 2^-800).
  struct FaceFilter {
    Vec3 n{};
    Vec3 c{};  // c_i: the coefficient of |z_i| in the bound
  };
  static constexpr double kTameFace = 0x1p200;

  Vec3 eye_;
  std::array<Vec3, 3> h_;
  Sign eye_side_;
  std::array<FaceFilter, 4> faces_{};
  std::array<Sign, 4> inside_{};
  HitPlaneNeighbours neighbours_;
};

// The pyramid itself is built only for the first candidate other than h that the cheap filter
// (EyePyramidFilter, for a hit triangle) leaves (most pixels of a mesh have none).
// `candidates`: as first_hit's (every triangle the pixel's eye pyramid can meet), or nullptr:
// the box tree's query. The answer is whether some triangle passes the exact test, so both give it.
bool footprint_sees_more(const ImageGeometry& g, const Vec3& eye, const CornerHits& corners, std::uint32_t h,
                         const EyePyramidFilter* filter = nullptr,
                         const std::vector<std::uint32_t>* candidates = nullptr) {
  std::optional<detail::FootprintPolytope> pyramid;
  bool more = false;
  const auto visit = [&](std::uint32_t id) {
    if (id == h) return true;
    if (filter != nullptr && (filter->separates(g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2)) ||
                              filter->beside_in_plane(g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2))))
      return true;
    if (!pyramid) pyramid.emplace(finite_point(eye), corners.parameters, corners.boxes);
    if (!pyramid->meets_an_edge_of(g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2))) return true;
    more = true;
    return false;
  };
  Vec3 from, slack;
  detail::FootprintPolytope::query_box(corners.boxes, from, slack);
  if (candidates != nullptr) {
    // The tile's list through the walk's own box test for this pixel first (a slab test costs
    // a tenth of the filter's determinants, and most entries lie beside this pixel's pyramid).
    g.tree.dilated_segment_query(from, eye, slack, std::span<const std::uint32_t>(*candidates), visit);
    return more;
  }
  g.tree.dilated_segment_query(from, eye, slack, visit);
  return more;
}

// Whether n changes over the footprint: a silhouette edge crosses its light pyramid.
// As footprint_sees_more, the pyramid is built for the first candidate edge only.
// `candidates`: a list holding every silhouette edge the light pyramid can meet (its tile's),
// or nullptr: the silhouette tree's query.
bool footprint_shadow_varies(const ImageGeometry& g, std::size_t light, const CornerHits& corners,
                             const std::vector<std::uint32_t>* candidates = nullptr) {
  const HomogeneousPoint& l = g.lights[light];
  std::optional<detail::FootprintPolytope> pyramid;
  const Silhouette& silhouette = *g.silhouettes[light];
  bool varies = false;
  const auto visit = [&](std::uint32_t id) {
    if (!pyramid) pyramid.emplace(l, corners.parameters, corners.boxes);
    if (!pyramid->meets(silhouette.edges[id][0], silhouette.edges[id][1])) return true;
    varies = true;
    return false;
  };
  Vec3 from, slack;
  detail::FootprintPolytope::query_box(corners.boxes, from, slack);
  if (candidates != nullptr && l[3] != 0.0) {
    // The tile's list, each entry first through the walk's own box test for this pixel (the
    // light pyramids of a tile's pixels are far narrower than the tile's cone near R).
    silhouette.tree.dilated_segment_query(from, {l[0], l[1], l[2]}, slack, std::span<const std::uint32_t>(*candidates),
                                          visit);
    return varies;
  }
  if (candidates != nullptr) {
    for (std::uint32_t id : *candidates)
      if (!visit(id)) break;
    return varies;
  }
  if (l[3] == 0.0) {
    silhouette.tree.dilated_ray_query(from, {l[0], l[1], l[2]}, slack, visit);
  } else {
    silhouette.tree.dilated_segment_query(from, {l[0], l[1], l[2]}, slack, visit);
  }
  return varies;
}

// The centre ray's depth band around P (ExactImageOptions::depth_band): the segment of the
// ray from P - b to P + b in view depth, b = band(D), as doubles.
struct DepthBand {
  Vec3 near{};
  Vec3 far{};
};

DepthBand depth_band(const ImageGeometry& g, const CameraFrame& frame, const PixelRay& ray, const RayHit& hit,
                     const std::function<double(double)>& band) {
  const std::uint32_t h = hit.triangle;
  const detail::HitPoint p(detail::RayParameter(ray, g.vertex(h, 0), g.vertex(h, 1), g.vertex(h, 2), hit.direction_side));
  Vec3 point;
  for (int k = 0; k < 3; ++k) point[k] = p.lo()[k] / 2 + p.hi()[k] / 2;
  const double per_t = dot(ray.direction, frame.forward);  // view depth per unit of t (> 0)
  const double t = dot({point[0] - ray.origin[0], point[1] - ray.origin[1], point[2] - ray.origin[2]},
                               ray.direction) / dot(ray.direction, ray.direction);
  const double dt = band(t * per_t) / per_t;
  DepthBand b;
  for (int k = 0; k < 3; ++k) {
    b.near[k] = ray.origin[k] + (t - dt) * ray.direction[k];
    b.far[k] = ray.origin[k] + (t + dt) * ray.direction[k];
  }
  return b;
}

// Whether the band meets a triangle other than h (two surfaces a depth buffer cannot order).
bool band_meets_surface(const ImageGeometry& g, const DepthBand& b, std::uint32_t h) {
  if (b.near == b.far) return false;
  bool meets = false;
  g.tree.segment_query(b.near, b.far, [&](std::uint32_t id) {
    if (id == h) return true;
    const detail::FaceMeeting m = detail::segment_meets_triangle(finite_point(b.near), finite_point(b.far),
                                                                 g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2));
    if (m.meeting == detail::Meeting::apart) return true;
    meets = true;
    return false;
  });
  return meets;
}

// Whether the band meets the side face of a casting edge of light number `light`.
bool band_meets_volume(const ImageGeometry& g, std::size_t light, const DepthBand& b) {
  if (b.near == b.far) return false;
  const HomogeneousPoint& l = g.lights[light];
  const Silhouette& edges = *g.casting_edges[light];
  bool meets = false;
  const auto visit = [&](std::uint32_t id) {
    if (detail::segment_meets_side(b.near, b.far, l, edges.edges[id][0], edges.edges[id][1]).meeting ==
        detail::Meeting::apart)
      return true;
    meets = true;
    return false;
  };
  // The side face of edge uv meets the band only if a segment from the light to a band point
  // crosses uv: the edge lies in hull{L, band}, inside the band's segment to L dilated by it.
  Vec3 from, slack;
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min(b.near[k], b.far[k]), hi = std::max(b.near[k], b.far[k]);
    from[k] = std::clamp(lo / 2 + hi / 2, lo, hi);
    slack[k] = std::nextafter(std::max(hi - from[k], from[k] - lo), std::numeric_limits<double>::infinity());
  }
  if (l[3] == 0.0) {
    edges.tree.dilated_ray_query(from, {l[0], l[1], l[2]}, slack, visit);
  } else {
    edges.tree.dilated_segment_query(from, {l[0], l[1], l[2]}, slack, visit);
  }
  return meets;
}

// A rasteriser snaps vertices to a subpixel grid (8 bits: 1/256 px on llvmpipe and NVIDIA): a
// face whose projected edge passes within that of a pixel centre may or may not cover it. Part
// of the diff's GL model (used only with ExactImageOptions::depth_band), as the depth band is.
constexpr double kSubpixelSnap = 1.0 / 256.0;

// Where a plane lies over the snap pyramid around a centre ray, against P's depth band.
enum class PlaneSide { in_front, behind, reaches };

// The points of ray `ray` at view depths `near_depth` and `far_depth` (doubles: they bound
// the band, as depth_band's end points do).
std::array<Vec3, 2> at_depths(const PixelRay& ray, const CameraFrame& frame, double near_depth, double far_depth) {
  const double per_t = dot(ray.direction, frame.forward);
  std::array<Vec3, 2> out{};
  for (int k = 0; k < 3; ++k) {
    out[0][k] = ray.origin[k] + near_depth / per_t * ray.direction[k];
    out[1][k] = ray.origin[k] + far_depth / per_t * ray.direction[k];
  }
  return out;
}

// The side of the plane through p, q, r (homogeneous: a side face's plane holds the light)
// over the snap rays, each given as (eye, band's near point, band's far point): in front when
// every ray crosses it before the band, behind when none crosses it before the band's far end
// (or at all), else it reaches the band. Exact orientations of the given points.
PlaneSide plane_side(const HomogeneousPoint& p, const HomogeneousPoint& q, const HomogeneousPoint& r,
                     const HomogeneousPoint& eye, const std::array<std::array<Vec3, 2>, 5>& band_points) {
  const Sign at_eye = orient(p, q, r, eye);
  if (at_eye == Sign::zero) return PlaneSide::reaches;  // the plane holds the eye: seen edge-on
  bool all_front = true, all_behind = true;
  for (const std::array<Vec3, 2>& b : band_points) {
    const Sign at_near = orient(p, q, r, finite_point(b[0]));
    const Sign at_far = orient(p, q, r, finite_point(b[1]));
    if (at_near != at_eye) all_behind = false;  // crossed before the band (or on its near end)
    if (at_near == at_eye) all_front = false;
    if (at_far != at_eye) all_behind = false;   // crossed before the band's far end
  }
  if (all_front) return PlaneSide::in_front;
  if (all_behind) return PlaneSide::behind;
  return PlaneSide::reaches;
}

// Whether a casting edge passes within kSubpixelSnap of pixel (i, r)'s centre (exactly: the edge
// meets the pyramid from the eye over four rays kSubpixelSnap around the centre) where its
// triangle's cap and its side face for `light` could count on opposite sides of P: either plane
// reaches P's depth band over the pyramid, or one lies in front and the other behind. Such a
// fold pair (the two faces meet on the edge) cancels when GL's rounding puts both over the
// centre on one side of P, and moves the count by one otherwise: docs/campaign.md, the 1920x1080
// reproducers of tests/regressions/gl_fold/. `band` is the centre's (depth_band), `hit` P's.
// The pixels whose centre a casting edge's projection passes within twice kSubpixelSnap of
// (doubles, a filter: fold_pair_at_centre decides exactly): one byte per pixel, 1 where it may.
// Light-independent: only the camera and the casting edges, each clipped to the eye's half-space
// and marched along its projection's major axis within the image, so the cost is its length in
// pixels. A projection that is not finite marks every pixel.
std::vector<std::uint8_t> fold_candidates(const ImageGeometry& g, const CameraFrame& frame) {
  const std::uint32_t w = frame.width, h = frame.height;
  std::vector<std::uint8_t> mask(std::size_t{w} * h, 0);
  const double reach = 2.0 * kSubpixelSnap;
  const auto pixel_of = [&](const Vec3& x, std::array<double, 2>& out) {
    const Vec3 d = difference(x, frame.eye);
    const double z = dot(d, frame.forward);
    if (!(z > 1e-300)) return false;
    out = {(dot(d, frame.right) / (z * frame.half_width) + 1.0) * w / 2.0,
           (1.0 - dot(d, frame.up) / (z * frame.half_height)) * h / 2.0};
    return std::isfinite(out[0]) && std::isfinite(out[1]);
  };
  // Marks (column, row) when its centre lies within `reach` of segment ab.
  const auto mark_near = [&](const std::array<double, 2>& a, const std::array<double, 2>& b, std::int64_t col,
                             std::int64_t row) {
    if (col < 0 || row < 0 || col >= static_cast<std::int64_t>(w) || row >= static_cast<std::int64_t>(h)) return;
    const double cx = static_cast<double>(col) + 0.5, cy = static_cast<double>(row) + 0.5;
    const double ex = b[0] - a[0], ey = b[1] - a[1], px = cx - a[0], py = cy - a[1];
    const double l2 = ex * ex + ey * ey;
    const double f = l2 > 0.0 ? std::clamp((px * ex + py * ey) / l2, 0.0, 1.0) : 0.0;
    const double dx = px - f * ex, dy = py - f * ey;
    if (!(std::sqrt(dx * dx + dy * dy) > reach)) mask[static_cast<std::size_t>(row) * w + static_cast<std::size_t>(col)] = 1;
  };
  const auto mark_segment = [&](Vec3 u, Vec3 v) {
    // Clipped to the part in front of the eye plane (the part behind meets no pixel's pyramid;
    // the part in front of the clip projects beyond the clipped end, off the image).
    const double zu = dot(difference(u, frame.eye), frame.forward), zv = dot(difference(v, frame.eye), frame.forward);
    const double clip = 1e-9 * std::max(std::abs(zu), std::abs(zv));
    if (!(zu > clip) && !(zv > clip)) return true;
    if (!(zu > clip) || !(zv > clip)) {
      Vec3& behind = zu > clip ? v : u;
      const double f = ((zu > clip ? zu : zv) - clip) / std::abs(zu - zv);
      const Vec3& ahead = zu > clip ? u : v;
      for (int k = 0; k < 3; ++k) behind[k] = ahead[k] + f * (behind[k] - ahead[k]);
    }
    std::array<double, 2> a{}, b{};
    if (!pixel_of(u, a) || !pixel_of(v, b)) {
      std::fill(mask.begin(), mask.end(), std::uint8_t{1});  // cannot tell: every pixel goes to the exact test
      return false;
    }
    const bool by_column = std::abs(b[0] - a[0]) >= std::abs(b[1] - a[1]);
    const int major = by_column ? 0 : 1, minor = 1 - major;
    const std::array<double, 2>& lo = a[major] <= b[major] ? a : b;
    const std::array<double, 2>& hi = a[major] <= b[major] ? b : a;
    const double limit = by_column ? w : h;
    const double first = std::max(std::floor(lo[major] - reach - 0.5), -1.0);
    const double last = std::min(std::ceil(hi[major] + reach - 0.5), limit);
    const double slope = hi[major] > lo[major] ? (hi[minor] - lo[minor]) / (hi[major] - lo[major]) : 0.0;
    for (double k = first; k <= last; k += 1.0) {
      const double centre = k + 0.5;
      const double along = std::clamp(centre, lo[major], hi[major]);
      const double m = lo[minor] + slope * (along - lo[major]);  // the segment's minor coordinate there
      const double centre_row = std::floor(m - 0.5);
      for (double j = centre_row - 1.0; j <= centre_row + 2.0; j += 1.0) {
        const auto kk = static_cast<std::int64_t>(k), jj = static_cast<std::int64_t>(j);
        if (by_column) mark_near(a, b, kk, jj);
        else mark_near(a, b, jj, kk);
      }
    }
    return true;
  };
  for (std::uint32_t t = 0; t < g.soup.triangles.size(); ++t) {
    if (!g.casting(t)) continue;
    for (int e = 0; e < 3; ++e)
      if (!mark_segment(g.vertex(t, e), g.vertex(t, (e + 1) % 3))) return mask;
  }
  return mask;
}

bool fold_pair_at_centre(const ImageGeometry& g, std::size_t light, const CameraFrame& frame, const Backdrop& backdrop,
                         std::uint32_t i, std::uint32_t r, const RayHit& hit, const DepthBand& band) {
  const double cx = i + 0.5, cy = r + 0.5, s = kSubpixelSnap;
  const std::array<std::array<double, 2>, 4> offsets{{{-s, -s}, {s, -s}, {s, s}, {-s, s}}};  // cyclic
  std::array<PixelRay, 5> rays{};
  rays[4] = pixel_ray(frame, cx, cy);
  for (std::size_t k = 0; k < 4; ++k) rays[k] = pixel_ray(frame, cx + offsets[k][0], cy + offsets[k][1]);
  // The query box: the segment from the eye to the centre ray's point on the backdrop plane,
  // dilated by the snap rays' offsets there (grown by 1%: the doubles are a filter's, the
  // pyramid below is exact), holds the pyramid.
  const double backdrop_depth = dot(difference(backdrop.triangle[0], frame.eye), frame.forward);
  const auto on_backdrop = [&](const PixelRay& ray) {
    const double t = backdrop_depth / dot(ray.direction, frame.forward);
    return Vec3{ray.origin[0] + t * ray.direction[0], ray.origin[1] + t * ray.direction[1],
                ray.origin[2] + t * ray.direction[2]};
  };
  const Vec3 from = on_backdrop(rays[4]);
  Vec3 slack{};
  for (std::size_t k = 0; k < 4; ++k) {
    const Vec3 c = on_backdrop(rays[k]);
    for (int a = 0; a < 3; ++a) slack[a] = std::max(slack[a], std::abs(c[a] - from[a]));
  }
  for (int a = 0; a < 3; ++a) slack[a] = slack[a] * 1.01 + 1e-9 * (std::abs(from[a]) + 1.0);
  // A filter in doubles: an edge whose projection lies farther than twice the snap from the
  // centre (the pyramid's half-diagonal is sqrt(2) snaps; double rounding is ~1e-10 px) cannot
  // meet the pyramid. An edge with an end at or behind the eye plane goes to the exact test.
  const auto pixel_of = [&](const Vec3& x, std::array<double, 2>& out) {
    const Vec3 d = difference(x, frame.eye);
    const double z = dot(d, frame.forward);
    if (!(z > 1e-300)) return false;
    out = {(dot(d, frame.right) / (z * frame.half_width) + 1.0) * frame.width / 2.0,
           (1.0 - dot(d, frame.up) / (z * frame.half_height)) * frame.height / 2.0};
    return true;
  };
  const auto may_meet = [&](const Vec3& u, const Vec3& v) {
    std::array<double, 2> a{}, b{};
    if (!pixel_of(u, a) || !pixel_of(v, b)) return true;
    const double ex = b[0] - a[0], ey = b[1] - a[1], px = cx - a[0], py = cy - a[1];
    const double l2 = ex * ex + ey * ey;
    const double f = l2 > 0.0 ? std::clamp((px * ex + py * ey) / l2, 0.0, 1.0) : 0.0;
    const double dx = px - f * ex, dy = py - f * ey;
    return !(std::sqrt(dx * dx + dy * dy) > 2.0 * s);  // NaN goes to the exact test
  };

  // What the exact tests need, made once the filter lets an edge through.
  std::optional<detail::FootprintPolytope> pyramid;
  std::array<std::array<Vec3, 2>, 5> band_points{};
  bool undecided = false;
  const auto prepare = [&] {
    std::array<detail::RayMeeting, 4> meetings{};
    for (std::size_t k = 0; k < 4; ++k) {
      meetings[k] = detail::ray_meets_triangle(rays[k], backdrop.triangle[0], backdrop.triangle[1], backdrop.triangle[2]);
      if (meetings[k].direction_side == Sign::zero || meetings[k].eye_side != -meetings[k].direction_side) {
        undecided = true;  // a snap ray misses the backdrop plane (not seen for a finite scene)
        return;
      }
    }
    const auto at = [&](std::size_t k) {
      return detail::RayParameter(rays[k], backdrop.triangle[0], backdrop.triangle[1], backdrop.triangle[2],
                                  meetings[k].direction_side);
    };
    pyramid.emplace(finite_point(frame.eye), std::array<detail::RayParameter, 4>{at(0), at(1), at(2), at(3)});
    // P's band in view depth (depth_band's end points measured along the forward axis).
    const auto view_depth = [&](const Vec3& x) { return dot(difference(x, frame.eye), frame.forward); };
    const double near_depth = view_depth(band.near), far_depth = view_depth(band.far);
    for (std::size_t k = 0; k < 5; ++k) band_points[k] = at_depths(rays[k], frame, near_depth, far_depth);
  };
  const HomogeneousPoint eye = finite_point(frame.eye);
  const HomogeneousPoint& l = g.lights[light];
  bool fold = false;
  g.tree.dilated_segment_query(from, frame.eye, slack, [&](std::uint32_t id) {
    if (id == hit.triangle || !g.casting(id)) return true;
    const std::array<Vec3, 3> t{g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2)};
    if (!may_meet(t[0], t[1]) && !may_meet(t[1], t[2]) && !may_meet(t[2], t[0])) return true;
    if (!pyramid && !undecided) prepare();
    if (undecided) {
      fold = true;  // undecided: ambiguous
      return false;
    }
    if (!pyramid->meets_an_edge_of(t[0], t[1], t[2])) return true;
    const PlaneSide cap = plane_side(finite_point(t[0]), finite_point(t[1]), finite_point(t[2]), eye, band_points);
    for (int e = 0; e < 3 && !fold; ++e) {
      const Vec3& u = t[static_cast<std::size_t>(e)];
      const Vec3& v = t[static_cast<std::size_t>((e + 1) % 3)];
      if (!may_meet(u, v) || !pyramid->meets(u, v)) continue;
      const PlaneSide side = plane_side(finite_point(u), finite_point(v), l, eye, band_points);
      fold = cap == PlaneSide::reaches || side == PlaneSide::reaches || cap != side;
    }
    return !fold;
  });
  return fold;
}

}  // namespace

ExactImage exact_image(const Soup& soup, std::span<const Light> lights, const Camera& camera,
                       const ExactImageOptions& options) {
  const auto start = Clock::now();
  validate(soup, lights, options);
  const RayGrid grid{camera_frame(camera, "exact_image"), camera.width, camera.height};
  // The imaged pixels: options.window, or all of them.
  const PixelWindow window = options.window.value_or(PixelWindow{0, 0, grid.width, grid.height});
  if (window.width == 0 || window.height == 0 || window.x > grid.width - window.width ||
      window.y > grid.height - window.height)
    throw std::invalid_argument("exact_image: the window is empty or not inside the image");
  const auto in_window = [&window](std::uint32_t i, std::uint32_t row) {
    return i - window.x < window.width && row - window.y < window.height;  // unsigned: below x wraps
  };

  // Every triangle is seen (the box tree); the volumes are the casting triangles' alone. The
  // silhouettes and volume faces serve only the footprint tests (options.footprints). The tree
  // and the lights' data are independent: built side by side.
  const bool footprints = options.footprints;
  std::unique_ptr<detail::BoxTree> tree;
  std::vector<HomogeneousPoint> light_points;
  std::vector<std::vector<Sign>> sides_of_lights;
  std::vector<std::unique_ptr<Silhouette>> silhouettes, edges_of_casters;
  // The box of every vertex: where the tiles' cones end, what each hit-point box is cut to, and
  // what the light grids project.
  const Box scene = soup.vertices.empty() ? Box{} : bounding_box(soup.vertices);
  // Per light, its grid of count lists (reference/detail/light_grid.h) where one pays: a point
  // light with the scene strictly on one side of it, counted light by light (not the beam), and
  // at least kGridRaysPerTriangle traced rays (all that may be counted) per casting triangle.
  std::vector<std::optional<detail::LightGrid>> light_grids(lights.size());
  const std::size_t traced_rays = std::size_t{window.width} * window.height +
                                  (footprints ? std::size_t{window.width + 1} * (window.height + 1) : 0);
  tbb::parallel_invoke(
      [&] { tree = std::make_unique<detail::BoxTree>(triangle_boxes(soup), detail::LeafTest::exact); },
      [&] {
        const CanonicalSoup canonical =
            canonical_soup(!footprints ? Soup{} : options.casts.empty() ? soup : casting_soup(soup, options.casts));
        const EdgeTable table = build_edge_table(canonical.soup);
        // Several point lights: every triangle's sides of all of them at once.
        const bool point_lights =
            lights.size() >= kBeamMinLights &&
            std::all_of(lights.begin(), lights.end(), [](const Light& l) { return l.position[3] != 0.0; });
        if (point_lights) sides_of_lights = point_light_sides(soup, lights);
        for (std::size_t k = 0; k < lights.size(); ++k) {
          const Light& light = lights[k];
          light_points.push_back(light.position);
          if (!point_lights) sides_of_lights.push_back(light_sides(soup, light));
          if (light.position[3] != 0.0 && !(point_lights && !footprints)) {
            std::vector<std::uint8_t> listed(soup.triangles.size());
            std::size_t listed_count = 0;
            for (std::uint32_t id = 0; id < listed.size(); ++id) {  // what light_tile_candidates keeps
              listed[id] = countable_caster(options.casts, sides_of_lights[k], id) ? 1 : 0;
              listed_count += listed[id];
            }
            if (listed_count * kGridRaysPerTriangle <= traced_rays)
              light_grids[k] = detail::LightGrid::build(soup, {light.position[0], light.position[1], light.position[2]},
                                                        scene, listed);
          }
          if (!footprints) continue;
          silhouettes.push_back(silhouette(canonical.soup, table, light));
          if (options.depth_band)
            edges_of_casters.push_back(
                casting_edges(canonical.soup, table, casting_sides(sides_of_lights[k], options.casts)));
        }
      });
  const ImageGeometry g{soup,
                        options.casts,
                        std::move(light_points),
                        std::move(sides_of_lights),
                        std::move(silhouettes),
                        std::move(edges_of_casters),
                        *tree};
  ExactImage image;
  image.width = grid.width;
  image.height = grid.height;
  image.stats.tree_seconds = seconds_since(start);

  // 1. First hits of every ray, row by row (rays of a row are coherent: good for the tree).
  auto stage = Clock::now();
  // The large per-ray arrays on huge pages (core/huge_page_advice.h): at 1024x768 they are about
  // 100 MB, whose 4 KiB first-touch faults cost this virtual machine about 0.1 s of CPU. Not
  // filled before the rays are traced where every ray is (the whole image, with its corners):
  // a fill first would touch all of it on one thread (12.6 MB, 3 to 15 ms on ogre at 1024x768),
  // where the tiles' threads touch it as they write. Otherwise the untraced rays read as no hit.
  RayHits hits(grid.size());
  if (window.width != grid.width || window.height != grid.height || !footprints)
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, hits.size()), [&](const auto& r) {
      std::fill(hits.data() + r.begin(), hits.data() + r.end(), RayHit{});
    });
  // Every countable hit's point box, once, as its ray is traced (the centres' for their counts;
  // the corners' for theirs and for the pyramids of the four pixels around each).
  // Not initialised (zeroing each ray's box costs more than the boxes): only the countable
  // hits' entries are written, and only those are read.
  detail::HitPointBoxes point_boxes(grid.size(), scene);
  const auto trace = [&](std::size_t k, const PixelRay& ray, const std::vector<std::uint32_t>* list,
                         std::span<const std::uint32_t> scan, const std::vector<CandidateRaySigns>& signs,
                         double length, TileScratch& local) {
    // The candidates the filters show apart (the plane behind the eye, or the crossing strictly
    // outside an edge line: ray_meets_triangle's own verdicts) are skipped.
    // With the eye off the plane (side s = +-1), the candidate is apart where the direction's
    // sign is certain and either it is s (the plane behind the eye) or some edge's is s (X
    // outside that edge line). s v > B is "certainly s" for either s; the filters never certify
    // a zero. Evaluated without a branch per sign (they vary from ray to ray).
    const auto known = [&](std::size_t c, detail::KnownRaySigns& s, ParameterEstimates& estimates) {
      const CandidateRaySigns& f = signs[c];
      const Vec3& d = ray.direction;
      const double v0 = f.along(0, d), v1 = f.along(1, d), v2 = f.along(2, d), v3 = f.along(3, d);
      const bool direction_known = (v0 > f.planes[0].bound) | (v0 < -f.planes[0].bound);
      const bool some_side_s = (f.side * v0 > f.planes[0].bound) | (f.side * v1 > f.planes[1].bound) |
                               (f.side * v2 > f.planes[2].bound) | (f.side * v3 > f.planes[3].bound);
      if (f.side != 0.0 && direction_known && some_side_s) return false;
      s.eye_side = f.eye_side;
      s.direction_side = f.sign_of(0, v0);
      s.edges = {f.sign_of(1, v1), f.sign_of(2, v2), f.sign_of(3, v3)};
      estimates = {f.numerator, {v0, f.planes[0].bound}};
      return true;
    };
    std::optional<detail::RayParameter>& best = local.best;
    const RayHit hit = first_hit(g, ray, local.in_plane, list, scan, local.near.data(), length, known, best);
    hits[k] = hit;  // (not read back from hits[k]: its two narrow stores would stall an 8-byte load)
    if (!countable(hit)) return;
    // A countable hit's nearest meeting is its triangle's: its semi-static stage gives the box.
    if (PointBox box; best->semi_static_hit_box(box)) {
      point_boxes.set(k, box);
      return;
    }
    const detail::HitPoint p(*best);
    point_boxes.set(k, {p.lo(), p.hi()});
  };
  // Tile by tile: the tile's list (TileCandidates), then its centre rays and (for the
  // footprints) the corner rays it owns.
  const TileGrid tiles(window);
  std::vector<TileCandidates> tile_lists(tiles.count());
  tbb::enumerable_thread_specific<TileScratch> tile_scratch;
  {
    const std::size_t centre_rays = std::size_t{window.width} * window.height;
    const std::size_t corner_rays = footprints ? std::size_t{window.width + 1} * (window.height + 1) : 0;
    Progress progress(options, "hits", centre_rays + corner_rays);
    // The rays of one block of pixels (a tile, or a quarter of one) with `candidates` its list
    // (or none: each walks the tree): its centres, then the corners it owns.
    const auto trace_block = [&](const TileGrid::Bounds& b, TileCandidates& candidates, TileScratch& local) {
      if (candidates.listed) order_by_distance(g, grid.frame.eye, candidates.ids, local.near);
      const std::vector<std::uint32_t>* list = candidates.list();
      const bool scanned = list != nullptr && !list->empty();
      const Vec3 W = scanned ? detail::eye_tile_direction_bound(grid.frame, b.x0, b.x1, b.y0, b.y1) : Vec3{};
      const std::vector<CandidateRaySigns> signs =
          scanned ? candidate_ray_signs(g, *list, grid.frame.eye, W) : std::vector<CandidateRaySigns>{};
      const double length = direction_length_bound(W);
      const RayBlocks blocks(grid.frame, b, signs, local);
      for (std::uint32_t y = b.y0; y < b.y1; ++y)
        for (std::uint32_t x = b.x0; x < b.x1; ++x)
          trace(std::size_t{y} * grid.width + x, grid.centre_ray(x, y), list, blocks.scan(x, y), signs, length, local);
      std::size_t done = std::size_t{b.x1 - b.x0} * (b.y1 - b.y0);
      if (footprints) {
        for (std::uint32_t y = b.y0; y < b.cy1; ++y)
          for (std::uint32_t x = b.x0; x < b.cx1; ++x)
            trace(grid.corner(x, y), grid.corner_ray(x, y), list, blocks.scan(x, y), signs, length, local);
        done += std::size_t{b.cx1 - b.x0} * (b.cy1 - b.y0);
      }
      return done;
    };
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, tiles.count(), 1), [&](const auto& r) {
      TileScratch& local = tile_scratch.local();
      for (std::uint32_t t = r.begin(); t != r.end(); ++t) {
        const TileGrid::Bounds b = tiles.bounds(t);
        const std::optional<detail::EyeTileCone> cone =
            detail::eye_tile_cone(grid.frame, b.x0, b.x1, b.y0, b.y1, scene.lo, scene.hi);
        tile_lists[t] = tile_candidates(g, cone, local);
        if (tile_lists[t].listed || !cone) {
          progress.advance(trace_block(b, tile_lists[t], local));
          continue;
        }
        // The tile's cone holds too many triangles (a dense patch, a grazing view): each quarter
        // of it lists its own narrower cone where that holds few enough, so that its rays scan
        // a list rather than each walk the tree (a walk costs several listed rays: ogre at
        // 1024x768, 56K walking rays took about a quarter of the stage). A quarter owns the
        // corners of the tile's it covers, those of its last column and row only where the
        // tile's are (TileGrid::Bounds). Its list serves its rays alone (the footprints keep
        // the tile's: none).
        const std::uint32_t xm = TileGrid::middle(b.x0, b.x1), ym = TileGrid::middle(b.y0, b.y1);
        std::size_t done = 0;
        for (const auto& [qx0, qx1] : {std::pair{b.x0, xm}, std::pair{xm, b.x1}})
          for (const auto& [qy0, qy1] : {std::pair{b.y0, ym}, std::pair{ym, b.y1}}) {
            if (qx0 == qx1 || qy0 == qy1) continue;
            const TileGrid::Bounds q{qx0, qx1, qy0, qy1, qx1 == b.x1 ? b.cx1 : qx1, qy1 == b.y1 ? b.cy1 : qy1};
            TileCandidates quarter =
                tile_candidates(g, detail::eye_tile_cone(grid.frame, q.x0, q.x1, q.y0, q.y1, scene.lo, scene.hi), local);
            done += trace_block(q, quarter, local);
          }
        progress.advance(done);
      }
    });
    image.stats.rays = centre_rays + corner_rays;
  }
  image.stats.hit_seconds = seconds_since(stage);

  // 2. and 3., light by light.
  stage = Clock::now();
  // Per pixel its hit triangle and its light-independent ambiguity (`geometric`, the image's
  // view_ambiguity), from its rays' hits; with the footprints, the footprint pass below sets
  // them as it reaches each pixel (one pass over the hits, not two).
  resize_huge(image.hit_triangles, grid.centres());
  resize_huge(image.view_ambiguity, grid.centres());
  std::vector<std::uint8_t>& geometric = image.view_ambiguity;
  const auto classify = [&](std::uint32_t i, std::uint32_t row) {
    const std::size_t pixel = std::size_t{row} * grid.width + i;
    image.hit_triangles[pixel] = hits[pixel].triangle;
    // Outside the window no ray was traced (no hit: nothing below looks further).
    geometric[pixel] = !in_window(i, row) ? static_cast<std::uint8_t>(kOutsideWindow)
                       : footprints       ? footprint_ambiguity(hits, grid.footprint(i, row))
                                          : static_cast<std::uint8_t>(hits[pixel].degenerate ? kZeroSign : 0);
  };
  if (!footprints) {
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, grid.height), [&](const auto& r) {
      for (std::uint32_t row = r.begin(); row != r.end(); ++row)
        for (std::uint32_t i = 0; i < grid.width; ++i) classify(i, row);
    });
  }
  image.stats.count_seconds = seconds_since(stage);

  // Where the corners and the centre agree on one triangle, the whole footprint must see only
  // it (reference/detail/pixel_footprint.h): a small triangle or an edge between the rays is ambiguous.
  // Where they agree on no triangle, the eye pyramid runs to the backdrop plane beyond the scene.
  stage = Clock::now();
  const std::optional<Backdrop> backdrop = Backdrop::behind(g.soup, grid.frame);
  if (footprints) {
    Progress progress(options, "footprints", grid.height);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, grid.height), [&](const auto& r) {
      std::uint32_t cached_tile = kNoHit, cached_h = kNoHit;
      bool cached_alone = false;
      for (std::uint32_t row = r.begin(); row != r.end(); ++row) {
        for (std::uint32_t i = 0; i < grid.width; ++i) {
          const std::size_t pixel = std::size_t{row} * grid.width + i;
          classify(i, row);
          if (geometric[pixel] == 0 && hits[pixel].triangle == kNoHit) {
            // All five rays miss (footprint_ambiguity found them alike): a triangle may still
            // poke into the footprint between them, a vertex or an edge within a rounding of
            // GL's sample at the centre (fuzz --gl seed 202 case 1706: 0.001 px).
            // The tile's list first: most such tiles list no triangle at all.
            const std::vector<std::uint32_t>* list = footprint_list(tile_lists[tiles.of(i, row)]);
            if (backdrop && list != nullptr && list->empty()) continue;
            if (!backdrop ||
                footprint_sees_more(g, grid.frame.eye, with_boxes(backdrop->corners(grid, i, row)), kNoHit, nullptr, list))
              geometric[pixel] |= kFootprintTriangles;
            continue;
          }
          if (geometric[pixel] != 0 || !countable(hits[pixel])) continue;
          const std::uint32_t h = hits[pixel].triangle;
          const std::uint32_t tile = tiles.of(i, row);
          const std::vector<std::uint32_t>* list = footprint_list(tile_lists[tile]);
          // A tile whose list holds, besides h, only triangles beside h in its plane: no pixel
          // of it that sees h alone at its five rays sees anything else (footprint_sees_more
          // passes each of them by with EyePyramidFilter::beside_in_plane, a test of h and the
          // eye alone); its answer is known without the corners. Cached for the last tile and h.
          if (list != nullptr && !(tile == cached_tile && h == cached_h)) {
            cached_tile = tile;
            cached_h = h;
            const HitPlaneNeighbours neighbours(grid.frame.eye, {g.vertex(h, 0), g.vertex(h, 1), g.vertex(h, 2)});
            cached_alone = std::all_of(list->begin(), list->end(), [&](std::uint32_t id) {
              return id == h || neighbours.beside_in_plane(g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2));
            });
          }
          const bool sees_more = [&] {
            if (list != nullptr && cached_alone) return false;
            const CornerHits corners = corner_hits(g, grid, hits, point_boxes, i, row);
            const EyePyramidFilter filter(grid.frame.eye, corners, {g.vertex(h, 0), g.vertex(h, 1), g.vertex(h, 2)},
                                          hits[pixel].eye_side);
            return footprint_sees_more(g, grid.frame.eye, corners, h, &filter, list);
          }();
          if (sees_more)
            geometric[pixel] |= kFootprintTriangles;
          else if (options.depth_band &&
                   band_meets_surface(g, depth_band(g, grid.frame, grid.ray(pixel), hits[pixel], options.depth_band),
                                      hits[pixel].triangle))
            geometric[pixel] |= kDepthBand;
        }
        progress.advance(1);
      }
    });
  }
  image.stats.footprint_seconds = seconds_since(stage);
  stage = Clock::now();
  // Per ray its count for the light at hand and whether that count is needed. Neither is
  // filled first (a fill would touch them on one thread): every entry of `needed` is written
  // for each light, and a count is read only where it was needed, and so written.
  HugePageBuffer<std::uint32_t> counts;
  HugePageBuffer<std::uint8_t> needed;
  // With the depth band: the pixels a casting edge passes near (fold_pair_at_centre's filter).
  const std::vector<std::uint8_t> fold_mask =
      footprints && options.depth_band && backdrop ? fold_candidates(g, grid.frame) : std::vector<std::uint8_t>{};
  // Several point lights and no footprints (the soft reference): every light's centre counts in
  // one pass (beam_counts), one count array per light.
  const bool beam = !footprints && lights.size() >= kBeamMinLights &&
                    std::all_of(g.lights.begin(), g.lights.end(), [](const HomogeneousPoint& l) { return l[3] != 0.0; });
  if (!beam) {  // the per-light counts' arrays, over every ray
    counts = HugePageBuffer<std::uint32_t>(grid.size());
    needed = HugePageBuffer<std::uint8_t>(grid.size());
  }
  // Without light images, the lights' sums per pixel (ExactLightTally).
  const bool tally = !options.light_images;
  if (tally) {
    image.tally.defined.assign(grid.centres(), 0);
    image.tally.lit.assign(grid.centres(), 0);
    image.tally.terminator.assign(grid.centres(), 0);
  }
  // One count array per light, each the light's out.counts in the end (no copy); none for a tally.
  std::vector<std::vector<std::uint32_t>> beam_counts_of(beam && !tally ? lights.size() : 0);
  if (beam) {
    const BeamLights beam_lights(g);
    for (auto& counts_of_light : beam_counts_of) resize_huge(counts_of_light, grid.centres());
    // Tiles of centres with a countable hit (beam_counts_tile), in row-major order.
    const std::uint32_t tile_columns = (grid.width + kBeamTileWidth - 1) / kBeamTileWidth,
                        tile_rows = (grid.height + kBeamTileHeight - 1) / kBeamTileHeight;
    const auto tile_pixels = [&](std::uint32_t tile, std::array<std::size_t, kBeamTile>& pixels) {
      const std::uint32_t x = kBeamTileWidth * (tile % tile_columns), y = kBeamTileHeight * (tile / tile_columns);
      std::size_t count = 0;
      for (std::uint32_t dy = 0; dy < kBeamTileHeight; ++dy)
        for (std::uint32_t dx = 0; dx < kBeamTileWidth; ++dx) {
          const std::size_t pixel = std::size_t{y + dy} * grid.width + x + dx;
          if (x + dx < grid.width && y + dy < grid.height && countable(hits[pixel])) pixels[count++] = pixel;
        }
      return count;
    };
    std::vector<std::uint32_t> beam_tiles;
    std::size_t work = 0;
    for (std::uint32_t tile = 0; tile < tile_columns * tile_rows; ++tile) {
      std::array<std::size_t, kBeamTile> pixels{};
      const std::size_t count = tile_pixels(tile, pixels);
      if (count > 0) beam_tiles.push_back(tile);
      work += count;
    }
    Progress progress(options, kAllLightsCounts, work * lights.size());
    tbb::enumerable_thread_specific<BeamScratch> scratch;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, beam_tiles.size(), 16), [&](const auto& r) {
      BeamScratch& local = scratch.local();
      std::size_t done = 0;
      for (std::size_t t = r.begin(); t != r.end(); ++t) {
        std::array<std::size_t, kBeamTile> pixels{};
        const std::size_t count = tile_pixels(beam_tiles[t], pixels);
        std::array<BeamPixel, kBeamTile> beam_pixels;
        for (std::size_t k = 0; k < count; ++k)
          beam_pixels[k] = {grid.ray(pixels[k]), hits[pixels[k]], point_boxes[pixels[k]]};
        beam_counts_tile(g, beam_lights, {beam_pixels.data(), count}, local);
        done += count;
        for (std::size_t k = 0; k < count; ++k) {
          const std::size_t pixel = pixels[k];
          const std::uint32_t* result = &local.result[k * lights.size()];
          if (!tally) {
            for (std::size_t slot = 0; slot < lights.size(); ++slot)
              beam_counts_of[beam_lights.order[slot]][pixel] = result[slot];
            continue;
          }
          // The per-light loop's verdicts, summed: a countable centre is defined unless its count
          // is undefined, lit at 0, and a terminator where the light is not on the eye's side.
          const RayHit& hit = hits[pixel];
          const Sign* hit_sides = beam_lights.sides.data() + std::size_t{hit.triangle} * lights.size();
          std::uint32_t defined = 0, lit = 0;
          bool behind = false;
          for (std::size_t slot = 0; slot < lights.size(); ++slot) {
            defined += result[slot] != kUndefinedCount ? 1 : 0;
            lit += result[slot] == 0 ? 1 : 0;
            behind = behind || hit_sides[slot] != hit.eye_side;  // terminator()
          }
          image.tally.defined[pixel] = defined;
          image.tally.lit[pixel] = lit;
          image.tally.terminator[pixel] = behind ? 1 : 0;
        }
      }
      progress.advance(done * lights.size());
    });
    image.stats.counts += work * lights.size();
  }
  // With a tally the beam has summed every light (no light image to make).
  for (std::size_t light = 0; light < (beam && tally ? 0 : lights.size()); ++light) {
    // The centres' counts of the beam (every light counted above, centres only: no footprints).
    const std::uint32_t* light_counts = beam ? beam_counts_of[light].data() : counts.data();
    if (!beam) {
      // Which rays' counts matter: every countable centre (the count image), and the corners of
      // pixels whose footprint sees one triangle that the light does not graze.
      // The centres first (kNeededCorners: a clean pixel's, whose corners are needed too), then
      // each corner from the four pixels around it: each entry written by one thread.
      constexpr std::uint8_t kNeededCorners = 2;
      tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, grid.height), [&](const auto& r) {
        for (std::uint32_t row = r.begin(); row != r.end(); ++row)
          for (std::uint32_t i = 0; i < grid.width; ++i) {
            const std::size_t k = std::size_t{row} * grid.width + i;
            const RayHit& centre = hits[k];
            needed[k] = !countable(centre) ? 0
                        : footprints && geometric[k] == 0 && !terminator(g, light, centre) ? kNeededCorners
                                                                                            : 1;
          }
      });
      tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, grid.height + 1), [&](const auto& r) {
        for (std::uint32_t y = r.begin(); y != r.end(); ++y)
          for (std::uint32_t x = 0; x <= grid.width; ++x) {
            bool any = false;
            for (std::uint32_t row = y == 0 ? 0 : y - 1; footprints && row <= std::min(y, grid.height - 1); ++row)
              for (std::uint32_t i = x == 0 ? 0 : x - 1; i <= std::min(x, grid.width - 1); ++i)
                any = any || needed[std::size_t{row} * grid.width + i] == kNeededCorners;
            needed[grid.corner(x, y)] = any ? 1 : 0;
          }
      });
      // The count lists of a light with a grid come from it, not from walks of the tree.
      const std::optional<detail::LightGrid>& light_grid = light_grids[light];
      // Tile by tile (the hits' tiles): the box of the needed rays' hit points and the light
      // give one list (light_tile_candidates) that each of them counts; with a grid, each reads
      // its own cells' lists and the tile shares their filters.
      std::atomic<std::uint64_t> work{0};
      Progress progress(options, "counts", tiles.count());
      tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, tiles.count(), 1), [&](const auto& r) {
        TileScratch& local = tile_scratch.local();
        std::vector<std::size_t> rays;
        std::vector<std::uint32_t> rest;
        for (std::uint32_t t = r.begin(); t != r.end(); ++t) {
          const TileGrid::Bounds b = tiles.bounds(t);
          rays.clear();
          for (std::uint32_t y = b.y0; y < b.y1; ++y)
            for (std::uint32_t x = b.x0; x < b.x1; ++x)
              if (const std::size_t k = std::size_t{y} * grid.width + x; needed[k] != 0) rays.push_back(k);
          for (std::uint32_t y = b.y0; y < b.cy1; ++y)
            for (std::uint32_t x = b.x0; x < b.cx1; ++x)
              if (const std::size_t k = grid.corner(x, y); needed[k] != 0) rays.push_back(k);
          if (rays.empty()) continue;
          // One group of rays per tile, halved where too many triangles (or, with a grid, cells)
          // lie between its hit points and the light.
          const auto count_group = [&](const auto& self, std::span<std::size_t> group) -> void {
            const PointBox front = point_boxes[group.front()];
            Vec3 lo = front[0], hi = front[1];
            for (std::size_t k : group) {
              const PointBox box = point_boxes[k];
              for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], box[0][a]);
                hi[a] = std::max(hi[a], box[1][a]);
              }
            }
            // The halves of the group across its box's longest axis, each counted on its own.
            const auto halve = [&] {
              int axis = 0;
              for (int a = 1; a < 3; ++a)
                if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
              const double cut = lo[axis] / 2 + hi[axis] / 2;
              auto middle = std::partition(group.begin(), group.end(), [&](std::size_t k) {
                const PointBox box = point_boxes[k];
                return box[0][axis] / 2 + box[1][axis] / 2 < cut;
              });
              if (middle == group.begin() || middle == group.end()) middle = group.begin() + static_cast<std::ptrdiff_t>(group.size() / 2);
              const auto split = static_cast<std::size_t>(middle - group.begin());
              self(self, group.first(split));
              self(self, group.subspan(split));
            };
            // The box middles x and the radius R around them that count_at's boxes give, and the
            // box of the middles: what the filters of the group's candidates are drawn for.
            const auto middles = [&](Vec3& mlo, Vec3& mhi, Vec3& R) {
              mlo = mhi = R = Vec3{};
              if (local.middles.size() < group.size()) local.middles.resize(group.size());
              for (std::size_t i = 0; i < group.size(); ++i) {
                const PointBox box = point_boxes[group[i]];
                Vec3& x = local.middles[i];
                for (int a = 0; a < 3; ++a) {
                  x[a] = std::clamp(box[0][a] / 2 + box[1][a] / 2, box[0][a], box[1][a]);
                  R[a] = std::max({R[a], box[1][a] - x[a], x[a] - box[0][a]});
                  mlo[a] = i == 0 ? x[a] : std::min(mlo[a], x[a]);
                  mhi[a] = i == 0 ? x[a] : std::max(mhi[a], x[a]);
                }
              }
              for (double& radius : R) radius *= 1.0 + 0x1p-50;
            };
            const auto count_filtered = [&](std::size_t i, auto&& candidates) {
              const std::size_t k = group[i];
              const std::uint32_t h = hits[k].triangle;
              if (h != local.side_of) {
                local.side_of = h;
                local.side_known.clear();
                local.in_plane_of_side_of = kNoHit;
              }
              return filtered_count(g, hits[k], candidates, local.middles[i], local,
                                    [&](const std::vector<std::uint32_t>& rest_of_list) {
                                      return count_at(g, light, grid.ray(k), hits[k], point_boxes[k], &rest_of_list);
                                    });
            };
            if (light_grid) {
              // Each hit point reads the lists of its own box's cells; the group only shares
              // the candidates' filters, each drawn when a point first meets it. A group whose
              // box meets many cells (hit points far apart: loose filters) is halved.
              const std::optional<detail::LightGrid::Reach> group_reach = light_grid->reach(lo, hi);
              if (group_reach && group_reach->cells() > kGridGroupCells && group.size() > kLeastCountGroup) return halve();
              const double group_threshold = group_reach ? group_reach->threshold : -std::numeric_limits<double>::infinity();
              // A group whose cells list no triangle nearer to the light than its farthest point
              // (the lit floor: 672K of ogre's 910K counted points at 1024x768) has no other
              // candidates than big()'s entries above its threshold: a point's box lies in the
              // group's, so its own reach would list nothing more (LightGrid::cells_list_any).
              const bool big_alone = group_reach && !light_grid->cells_list_any(*group_reach);
              if (big_alone) {
                // Where each of those is the point's hit triangle or lies in its plane (the
                // floor's two halves under a floor point), count_at passes them all by: 0, with
                // no filter drawn (local.in_plane_pairs remembers the pairs found in one plane).
                const auto in_plane = [&](std::uint32_t h, std::uint32_t id) {
                  if (id == h) return true;
                  const std::pair<std::uint32_t, std::uint32_t> pair{h, id};
                  if (std::find(local.in_plane_pairs.begin(), local.in_plane_pairs.end(), pair) != local.in_plane_pairs.end())
                    return true;
                  const HomogeneousPoint ha = finite_point(g.vertex(h, 0)), hb = finite_point(g.vertex(h, 1)),
                                         hc = finite_point(g.vertex(h, 2));
                  for (int v = 0; v < 3; ++v)
                    if (detail::orient_unchecked(ha, hb, hc, finite_point(g.vertex(id, v))) != Sign::zero) return false;
                  local.in_plane_pairs.push_back(pair);
                  return true;
                };
                std::uint32_t last_h = kNoHit;
                bool all_in_plane = true;
                for (const std::size_t k : group) {
                  const std::uint32_t h = hits[k].triangle;
                  if (h == last_h) continue;
                  last_h = h;
                  for (const std::uint32_t id : light_grid->big())
                    if (light_grid->key(id) > group_threshold && !in_plane(h, id)) all_in_plane = false;
                  if (!all_in_plane) break;
                }
                if (all_in_plane) {
                  for (const std::size_t k : group) counts[k] = 0;
                  return;
                }
              }
              Vec3 mlo{}, mhi{}, R{};
              middles(mlo, mhi, R);
              const CrossingFrame frame(g.lights[light], mlo, mhi, R);
              const std::uint32_t generation = local.next_generation(g.soup.triangles.size());
              local.crossing.clear();
              local.crossing_ids.clear();
              const auto slot_of = [&](std::uint32_t id) {
                if (local.seen[id] != generation) {
                  local.seen[id] = generation;
                  local.slot[id] = static_cast<std::uint32_t>(local.crossing.size());
                  add_segment_crossing_filter(g, light, id, frame, local.crossing);
                  local.crossing_ids.push_back(id);
                }
                return local.slot[id];
              };
              // Neighbouring hit points mostly reach one and the same cell: its list's filters
              // are kept for the last cell read (no entry at or below the group's threshold is
              // read by any of its points).
              std::uint64_t cached_cell = std::numeric_limits<std::uint64_t>::max();
              // The group above with big()'s entries alone: each point counts against those above
              // the group's threshold (which include those above its own), without its reach.
              if (big_alone) {
                for (std::size_t i = 0; i < group.size(); ++i)
                  counts[group[i]] = count_filtered(i, [&](auto&& visit) {
                    for (const std::uint32_t id : light_grid->big())
                      if (light_grid->key(id) > group_threshold) visit(id, local.crossing[slot_of(id)]);
                  });
                return;
              }
              for (std::size_t i = 0; i < group.size(); ++i) {
                const std::size_t k = group[i];
                const PointBox box = point_boxes[k];
                const std::optional<detail::LightGrid::Reach> reach = light_grid->reach(box[0], box[1]);
                if (!reach) {
                  counts[k] = count_at(g, light, grid.ray(k), hits[k], box);
                  continue;
                }
                if (reach->one_cell()) {
                  if (const std::uint64_t cell = std::uint64_t{reach->r0} << 32 | reach->c0; cell != cached_cell) {
                    cached_cell = cell;
                    local.cell_slots.clear();
                    for (const std::uint32_t id : light_grid->list(reach->c0, reach->r0))
                      if (light_grid->key(id) > group_threshold) local.cell_slots.emplace_back(light_grid->key(id), slot_of(id));
                  }
                  // The point's candidates read straight from big() and the cached cell (each
                  // filter used at once, before slot_of may grow local.crossing again).
                  const double threshold = reach->threshold;
                  counts[k] = count_filtered(i, [&](auto&& visit) {
                    for (const std::uint32_t id : light_grid->big())
                      if (light_grid->key(id) > threshold) visit(id, local.crossing[slot_of(id)]);
                    for (const auto& [key, slot] : local.cell_slots)
                      if (key > threshold) visit(local.crossing_ids[slot], local.crossing[slot]);
                  });
                  continue;
                }
                local.point_slots.clear();
                for (const std::uint32_t id : light_grid->big())
                  if (light_grid->key(id) > reach->threshold) local.point_slots.push_back(slot_of(id));
                light_grid->visit(*reach, [&](std::uint32_t id) { local.point_slots.push_back(slot_of(id)); });
                // A triangle listed in two of its cells (or wide and in big()) comes twice.
                std::sort(local.point_slots.begin(), local.point_slots.end());
                local.point_slots.erase(std::unique(local.point_slots.begin(), local.point_slots.end()), local.point_slots.end());
                counts[k] = count_filtered(i, [&](auto&& visit) {
                  for (const std::uint32_t slot : local.point_slots) visit(local.crossing_ids[slot], local.crossing[slot]);
                });
              }
              return;
            }
            // A point light outside the box: the filters decide most candidates per hit point,
            // so the tile may list more of them.
            const HomogeneousPoint& l = g.lights[light];
            const bool filtered = l[3] != 0.0 && !(lo[0] <= l[0] && l[0] <= hi[0] && lo[1] <= l[1] && l[1] <= hi[1] &&
                                                  lo[2] <= l[2] && l[2] <= hi[2]);
            const TileCandidates list =
                light_tile_candidates(g, light, lo, hi, local, filtered ? kFilteredCountCandidates : kTileCandidates);
            // Too many for one list (hit points far apart, as across a silhouette): the halves.
            if (!list.listed && filtered && group.size() > kLeastCountGroup) return halve();
            if (!list.listed) {
              for (std::size_t k : group) counts[k] = count_at(g, light, grid.ray(k), hits[k], point_boxes[k]);
              return;
            }
            if (filtered) {
              Vec3 mlo{}, mhi{}, R{};
              middles(mlo, mhi, R);
              local.crossing.clear();
              const CrossingFrame frame(g.lights[light], mlo, mhi, R);
              for (const std::uint32_t id : list.ids) add_segment_crossing_filter(g, light, id, frame, local.crossing);
            }
            // Per hit triangle h, the list without h and the triangles in h's plane: P lies on
            // that plane, so count_at passes them by (P on their plane); an empty rest counts 0.
            // With the filters only the candidates they leave are checked (per h, remembered).
            std::uint32_t cached_h = kNoHit;
            for (std::size_t i = 0; i < group.size(); ++i) {
              const std::size_t k = group[i];
              const std::uint32_t h = hits[k].triangle;
              if (filtered) {
                counts[k] = count_filtered(i, [&](auto&& visit) {
                  for (std::size_t c = 0; c < list.ids.size(); ++c) visit(list.ids[c], local.crossing[c]);
                });
                continue;
              }
              if (h != cached_h) {
                cached_h = h;
                const HomogeneousPoint ha = finite_point(g.vertex(h, 0)), hb = finite_point(g.vertex(h, 1)),
                                       hc = finite_point(g.vertex(h, 2));
                const auto on_plane = [&](std::uint32_t v) {
                  return detail::orient_unchecked(ha, hb, hc, finite_point(g.soup.vertices[v])) == Sign::zero;
                };
                rest.clear();
                for (std::uint32_t id : list.ids)
                  if (id != h && !std::all_of(g.soup.triangles[id].begin(), g.soup.triangles[id].end(), on_plane))
                    rest.push_back(id);
              }
              counts[k] = rest.empty() ? 0 : count_at(g, light, grid.ray(k), hits[k], point_boxes[k], &rest);
            }
          };
          count_group(count_group, std::span<std::size_t>(rays));
          work += rays.size();
        }
        progress.advance(r.size());
      });
      image.stats.counts += work;
    }

    // With the footprints, per tile the silhouette edges the light pyramids of its pixels can
    // meet (the box of its pixels' countable corner hits and the light: light_cone_candidates),
    // for footprint_shadow_varies.
    std::vector<TileCandidates> silhouette_lists(footprints ? tiles.count() : 0);
    if (footprints) {
      const Silhouette& silhouette = *g.silhouettes[light];
      tbb::enumerable_thread_specific<TileScratch> silhouette_scratch;
      tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, tiles.count(), 1), [&](const auto& r) {
        TileScratch& local = silhouette_scratch.local();
        for (std::uint32_t t = r.begin(); t != r.end(); ++t) {
          const TileGrid::Bounds b = tiles.bounds(t);
          bool any = false;
          Vec3 lo{}, hi{};
          for (std::uint32_t y = b.y0; y <= b.y1; ++y)
            for (std::uint32_t x = b.x0; x <= b.x1; ++x) {
              const std::size_t k = grid.corner(x, y);
              if (!countable(hits[k])) continue;
              const PointBox box = point_boxes[k];
              for (int a = 0; a < 3; ++a) {
                lo[a] = any ? std::min(lo[a], box[0][a]) : box[0][a];
                hi[a] = any ? std::max(hi[a], box[1][a]) : box[1][a];
              }
              any = true;
            }
          if (any)
            silhouette_lists[t] = light_cone_candidates(silhouette.tree, silhouette.edges.size(), g.lights[light], lo, hi,
                                                        [](std::uint32_t) { return true; }, local);
        }
      });
    }

    // The light's image, or with a tally its sums straight into the tally: no per-light arrays
    // (4.7 MB at 1024x768, filled on one thread before this pass) where none is kept.
    ExactLightImage out;
    if (!tally) {
      resize_huge(out.counts, grid.centres());
      resize_huge(out.lit, grid.centres());
      resize_huge(out.ambiguity, grid.centres());
    }
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, grid.height), [&](const auto& r) {
      for (std::uint32_t row = r.begin(); row != r.end(); ++row)
        for (std::uint32_t i = 0; i < grid.width; ++i) {
          const auto rays = grid.footprint(i, row);
          const std::size_t pixel = rays[0];
          const RayHit& centre = hits[pixel];
          std::uint8_t bits = geometric[pixel];
          std::uint32_t n = centre.triangle == kNoHit ? kNoHit : kUndefinedCount;
          if (countable(centre)) {
            n = light_counts[pixel];
            if (n == kUndefinedCount) bits |= kZeroSign;
            if (terminator(g, light, centre)) bits |= kTerminator;
            if (bits == 0 && footprints)
              for (std::size_t k = 1; k < rays.size(); ++k) {
                if (light_counts[rays[k]] == kUndefinedCount) bits |= kZeroSign;
                else if (light_counts[rays[k]] != n) bits |= kFootprintCounts;
              }
            // The corners agree: n must still be constant between them (a shadow sliver). A
            // tile whose list holds no silhouette edge has none to meet: its corners' parameters
            // are not built (footprint_shadow_varies would test no candidate).
            const std::vector<std::uint32_t>* silhouettes_near =
                footprints ? silhouette_lists[tiles.of(i, row)].list() : nullptr;
            if (bits == 0 && footprints && !(silhouettes_near != nullptr && silhouettes_near->empty()) &&
                footprint_shadow_varies(g, light, corner_hits(g, grid, hits, point_boxes, i, row), silhouettes_near))
              bits |= kFootprintCounts;
            if (bits == 0 && footprints && options.depth_band) {
              const DepthBand band = depth_band(g, grid.frame, grid.ray(pixel), centre, options.depth_band);
              if (band_meets_volume(g, light, band) ||
                  (!fold_mask.empty() && fold_mask[pixel] != 0 &&
                   fold_pair_at_centre(g, light, grid.frame, *backdrop, i, row, centre, band)))
                bits |= kDepthBand;
            }
          } else if (centre.triangle != kNoHit) {
            bits |= kZeroSign;
          }
          if (tally) {
            const bool defined = n != kNoHit && n != kUndefinedCount;
            image.tally.defined[pixel] += defined ? 1 : 0;
            image.tally.lit[pixel] += defined && n == 0 ? 1 : 0;
            if ((bits & kTerminator) != 0) image.tally.terminator[pixel] = 1;
            continue;
          }
          out.counts[pixel] = n;
          out.lit[pixel] = countable(centre) && n == 0 ? 255 : 0;
          out.ambiguity[pixel] = bits;
        }
    });
    if (beam) beam_counts_of[light] = {};  // read: its memory back before the next light
    if (!tally) image.lights.push_back(std::move(out));
  }
  image.stats.count_seconds += seconds_since(stage);
  image.stats.seconds = seconds_since(start);
  return image;
}

}  // namespace shadowcert
