#include "exact/box_tree.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "exact/count_sampling.h"

namespace shadowcert::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// Box ids to their CGAL boxes: the tree reads every node's box from here, never from a datum.
struct BoxMap {
  using key_type = std::uint32_t;
  using value_type = CGAL::Bbox_3;
  using reference = const CGAL::Bbox_3&;
  using category = boost::readable_property_map_tag;
  const std::vector<CGAL::Bbox_3>* boxes = nullptr;
  friend reference get(const BoxMap& map, key_type id) { return (*map.boxes)[id]; }
};

// A box by id, with its centre inline: the build's splits compare centres without following
// a pointer. (The centre is rounded; it only orders the split, never decides a query.)
class BoxPrimitive {
 public:
  using Id = std::uint32_t;
  using Point = Kernel::Point_3;
  using Datum = Kernel::Iso_cuboid_3;

  BoxPrimitive() = default;
  template <typename IdIterator>
  BoxPrimitive(IdIterator it, const std::vector<CGAL::Bbox_3>* boxes)
      : id_(*it), centre_(centre((*boxes)[*it])), boxes_(boxes) {}

  [[nodiscard]] Id id() const { return id_; }
  [[nodiscard]] const Point& reference_point() const { return centre_; }
  [[nodiscard]] Datum datum() const { return Datum((*boxes_)[id_]); }

 private:
  static Point centre(const CGAL::Bbox_3& b) {
    return {(b.xmin() + b.xmax()) / 2, (b.ymin() + b.ymax()) / 2, (b.zmin() + b.zmax()) / 2};
  }
  Id id_ = 0;
  Point centre_;
  const std::vector<CGAL::Bbox_3>* boxes_ = nullptr;
};

using Traits = CGAL::AABB_traits<Kernel, BoxPrimitive, BoxMap>;
using Tree = CGAL::AABB_tree<Traits>;

// The query's own box: the segment's endpoints' box, or for a ray the half-infinite box
// along its direction. A node or leaf box that misses it cannot meet the query: a handful of
// exact comparisons spares most of CGAL's segment/box tests.
struct QueryBox {
  std::array<double, 3> lo{};
  std::array<double, 3> hi{};

  [[nodiscard]] bool overlaps(const CGAL::Bbox_3& b) const {
    return lo[0] <= b.xmax() && b.xmin() <= hi[0] && lo[1] <= b.ymax() && b.ymin() <= hi[1] && lo[2] <= b.zmax() &&
           b.zmin() <= hi[2];
  }
};

QueryBox segment_box(const Vec3& from, const Vec3& to) {
  QueryBox q;
  for (int d = 0; d < 3; ++d) {
    q.lo[d] = std::min(from[d], to[d]);
    q.hi[d] = std::max(from[d], to[d]);
  }
  return q;
}

QueryBox ray_box(const Vec3& from, const Vec3& direction) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  QueryBox q;
  for (int d = 0; d < 3; ++d) {
    q.lo[d] = direction[d] < 0.0 ? -kInfinity : from[d];
    q.hi[d] = direction[d] > 0.0 ? kInfinity : from[d];
  }
  return q;
}

// Reports the boxes a query meets: node and leaf boxes tested exactly, stops on request.
template <typename Query, typename Callback>
class Reporting {
 public:
  Reporting(const Traits& traits, const std::vector<CGAL::Bbox_3>& boxes, LeafTest leaf_test, const QueryBox& box,
            void* visit, Callback callback)
      : traits_(traits), boxes_(boxes), leaf_test_(leaf_test), box_(box), visit_(visit), callback_(callback) {}

  [[nodiscard]] bool go_further() const { return going_; }
  void intersection(const Query& query, const BoxPrimitive& primitive) {
    if (!going_) return;
    if (leaf_test_ == LeafTest::exact && !meets(query, boxes_[primitive.id()])) return;
    going_ = callback_(visit_, primitive.id());
  }
  [[nodiscard]] bool do_intersect(const Query& query, const CGAL::AABB_node<Traits>& node) const {
    return meets(query, node.bbox());
  }

 private:
  [[nodiscard]] bool meets(const Query& query, const CGAL::Bbox_3& b) const {
    return box_.overlaps(b) && traits_.do_intersect_object()(query, b);
  }

  const Traits& traits_;
  const std::vector<CGAL::Bbox_3>& boxes_;
  LeafTest leaf_test_;
  QueryBox box_;
  void* visit_;
  Callback callback_;
  bool going_ = true;
};

