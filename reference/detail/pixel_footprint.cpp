#include "reference/detail/pixel_footprint.h"

#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "reference/detail/hit_point_coordinates.h"

namespace shadowcert::detail {
namespace {

using Interval = CGAL::Interval_nt<false>;  // only under a Protect_FPU_rounding
using IVec = VecOf<Interval>;
using EVec = VecOf<CGAL::Mpzf>;
using EPoint = HomogeneousCoordinates<CGAL::Mpzf>;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// x - origin, enclosed.
IVec relative(const Vec3& x, const Vec3& origin) {
  return {Interval(x[0]) - origin[0], Interval(x[1]) - origin[1], Interval(x[2]) - origin[2]};
}

// p - q up to the positive factor 1 / (w_p w_q): w_q x_p - w_p x_q.
EVec difference(const EPoint& p, const EPoint& q) {
  return {q.w * p.x[0] - p.w * q.x[0], q.w * p.x[1] - p.w * q.x[1], q.w * p.x[2] - p.w * q.x[2]};
}

EPoint exact_point(const Vec3& p) { return {{CGAL::Mpzf(p[0]), CGAL::Mpzf(p[1]), CGAL::Mpzf(p[2])}, CGAL::Mpzf(1)}; }

// How far the interval projections settle one axis n: the points P (segment ends or triangle
// corners) lie strictly on one side of the polytope K's projection (separated), certainly not
// (some point is at or beyond K's extreme on both sides), or unsure. For a prism along l, K's
// projection is unbounded towards the sign of n . l.
using Verdict = FootprintPolytope::Verdict;

struct Extent {
  double min_lo = kInfinity, min_hi = kInfinity;     // bounds of the minimum
  double max_lo = -kInfinity, max_hi = -kInfinity;  // bounds of the maximum
  void add(const Interval& x) {
    min_lo = std::min(min_lo, x.inf());
    min_hi = std::min(min_hi, x.sup());
    max_lo = std::max(max_lo, x.inf());
    max_hi = std::max(max_hi, x.sup());
  }
};

Verdict decide(const Extent& k, const Extent& p, const std::optional<Interval>& along) {
  // "below": every point strictly below K (K must not extend downwards: n . l >= 0).
  const bool below = p.max_hi < k.min_lo && (!along || along->inf() >= 0.0);
  const bool above = p.min_lo > k.max_hi && (!along || along->sup() <= 0.0);
  if (below || above) return Verdict::separated;
  const bool never_below = p.max_lo >= k.min_hi || (along && along->sup() < 0.0);
  const bool never_above = p.min_hi <= k.max_lo || (along && along->inf() > 0.0);
  return never_below && never_above ? Verdict::not_separated : Verdict::unsure;
}

template <typename Bounds>
Interval load(const Bounds& b) {
  return Interval(b.lo, b.hi);
}
template <typename BoundsVec>
IVec load_vec(const BoundsVec& v) {
  return {load(v[0]), load(v[1]), load(v[2])};
}
template <typename BoundsVec>
BoundsVec store_vec(const IVec& v) {
  BoundsVec out{};
  for (std::size_t k = 0; k < 3; ++k) out[k] = {v[k].inf(), v[k].sup()};
  return out;
}

}  // namespace

// The polytope as exact homogeneous points (w > 0), built on first need.
struct FootprintPolytope::Exact {
  bool directional = false;
  EVec direction;                // directional apex
  EPoint apex;                   // finite apex
  std::array<EPoint, 4> corners;
};

namespace {

FootprintPolytope::CornerBoxes corner_boxes(const std::array<RayParameter, 4>& corners) {
  FootprintPolytope::CornerBoxes boxes;
  for (std::size_t i = 0; i < 4; ++i) {
    const HitPoint h(corners[i]);
    boxes[i] = {h.lo(), h.hi()};
  }
  return boxes;
}

}  // namespace

FootprintPolytope::FootprintPolytope(const HomogeneousPoint& apex, const std::array<RayParameter, 4>& corners)
    : apex_(apex), corners_(corners), directional_(apex[3] == 0.0) {
  enclose(corner_boxes(corners));
}

FootprintPolytope::FootprintPolytope(const HomogeneousPoint& apex, const std::array<RayParameter, 4>& corners,
                                     const CornerBoxes& boxes)
    : apex_(apex), corners_(corners), directional_(apex[3] == 0.0) {
  enclose(boxes);
}

void FootprintPolytope::query_box(const CornerBoxes& boxes, Vec3& from, Vec3& slack) {
  // The origin: the middle of R's enclosing box; the slack covers that box (exact/box_tree.h).
  Vec3 lo = boxes[0][0], hi = boxes[0][1];
  for (const auto& h : boxes)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], h[0][k]);
      hi[k] = std::max(hi[k], h[1][k]);
    }
  for (int k = 0; k < 3; ++k) {
    from[k] = std::clamp(lo[k] / 2 + hi[k] / 2, lo[k], hi[k]);
    slack[k] = std::nextafter(std::max(hi[k] - from[k], from[k] - lo[k]), kInfinity);
  }
}

