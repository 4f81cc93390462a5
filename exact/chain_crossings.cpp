#include "exact/chain_crossings.h"

#include <CGAL/Interval_nt.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "exact/box_tree.h"
#include "exact/face_crossing.h"
#include "exact/light_orientation.h"

namespace shadowcert::detail {
namespace {

using Interval = CGAL::Interval_nt<false>;

constexpr std::size_t kMaxPiecesPerSide = 32;

// A closed axis-aligned box; `index` is the face it bounds (a side face has several boxes).
struct IndexedBox {
  std::array<double, 3> lo{};
  std::array<double, 3> hi{};
  std::uint32_t index = 0;
};

// Intersects `box` with `clip`; false when nothing is left.
bool clip_to(IndexedBox& box, const IndexedBox& clip) {
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = std::max(box.lo[d], clip.lo[d]);
    box.hi[d] = std::min(box.hi[d], clip.hi[d]);
    if (box.lo[d] > box.hi[d]) return false;
  }
  return true;
}

IndexedBox segment_box(const Vec3& a, const Vec3& b) {
  IndexedBox box;
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = std::min(a[d], b[d]);
    box.hi[d] = std::max(a[d], b[d]);
  }
  return box;
}

void extend(IndexedBox& box, const IndexedBox& other) {
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = std::min(box.lo[d], other.lo[d]);
    box.hi[d] = std::max(box.hi[d], other.hi[d]);
  }
}

// The faces a finite segment can cross (chain_crossings.h): front caps [0, caps), then the
// side faces, one per side edge with its multiplicity (no |m| copies are expanded).
class CrossableFaces {
 public:
  explicit CrossableFaces(const CrossingQuery& q) : q_(q), light_(q.light.position) {
    if (q.chain.finite_vertices != q.canonical.vertices.size() || q.chain.directional != q.light.directional() ||
        q.chain.cap_triangles.size() != q.chain.cap_sign.size() ||
        q.chain.side_edges.size() != q.chain.side_multiplicity.size())
      throw std::invalid_argument("chain crossings: the chain was not assembled on this soup and light");
    for (std::uint32_t t : q.chain.cap_triangles)
      if (t >= q.canonical.triangles.size()) throw std::invalid_argument("chain crossings: cap triangle out of range");
    for (const auto& e : q.chain.side_edges)
      if (e[0] >= q.canonical.vertices.size() || e[1] >= q.canonical.vertices.size())
        throw std::invalid_argument("chain crossings: side edge out of range");
  }

  [[nodiscard]] std::size_t caps() const { return q_.chain.cap_triangles.size(); }
  [[nodiscard]] std::size_t size() const { return caps() + q_.chain.side_edges.size(); }

  // Signed crossings of face f by A -> B (0 when apart); nullopt on a touch.
  [[nodiscard]] std::optional<std::int64_t> contribution(std::size_t f, const Vec3& a, const Vec3& b) const {
    if (f < caps()) return cap_contribution(f, a, b);
    return side_contribution(f - caps(), a, b);
  }

  // Closed boxes that together hold face f's part inside `clip`, appended to `out` with
  // index f: one box for a cap (its vertices' box), consecutive pieces along the rays for a
  // side face (`target` is the piece length to aim at). Conservative by construction: box
  // coordinates are input doubles or bounds of interval arithmetic, never rounded values.
  void append_boxes(std::size_t f, const IndexedBox& clip, double target, std::vector<IndexedBox>& out) const {
    IndexedBox box;
    box.index = static_cast<std::uint32_t>(f);
    if (f < caps()) {
      const Triangle& t = q_.canonical.triangles[q_.chain.cap_triangles[f]];
      const auto& p = q_.canonical.vertices;
      box = segment_box(p[t[0]], p[t[1]]);
      extend(box, segment_box(p[t[2]], p[t[2]]));
      box.index = static_cast<std::uint32_t>(f);
      if (clip_to(box, clip)) out.push_back(box);
      return;
    }
    append_side_pieces(f - caps(), clip, target, box, out);
  }