// A conservative slab test for the dilated and nearest-first queries: the line piece
// from + t v, t in [0, t_max] (a ray: v its direction, t_max = infinity; a segment: v = to -
// from, t_max = 1) against a box dilated by `slack`. It answers "may meet" for every box the
// exact piece meets, in plain double arithmetic (no rounding-mode switch, the inner loop of
// every query), by bounding each rounding error as in exact/light_orientation_filter.h:
//   a slab parameter is A -+ B with A = fl(fl(x - from_k) * inv), B = fl(slack_k * |inv|) and
//   inv = fl(1 / v_k) (v_k itself fl(to_k - from_k) for a segment): at most four roundings of
//   relative error u = 2^-53 for A, three for B, one for their sum T, one more when the bound
//   T -+ m is formed. So |T - exact| <= 4.01 u (|A| + B) + u |T|, and the margin
//   m = (|A| + B + |T|) 2^-50 + 2^-1000 (8 u per term, plus an absolute term far above any
//   underflow error) covers it with the last rounding. An axis whose inv overflows is left
//   unconstrained (a superset). This is no tolerance: it only widens what may be visited.
inline constexpr double kSlabRelativeMargin = 0x1p-50;
inline constexpr double kSlabAbsoluteMargin = 0x1p-1000;

class Slab {
 public:
  Slab(const Vec3& from, const Vec3& v, double t_max, const Vec3& slack)
      : from_(from), t_max_(t_max), slack_(slack) {
    for (int k = 0; k < 3; ++k) {
      direction_[k] = v[k];
      inverse_[k] = v[k] != 0.0 ? 1.0 / v[k] : 0.0;
    }
  }

  // A lower bound of the entry parameter of the piece into b (dilated), or nullopt when the
  // piece certainly misses it.
  [[nodiscard]] std::optional<double> entry(const CGAL::Bbox_3& b) const {
    double enter = 0.0;
    double leave = t_max_;
    for (int k = 0; k < 3; ++k) {
      const double lo = b.min_coord(k), hi = b.max_coord(k), s = slack_[k];
      if (direction_[k] == 0.0) {
        // Parallel to the slab: certainly outside when lo - from_k > s (or from_k - hi > s);
        // fl(lo - from_k) (1 - 2^-50) is below lo - from_k for a positive difference.
        if ((lo - from_k(k)) * (1.0 - kSlabRelativeMargin) > s || (from_k(k) - hi) * (1.0 - kSlabRelativeMargin) > s)
          return std::nullopt;
        continue;
      }
      const double inv = inverse_[k];
      if (!std::isfinite(inv)) continue;
      const double a_lo = (lo - from_k(k)) * inv, a_hi = (hi - from_k(k)) * inv, widen = s * std::fabs(inv);
      const bool forward = inv > 0.0;
      const double a_near = forward ? a_lo : a_hi, a_far = forward ? a_hi : a_lo;
      const double near = a_near - widen, far = a_far + widen;
      const double near_margin = (std::fabs(a_near) + widen + std::fabs(near)) * kSlabRelativeMargin + kSlabAbsoluteMargin;
      const double far_margin = (std::fabs(a_far) + widen + std::fabs(far)) * kSlabRelativeMargin + kSlabAbsoluteMargin;
      const double near_bound = near - near_margin, far_bound = far + far_margin;
      if (std::isfinite(near_bound)) enter = std::max(enter, near_bound);
      if (std::isfinite(far_bound)) leave = std::min(leave, far_bound);
    }
    if (enter > leave) return std::nullopt;
    return enter;
  }

 private:
  [[nodiscard]] double from_k(int k) const { return from_[static_cast<std::size_t>(k)]; }
  Vec3 from_;
  Vec3 direction_{};
  Vec3 inverse_{};
  double t_max_;
  Vec3 slack_;
};

// Traversal traits over a Slab: visits every leaf whose box the piece may meet; with a bound,
// only those it may enter at t <= *bound, and (traversal_with_priority) the child it enters
// first before the other.
template <typename Callback>
class SlabTraversal {
 public:
  using Priority = double;

  SlabTraversal(const std::vector<CGAL::Bbox_3>& boxes, const Slab& slab, const double* bound, void* visit,
                Callback callback)
      : boxes_(boxes), slab_(slab), bound_(bound), visit_(visit), callback_(callback) {}

  [[nodiscard]] bool go_further() const { return going_; }
  template <typename Query>
  void intersection(const Query&, const BoxPrimitive& primitive) {
    if (!going_ || !within(slab_.entry(boxes_[primitive.id()]))) return;
    going_ = callback_(visit_, primitive.id());
  }
  template <typename Query>
  [[nodiscard]] bool do_intersect(const Query&, const CGAL::AABB_node<Traits>& node) const {
    return within(slab_.entry(node.bbox()));
  }
  template <typename Query>
  [[nodiscard]] std::pair<bool, Priority> do_intersect_with_priority(const Query&,
                                                                     const CGAL::AABB_node<Traits>& node) const {
    const std::optional<double> t = slab_.entry(node.bbox());
    return {within(t), t ? -*t : 0.0};
  }