void FootprintPolytope::enclose(const CornerBoxes& boxes) {
  const CornerBoxes& hits = boxes;
  query_box(boxes, from_, slack_);
  const CGAL::Protect_FPU_rounding<true> protect;
  std::array<IVec, 4> c;
  for (std::size_t i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) c[i][k] = Interval(hits[i][0][k], hits[i][1][k]) - from_[k];
  // Zero-initialised explicitly: Interval_nt's default constructor leaves its value unset, and
  // GCC cannot see that only the branch that set `l` (or `a`) reads it.
  const IVec zero{Interval(0.0), Interval(0.0), Interval(0.0)};
  IVec a = zero, l = zero;
  if (directional_) {
    l = {Interval(apex_[0]), Interval(apex_[1]), Interval(apex_[2])};
    direction_ = store_vec<BoundsVec>(l);
  } else {
    a = relative({apex_[0], apex_[1], apex_[2]}, from_);
    vertices_[static_cast<std::size_t>(vertex_count_++)] = store_vec<BoundsVec>(a);
  }
  for (const IVec& corner : c) vertices_[static_cast<std::size_t>(vertex_count_++)] = store_vec<BoundsVec>(corner);
  for (std::size_t i = 0; i < 4; ++i) {
    const IVec& p = c[i];
    const IVec& q = c[(i + 1) % 4];
    region_edges_[i] = store_vec<BoundsVec>(shadowcert::difference(q, p));
    if (!directional_) apex_edges_[i] = store_vec<BoundsVec>(shadowcert::difference(p, a));
    normals_[i] = store_vec<BoundsVec>(directional_ ? cross(shadowcert::difference(q, p), l)
                                                    : cross(shadowcert::difference(p, a), shadowcert::difference(q, a)));
  }
  normals_[4] = store_vec<BoundsVec>(cross(shadowcert::difference(c[1], c[0]), shadowcert::difference(c[2], c[0])));
  for (std::size_t j = 0; j < normals_.size(); ++j) {
    const IVec n = load_vec(normals_[j]);
    Extent e;
    for (int v = 0; v < vertex_count_; ++v) e.add(dot(n, load_vec(vertices_[static_cast<std::size_t>(v)])));
    minimum_[j] = {e.min_lo, e.min_hi};
    maximum_[j] = {e.max_lo, e.max_hi};
  }
}

FootprintPolytope::~FootprintPolytope() = default;

const FootprintPolytope::Exact& FootprintPolytope::exact() const {
  if (!exact_) {
    auto e = std::make_unique<Exact>();
    e->directional = directional_;
    if (directional_) {
      e->direction = {CGAL::Mpzf(apex_[0]), CGAL::Mpzf(apex_[1]), CGAL::Mpzf(apex_[2])};
    } else {
      e->apex = exact_point({apex_[0], apex_[1], apex_[2]});
    }
    for (std::size_t i = 0; i < 4; ++i)
      e->corners[i] =
          hit_point_coordinates<CGAL::Mpzf>(corners_[i].ray(), corners_[i].triangle(), corners_[i].direction_side());
    exact_ = std::move(e);
  }
  return *exact_;
}