 private:
  std::optional<std::int64_t> cap_contribution(std::size_t c, const Vec3& a, const Vec3& b) const {
    const Triangle& t = q_.canonical.triangles[q_.chain.cap_triangles[c]];
    const auto& p = q_.canonical.vertices;
    const FaceMeeting m = segment_meets_triangle(finite_point(a), finite_point(b), p[t[0]], p[t[1]], p[t[2]]);
    switch (m.meeting) {
      case Meeting::apart:
        return 0;
      case Meeting::crosses:
        return to_int(q_.chain.cap_sign[c] * m.start_side);  // A's side of t' = s(t) * t
      case Meeting::touches:
        return std::nullopt;
    }
    return std::nullopt;
  }

  std::optional<std::int64_t> side_contribution(std::size_t k, const Vec3& a, const Vec3& b) const {
    const auto [u, v] = q_.chain.side_edges[k];
    const auto& p = q_.canonical.vertices;
    const FaceMeeting m = segment_meets_side(a, b, light_, p[u], p[v]);
    switch (m.meeting) {
      case Meeting::apart:
        return 0;
      case Meeting::crosses:  // the quad (u, v, v_inf, u_inf) faces -(L, u, v): m copies
        return -std::int64_t{q_.chain.side_multiplicity[k]} * to_int(m.start_side);
      case Meeting::touches:
        return std::nullopt;
    }
    return std::nullopt;
  }

  // Per axis d, the side face's coordinate along each of its rays from x on [u, v]:
  // point light, l_d + t (x_d - l_d), t >= 1, so >= min(u_d, v_d) when both rays go up
  // (u_d >= l_d and v_d >= l_d), <= max(u_d, v_d) when both go down; directional,
  // x_d - t l_d, t >= 0, the same with the direction -l. Unbounded ends stop at the clip box.
  // The fallback when no parameter bound exists (side_parameters).
  void loose_side_box(const Vec3& pu, const Vec3& pv, const IndexedBox& clip, IndexedBox& box) const {
    const bool directional = q_.chain.directional;
    for (int d = 0; d < 3; ++d) {
      const bool up = directional ? light_[d] <= 0.0 : (pu[d] >= light_[d] && pv[d] >= light_[d]);
      const bool down = directional ? light_[d] >= 0.0 : (pu[d] <= light_[d] && pv[d] <= light_[d]);
      box.lo[d] = up ? std::min(pu[d], pv[d]) : clip.lo[d];
      box.hi[d] = down ? std::max(pu[d], pv[d]) : clip.hi[d];
    }
  }

  // The ray parameter range [first, last] outside which the side face lies outside `clip`:
  // point light, t >= 1 and, past R / r, |p - l|_inf = t |x - l|_inf >= t r > R, where R bounds
  // |c - l|_inf over the clip box and r = max_d dist(l_d, [u_d, v_d]) bounds |x - l|_inf from
  // below; directional, t >= 0 and, past W / |l_d| on the axis of largest |l_d|, p_d = x_d - t l_d
  // has left [lo_d, hi_d] (W bounds |p_d - x_d| inside the box). Upper bounds from interval
  // arithmetic (rounded outwards). nullopt when r = 0: no bound (the light's coordinates lie
  // within the edge's box).
  std::optional<std::array<double, 2>> side_parameters(const Vec3& pu, const Vec3& pv, const IndexedBox& clip) const {
    if (q_.chain.directional) {
      int axis = 0;
      for (int d = 1; d < 3; ++d)
        if (std::fabs(light_[d]) > std::fabs(light_[axis])) axis = d;
      const Interval lo = std::min({clip.lo[axis], pu[axis], pv[axis]});
      const Interval hi = std::max({clip.hi[axis], pu[axis], pv[axis]});
      return std::array<double, 2>{0.0, ((hi - lo) / Interval(std::fabs(light_[axis]))).sup()};
    }
    double reach = 0.0, gap = 0.0;  // R (upper bound) and r (lower bound)
    for (int d = 0; d < 3; ++d) {
      const Interval l = light_[d];
      reach = std::max({reach, CGAL::abs(Interval(clip.lo[d]) - l).sup(), CGAL::abs(Interval(clip.hi[d]) - l).sup()});
      const double lo = std::min(pu[d], pv[d]), hi = std::max(pu[d], pv[d]);
      if (light_[d] < lo) gap = std::max(gap, (Interval(lo) - l).inf());
      if (light_[d] > hi) gap = std::max(gap, (l - Interval(hi)).inf());
    }
    if (!(gap > 0.0)) return std::nullopt;
    return std::array<double, 2>{1.0, (Interval(reach) / Interval(gap)).sup()};
  }