 private:
  [[nodiscard]] bool within(const std::optional<double>& t) const {
    return t.has_value() && (bound_ == nullptr || *t <= *bound_);
  }

  const std::vector<CGAL::Bbox_3>& boxes_;
  const Slab& slab_;
  const double* bound_;
  void* visit_;
  Callback callback_;
  bool going_ = true;
};

// The query object CGAL's traversal passes through; the traits above carry the geometry.
struct SlabQuery {};

Kernel::Point_3 point_3(const Vec3& p) { return {p[0], p[1], p[2]}; }

}  // namespace

struct BoxTree::Impl {
  std::vector<CGAL::Bbox_3> boxes;
  LeafTest leaf_test;
  Tree tree;

  Impl(const std::vector<Box>& closed, LeafTest test) : leaf_test(test), tree(Traits(BoxMap{&boxes})) {
    if (closed.size() >= std::numeric_limits<std::uint32_t>::max())
      throw std::invalid_argument("BoxTree: more than 2^32 boxes");
    boxes.reserve(closed.size());
    std::vector<Vec3> centres;
    centres.reserve(closed.size());
    for (const Box& b : closed) {
      boxes.emplace_back(b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]);
      centres.push_back({(b.lo[0] + b.hi[0]) / 2, (b.lo[1] + b.hi[1]) / 2, (b.lo[2] + b.hi[2]) / 2});
    }
    if (boxes.empty()) return;
    const std::vector<std::uint32_t> order = morton_order(centres, bounding_box(centres));
    tree.insert(order.begin(), order.end(), &boxes);
    tree.build();  // now, not lazily on a first query: queries then run concurrently
  }
};

BoxTree::BoxTree(const std::vector<Box>& boxes, LeafTest leaf_test)
    : impl_(std::make_unique<Impl>(boxes, leaf_test)) {}
BoxTree::~BoxTree() = default;

void BoxTree::segment_query(const Vec3& from, const Vec3& to, void* visit, Callback callback) const {
  Reporting<Kernel::Segment_3, Callback> reporting(impl_->tree.traits(), impl_->boxes, impl_->leaf_test,
                                                   segment_box(from, to), visit, callback);
  impl_->tree.traversal(Kernel::Segment_3(point_3(from), point_3(to)), reporting);
}

void BoxTree::ray_query(const Vec3& from, const Vec3& direction, void* visit, Callback callback) const {
  Reporting<Kernel::Ray_3, Callback> reporting(impl_->tree.traits(), impl_->boxes, impl_->leaf_test,
                                               ray_box(from, direction), visit, callback);
  impl_->tree.traversal(Kernel::Ray_3(point_3(from), Kernel::Direction_3(direction[0], direction[1], direction[2])),
                        reporting);
}

void BoxTree::dilated_segment_query(const Vec3& from, const Vec3& to, const Vec3& slack, void* visit,
                                    Callback callback) const {
  const Slab slab(from, {to[0] - from[0], to[1] - from[1], to[2] - from[2]}, 1.0, slack);
  SlabTraversal<Callback> traversal(impl_->boxes, slab, nullptr, visit, callback);
  impl_->tree.traversal(SlabQuery{}, traversal);
}

void BoxTree::dilated_ray_query(const Vec3& from, const Vec3& direction, const Vec3& slack, void* visit,
                                Callback callback) const {
  const Slab slab(from, direction, std::numeric_limits<double>::infinity(), slack);
  SlabTraversal<Callback> traversal(impl_->boxes, slab, nullptr, visit, callback);
  impl_->tree.traversal(SlabQuery{}, traversal);
}

void BoxTree::nearest_first_ray_query(const Vec3& from, const Vec3& direction, const double* bound, void* visit,
                                      Callback callback) const {
  if (direction[0] == 0.0 && direction[1] == 0.0 && direction[2] == 0.0)
    throw std::invalid_argument("BoxTree::nearest_first_ray_query: zero direction");
  const Slab slab(from, direction, std::numeric_limits<double>::infinity(), Vec3{});
  SlabTraversal<Callback> traversal(impl_->boxes, slab, bound, visit, callback);
  impl_->tree.traversal_with_priority(SlabQuery{}, traversal);
}

}  // namespace shadowcert::detail