// The axis, exactly (a positive multiple of the interval one), and the pairwise test: every
// (polytope vertex - point) has the same strict sign along it, and a prism does not extend
// towards the points.
bool FootprintPolytope::exactly_separated(AxisKind kind, int index, std::initializer_list<const Vec3*> points) const {
  const Exact& k = exact();
  const auto i = static_cast<std::size_t>(index);
  EVec n;
  switch (kind) {
    case AxisKind::face:
      if (i == 4) {
        n = cross(difference(k.corners[1], k.corners[0]), difference(k.corners[2], k.corners[0]));
      } else if (k.directional) {
        n = cross(difference(k.corners[(i + 1) % 4], k.corners[i]), k.direction);
      } else {
        n = cross(difference(k.corners[i], k.apex), difference(k.corners[(i + 1) % 4], k.apex));
      }
      break;
    case AxisKind::region_edge:
    case AxisKind::apex_edge: {
      const Vec3& u = **points.begin();
      const Vec3& v = **(points.begin() + 1);
      const EVec d = difference<CGAL::Mpzf>(v, u);
      if (kind == AxisKind::region_edge) {
        n = cross(d, difference(k.corners[(i + 1) % 4], k.corners[i]));
      } else {
        n = k.directional ? cross(d, k.direction) : cross(d, difference(k.corners[i], k.apex));
      }
      break;
    }
  }
  bool positive = true, negative = true;
  const auto vertex = [&](const EPoint& x) {
    for (const Vec3* p : points) {
      const CGAL::Sign s = CGAL::sign(dot(n, difference(x, exact_point(*p))));
      positive = positive && s == CGAL::POSITIVE;
      negative = negative && s == CGAL::NEGATIVE;
    }
  };
  if (!k.directional) vertex(k.apex);
  for (const EPoint& c : k.corners) vertex(c);
  if (k.directional) {
    const CGAL::Sign along = CGAL::sign(dot(n, k.direction));
    positive = positive && along != CGAL::NEGATIVE;
    negative = negative && along != CGAL::POSITIVE;
  }
  return positive || negative;
}

// Every axis is first tried in intervals; only when none separates for certain are the axes
// the intervals could not settle decided exactly (most segments near the footprint have a
// certain separating axis, often not the first one tried).
// Both verdicts run under the caller's Protect_FPU_rounding (one rounding-mode switch for all
// the axes of a test, not one per axis).
Verdict FootprintPolytope::face_verdict(std::size_t j, std::initializer_list<const Vec3*> points) const {
  const IVec n = load_vec(normals_[j]);
  Extent p;
  for (const Vec3* x : points) p.add(dot(n, relative(*x, from_)));
  const Extent k{minimum_[j].lo, minimum_[j].hi, maximum_[j].lo, maximum_[j].hi};
  std::optional<Interval> along;
  if (directional_) along = dot(n, load_vec(direction_));
  return decide(k, p, along);
}

Verdict FootprintPolytope::edge_verdict(AxisKind kind, int index, const Vec3& u, const Vec3& v) const {
  const IVec pu = relative(u, from_), pv = relative(v, from_);
  const IVec d = shadowcert::difference(pv, pu);
  const auto i = static_cast<std::size_t>(index);
  const IVec n = kind == AxisKind::region_edge ? cross(d, load_vec(region_edges_[i]))
                 : directional_               ? cross(d, load_vec(direction_))
                                              : cross(d, load_vec(apex_edges_[i]));
  Extent k, p;
  for (int x = 0; x < vertex_count_; ++x) k.add(dot(n, load_vec(vertices_[static_cast<std::size_t>(x)])));
  p.add(dot(n, pu));
  p.add(dot(n, pv));
  std::optional<Interval> along;
  if (directional_) along = dot(n, load_vec(direction_));
  return decide(k, p, along);
}

bool FootprintPolytope::meets(const Vec3& u, const Vec3& v) const {
  struct Axis {
    AxisKind kind;
    int index;
  };
  std::array<Axis, 13> unsure{};
  std::size_t count = 0;
  const auto consider = [&](AxisKind kind, int index, Verdict verdict) {
    if (verdict == Verdict::unsure) unsure[count++] = {kind, index};
    return verdict == Verdict::separated;
  };
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    for (int j = 0; j < 5; ++j)
      if (consider(AxisKind::face, j, face_verdict(static_cast<std::size_t>(j), {&u, &v}))) return false;
    for (int i = 0; i < 4; ++i)
      if (consider(AxisKind::region_edge, i, edge_verdict(AxisKind::region_edge, i, u, v))) return false;
    for (int i = 0; i < (directional_ ? 1 : 4); ++i)
      if (consider(AxisKind::apex_edge, i, edge_verdict(AxisKind::apex_edge, i, u, v))) return false;
  }
  // The exact stage in the default rounding mode.
  for (std::size_t k = 0; k < count; ++k)
    if (exactly_separated(unsure[k].kind, unsure[k].index, {&u, &v})) return false;
  return true;
}

bool FootprintPolytope::meets_an_edge_of(const Vec3& a, const Vec3& b, const Vec3& c) const {
  // The whole triangle beside one face plane for certain: no edge can meet.
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    for (std::size_t j = 0; j < 5; ++j)
      if (face_verdict(j, {&a, &b, &c}) == Verdict::separated) return false;
  }
  return meets(a, b) || meets(b, c) || meets(c, a);
}

}  // namespace shadowcert::detail