  // Interval enclosure of the point at parameter t on the ray from x (see side_parameters).
  std::array<Interval, 3> ray_point(const Vec3& x, double t) const {
    std::array<Interval, 3> p;
    for (int d = 0; d < 3; ++d)
      p[d] = q_.chain.directional ? Interval(x[d]) - Interval(t) * Interval(light_[d])
                                  : Interval(light_[d]) + Interval(t) * (Interval(x[d]) - Interval(light_[d]));
    return p;
  }

  // How many pieces: about the face's length over `target` (plain doubles: only the speed
  // depends on it), at least one, at most kMaxPiecesPerSide.
  std::size_t piece_count(const Vec3& pu, const Vec3& pv, const std::array<double, 2>& range, double target) const {
    double reach = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double along = q_.chain.directional ? std::fabs(light_[d])
                                                : std::max(std::fabs(pu[d] - light_[d]), std::fabs(pv[d] - light_[d]));
      reach = std::max({reach, along, std::fabs(pu[d] - pv[d])});
    }
    const double pieces = (range[1] - range[0]) * reach / target;
    if (!(pieces > 1.0)) return 1;
    return pieces >= double(kMaxPiecesPerSide) ? kMaxPiecesPerSide : static_cast<std::size_t>(std::ceil(pieces));
  }

  // The pieces t in [t_j, t_j+1] of side face k: each a convex quadrilateral whose corners are
  // the rays' points at t_j and t_j+1, so the hull of their enclosures bounds it.
  void append_side_pieces(std::size_t k, const IndexedBox& clip, double target, IndexedBox box,
                          std::vector<IndexedBox>& out) const {
    const auto [u, v] = q_.chain.side_edges[k];
    const Vec3 &pu = q_.canonical.vertices[u], &pv = q_.canonical.vertices[v];
    CGAL::Protect_FPU_rounding<true> rounding_up;  // what Interval_nt<false> requires
    const std::optional<std::array<double, 2>> range = side_parameters(pu, pv, clip);
    if (!range || !std::isfinite((*range)[1])) {  // no finite bound: one box for the whole face
      loose_side_box(pu, pv, clip, box);
      if (clip_to(box, clip)) out.push_back(box);
      return;
    }
    if ((*range)[1] < (*range)[0]) return;  // entirely outside the clip box
    const std::size_t pieces = piece_count(pu, pv, *range, target);
    // Breakpoints by one formula, so that consecutive pieces share theirs bit for bit.
    // Named doubles, not a structured binding: clang 14 (the sanitizer build) cannot capture one.
    const double first = (*range)[0], last = (*range)[1];
    auto breakpoint = [&](std::size_t j) {
      return j == pieces ? last : first + (last - first) * double(j) / double(pieces);
    };
    for (std::size_t j = 0; j < pieces; ++j) {
      const double t0 = breakpoint(j), t1 = breakpoint(j + 1);
      box.lo = {clip.hi[0], clip.hi[1], clip.hi[2]};
      box.hi = {clip.lo[0], clip.lo[1], clip.lo[2]};
      for (const Vec3* x : {&pu, &pv})
        for (double t : {t0, t1}) {
          const std::array<Interval, 3> p = ray_point(*x, t);
          for (int d = 0; d < 3; ++d) {
            box.lo[d] = std::min(box.lo[d], p[d].inf());
            box.hi[d] = std::max(box.hi[d], p[d].sup());
          }
        }
      IndexedBox piece = box;
      if (clip_to(piece, clip)) out.push_back(piece);
    }
  }

  CrossingQuery q_;  // references: the soup, light and chain outlive the faces
  HomogeneousPoint light_;
};

