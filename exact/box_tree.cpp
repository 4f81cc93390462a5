#include "exact/box_tree.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <limits>
#include <stdexcept>

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

Kernel::Point_3 point_3(const Vec3& p) { return {p[0], p[1], p[2]}; }

}  // namespace

struct BoxTree::Impl {
  std::vector<CGAL::Bbox_3> boxes;
  LeafTest leaf_test;
  Tree tree;

  Impl(const std::vector<ClosedBox>& closed, LeafTest test) : leaf_test(test), tree(Traits(BoxMap{&boxes})) {
    if (closed.size() >= std::numeric_limits<std::uint32_t>::max())
      throw std::invalid_argument("BoxTree: more than 2^32 boxes");
    boxes.reserve(closed.size());
    std::vector<Vec3> centres;
    centres.reserve(closed.size());
    for (const ClosedBox& b : closed) {
      boxes.emplace_back(b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]);
      centres.push_back({(b.lo[0] + b.hi[0]) / 2, (b.lo[1] + b.hi[1]) / 2, (b.lo[2] + b.hi[2]) / 2});
    }
    if (boxes.empty()) return;
    const std::vector<std::uint32_t> order = morton_order(centres, bounding_box(centres));
    tree.insert(order.begin(), order.end(), &boxes);
    tree.build();  // now, not lazily on a first query: queries then run concurrently
  }
};

BoxTree::BoxTree(const std::vector<ClosedBox>& boxes, LeafTest leaf_test)
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

}  // namespace shadowcert::detail