// Every face, no acceleration.
std::optional<std::int64_t> chain_crossings_of_segment_unchecked(const CrossableFaces& faces, const Vec3& from,
                                                                 const Vec3& to) {
  std::int64_t sum = 0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::optional<std::int64_t> c = faces.contribution(f, from, to);
    if (!c) return std::nullopt;
    sum += *c;
  }
  return sum;
}

IndexedBox box_of(const Box& b) {
  IndexedBox box;
  box.lo = b.lo;
  box.hi = b.hi;
  return box;
}

bool inside(const Vec3& p, const IndexedBox& box) {
  for (int d = 0; d < 3; ++d)
    if (!(box.lo[d] <= p[d] && p[d] <= box.hi[d])) return false;
  return true;
}

}  // namespace

struct ChainCrossingIndex::Impl {
  CrossableFaces faces;
  IndexedBox clip;
  std::vector<std::uint32_t> face_of_box;
  BoxTree tree;

  Impl(const CrossingQuery& query, const Box& clip_box, double piece_length)
      : faces(query),
        clip(box_of(clip_box)),
        tree(face_boxes(faces, clip, piece_length, face_of_box), LeafTest::exact) {}

  // Every face box, and the face each belongs to (a side face has several).
  static std::vector<Box> face_boxes(const CrossableFaces& faces, const IndexedBox& clip, double piece_length,
                                           std::vector<std::uint32_t>& face_of_box) {
    if (faces.size() >= std::numeric_limits<std::uint32_t>::max())
      throw std::invalid_argument("chain crossings: more than 2^32 faces");
    std::vector<IndexedBox> indexed;
    for (std::size_t f = 0; f < faces.size(); ++f) faces.append_boxes(f, clip, piece_length, indexed);
    std::vector<Box> boxes(indexed.size());
    face_of_box.resize(indexed.size());
    for (std::size_t i = 0; i < indexed.size(); ++i) {
      boxes[i] = {indexed[i].lo, indexed[i].hi};
      face_of_box[i] = indexed[i].index;
    }
    return boxes;
  }

  // Sums the crossings over the faces whose boxes the segment meets, each face once (a side
  // face's pieces can all report it), stopping at the first touch.
  [[nodiscard]] std::optional<std::int64_t> crossings(const Vec3& from, const Vec3& to) const {
    std::vector<std::uint32_t> tested;
    std::int64_t sum = 0;
    bool touched = false;
    tree.segment_query(from, to, [&](std::uint32_t box) {
      const std::uint32_t face = face_of_box[box];
      if (face >= faces.caps()) {  // only side faces have several boxes
        if (std::find(tested.begin(), tested.end(), face) != tested.end()) return true;
        tested.push_back(face);
      }
      const std::optional<std::int64_t> c = faces.contribution(face, from, to);
      if (!c) {
        touched = true;
        return false;
      }
      sum += *c;
      return true;
    });
    if (touched) return std::nullopt;
    return sum;
  }
};

ChainCrossingIndex::ChainCrossingIndex(const CrossingQuery& query, const Box& clip, double piece_length)
    : impl_(std::make_unique<Impl>(query, clip, piece_length)) {}

ChainCrossingIndex::~ChainCrossingIndex() = default;

std::optional<std::int64_t> ChainCrossingIndex::crossings(const Vec3& from, const Vec3& to) const {
  if (from == to) return 0;  // no segment: nothing crossed (both ends have the same count)
  if (!inside(from, impl_->clip) || !inside(to, impl_->clip))
    return chain_crossings_of_segment_unchecked(impl_->faces, from, to);
  return impl_->crossings(from, to);
}

std::optional<std::int64_t> chain_crossings_of_segment(const CrossingQuery& query, const Vec3& from, const Vec3& to) {
  return chain_crossings_of_segment_unchecked(CrossableFaces(query), from, to);
}

}  // namespace shadowcert::detail
