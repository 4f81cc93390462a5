// BoxTree of exact/box_tree.h: a binary bounding-volume hierarchy of its own (flat arrays, both
// children's boxes stored in their parent, binned SAH build in parallel, leaves of at most
// kLeafSize boxes), traversed with an explicit stack. Replaces CGAL's AABB tree (issue 24: the
// tree queries were half of the exact image's time): the queries report the same boxes (every
// box the query meets; the exact queries exactly those), only faster.
//
// Node tests are conservative slab tests in plain double arithmetic with a certified bound on
// their rounding errors (class Slab below); a leaf box of an exact query (LeafTest::exact) is
// then decided exactly by CGAL's filtered Do_intersect_3 (Epick) on the doubles.
#include "exact/box_tree.h"

#include "core/huge_page_advice.h"
#include "core/outward_float.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace shadowcert::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A node's or a box's bounds, closed: lo[k] <= x[k] <= hi[k].
struct Bounds {
  std::array<double, 3> lo{kInfinity, kInfinity, kInfinity};
  std::array<double, 3> hi{-kInfinity, -kInfinity, -kInfinity};

  void grow(const Bounds& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], b.lo[k]);
      hi[k] = std::max(hi[k], b.hi[k]);
    }
  }
  void grow(const std::array<double, 3>& p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  // Half the surface area (the SAH's cost weight); 0 for an empty box.
  [[nodiscard]] double half_area() const {
    const double x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
    if (!(x >= 0.0 && y >= 0.0 && z >= 0.0)) return 0.0;
    return x * y + y * z + z * x;
  }
};

// A child of an inner node: an inner node's index (count == 0) or a leaf, boxes
// [first, first + count) of the tree's leaf order.
// Trivial (no member initialisers): the traversal stacks of them are left uninitialised (zeroing
// 2-4 KiB of stack per query cost a sixth of the traversal).
struct Child {
  std::uint32_t index;
  std::uint32_t count;
};

// An inner node: its two children's boxes, axis by axis, child 0 and child 1 side by side (so
// that one slab test runs on both children in the two lanes of a vector register).
struct Node {
  std::array<std::array<double, 2>, 3> lo;
  std::array<std::array<double, 2>, 3> hi;
  std::array<Child, 2> child;

  [[nodiscard]] Bounds box(int side) const {
    Bounds b;
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = lo[k][side];
      b.hi[k] = hi[k][side];
    }
    return b;
  }
  void set_box(int side, const Bounds& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k][side] = b.lo[k];
      hi[k][side] = b.hi[k];
    }
  }
};

// The tree as the queries walk it when its boxes and the query are moderate (kTame32 below): the
// binary tree collapsed to nodes of up to 4 children (each binary node's children, the larger
// inner ones replaced by theirs), their boxes rounded outward to floats, axis by axis, child k in
// lane k, so that one slab test runs on all four in a 4-lane float register. Half the nodes to
// visit and half the bytes per child: the traversal was a third of the exact image's time.
struct Node4 {
  using Lanes = float __attribute__((vector_size(16)));
  std::array<Lanes, 3> lo;
  std::array<Lanes, 3> hi;
  std::array<Child, 4> child;
  std::uint32_t size = 0;  // children in lanes [0, size)
};

// Where the float test applies: box coordinates, the query's origin and slack, and its inverse
// directions within 2^40 in magnitude (and the inverses at least 2^-100, so that none rounds to
// a float zero or loses its relative precision to underflow): every difference stays below
// 2^41, every product below 2^81 and every sum below 2^84, far from float's 2^128.
inline constexpr double kTame32 = 0x1p40;
inline constexpr double kTinyInverse32 = 0x1p-100;

// Where every value of a slab test stays far from overflow: box coordinates, query origins and
// slacks, and inverse directions all within 2^400 in magnitude, so every product and sum of the
// test is finite (below 2^803) and the general test's non-finite cases cannot arise.
inline constexpr double kTame = 0x1p400;
[[nodiscard]] inline bool tame(double x) { return std::fabs(x) <= kTame; }

// A box during the build and its id; the build partitions these records themselves, so that
// every pass reads them in order. The box's centre (rounded: it only orders the splits, never
// decides a query) is computed where it is read, not stored: 56 bytes a record, not 80, for
// passes that stream the records.
struct Primitive {
  Bounds box;
  std::uint32_t id;
  // The node's binning pass leaves here the box's bin, which its partition then reads.
  std::uint32_t bin;

  [[nodiscard]] double centre(int axis) const { return box.lo[axis] / 2 + box.hi[axis] / 2; }
  [[nodiscard]] std::array<double, 3> centre() const { return {centre(0), centre(1), centre(2)}; }
};

inline constexpr std::uint32_t kLeafSize = 4;
inline constexpr int kBins = 12;
// Past this depth the build splits at the median (depth below 2 * 48 + log2 n).
inline constexpr int kMaxSahDepth = 48;
// The grain of the parallel loops over every box (filling the build's records, copying them out).
inline constexpr std::uint32_t kParallelFill = 16384;
// Below this many boxes a subtree is built on the calling thread.
inline constexpr std::uint32_t kParallelBuild = 4096;

// A conservative slab test for every query: the line piece from + t v, t in [0, t_max] (a ray:
// v its direction, t_max = infinity; a segment: v = to - from, t_max = 1) against a box
// dilated by `slack` (0 for the plain and nearest-first queries). It answers "may meet" for
// every box the exact piece meets, in plain double arithmetic (no rounding-mode switch, the
// inner loop of every query), by bounding each rounding error as in
// exact/light_orientation_filter.h:
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
  Slab(const Vec3& from, const Vec3& v, double t_max, const Vec3& slack) : t_max_(t_max) {
    for (int k = 0; k < 3; ++k) {
      from_[k] = from[k];
      slack_[k] = slack[k];
      parallel_[k] = v[k] == 0.0;
      const double inv = v[k] != 0.0 ? 1.0 / v[k] : 0.0;
      free_[k] = !parallel_[k] && !std::isfinite(inv);
      inverse_[k] = inv;
      forward_[k] = inv > 0.0;
      widen_[k] = slack[k] * std::fabs(inv);
      fast_ = fast_ && !parallel_[k] && !free_[k] && tame(inv) && tame(from[k]) && tame(slack[k]);
    }
    // The float query (entry4): from rounded to float, the slack widened by that rounding and
    // rounded up, the inverse direction rounded to float (an error the margin covers); its
    // widening slack32 |inv32| is formed in the test, as in the double one.
    // No libm call here (once per query): each upper bound is a product by 1 + 2^-50 (double) or
    // 1 + 2^-22 (float) plus a tiny absolute term, more than the one rounding it covers.
    fast32_ = fast_;
    for (int k = 0; k < 3 && fast32_; ++k) {
      const double inv = inverse_[k];
      fast32_ = std::fabs(from[k]) <= kTame32 && slack[k] <= kTame32 && std::fabs(inv) <= kTame32 &&
                std::fabs(inv) >= kTinyInverse32;
      if (!fast32_) break;
      // Through a volatile, as core/float_rounding.h: the difference below must see the float.
      const volatile float rounded = static_cast<float>(from[k]);
      from32_[k] = rounded;
      // |from - from32| (exact, or within its own rounding, which the factor covers).
      const double moved = std::fabs(from[k] - static_cast<double>(from32_[k]));
      const double slack32 = (slack[k] + moved) * (1.0 + 0x1p-50) + 0x1p-1000;
      inverse32_[k] = static_cast<float>(inv);
      widen32_[k] = (static_cast<float>(slack32) * (1.0f + 0x1p-22f) + 0x1p-120f) * std::fabs(inverse32_[k]);
    }
    t_max32_ = t_max == kInfinity ? std::numeric_limits<float>::infinity()
                                  : static_cast<float>(t_max) * (1.0f + 0x1p-22f) + 0x1p-120f;
  }

  // false when the piece certainly misses b (dilated); else true with *enter a lower bound of
  // the parameter where it enters.
  // Both children of `node` at once: in[c] and t[c] as entry(node.box(c)). Valid only when
  // fast() and the tree is tame: then every axis has a finite nonzero inverse and no value of
  // the test can overflow, so the general test's special cases never apply and this is the
  // same computation, without branches (vectorised over the two children).
  void entry_pair(const Node& node, std::array<bool, 2>& in, std::array<double, 2>& t) const {
    // GCC/Clang vector extensions: the two children in the two lanes of one register.
    using Pair = double __attribute__((vector_size(16)));
    const auto load = [](const std::array<double, 2>& x) { return Pair{x[0], x[1]}; };
    const auto abs = [](Pair x) { return x < 0.0 ? -x : x; };
    Pair enter{0.0, 0.0}, leave{t_max_, t_max_};
    for (int k = 0; k < 3; ++k) {
      const Pair near_side = load(forward_[k] ? node.lo[k] : node.hi[k]);
      const Pair far_side = load(forward_[k] ? node.hi[k] : node.lo[k]);
      const double f = from_[k], inv = inverse_[k], widen = widen_[k];
      const Pair a_near = (near_side - f) * inv, a_far = (far_side - f) * inv;
      const Pair near = a_near - widen, far = a_far + widen;
      const Pair near_margin = (abs(a_near) + widen + abs(near)) * kSlabRelativeMargin + kSlabAbsoluteMargin;
      const Pair far_margin = (abs(a_far) + widen + abs(far)) * kSlabRelativeMargin + kSlabAbsoluteMargin;
      const Pair near_bound = near - near_margin, far_bound = far + far_margin;
      enter = near_bound > enter ? near_bound : enter;
      leave = far_bound < leave ? far_bound : leave;
    }
    for (int c = 0; c < 2; ++c) {
      in[c] = enter[c] <= leave[c];
      t[c] = enter[c];
    }
  }
  // One box as entry(b), under entry_pair's conditions (fast() and a tame tree): no branch.
  [[nodiscard]] bool entry_fast(const Bounds& b, double* enter_out) const {
    double enter = 0.0, leave = t_max_;
    for (int k = 0; k < 3; ++k) {
      const double f = from_[k], inv = inverse_[k], widen = widen_[k];
      const double a_near = ((forward_[k] ? b.lo[k] : b.hi[k]) - f) * inv;
      const double a_far = ((forward_[k] ? b.hi[k] : b.lo[k]) - f) * inv;
      const double near = a_near - widen, far = a_far + widen;
      const double near_margin = (std::fabs(a_near) + widen + std::fabs(near)) * kSlabRelativeMargin + kSlabAbsoluteMargin;
      const double far_margin = (std::fabs(a_far) + widen + std::fabs(far)) * kSlabRelativeMargin + kSlabAbsoluteMargin;
      enter = std::max(enter, near - near_margin);
      leave = std::min(leave, far + far_margin);
    }
    *enter_out = enter;
    return !(enter > leave);
  }

  // Whether entry_pair applies (given a tame tree): no axis parallel or overflowing, every
  // input within kTame.
  [[nodiscard]] bool fast() const { return fast_; }

  // Whether entry4 applies (given a tree within kTame32): fast(), and the query's float
  // rounding within kTame32 (see the constructor).
  [[nodiscard]] bool fast32() const { return fast32_; }

  // The four children of `node` at once in float arithmetic: bit c of the result set where the
  // piece may meet child c's box (dilated), t[c] then a lower bound of its entry parameter.
  // The query runs from from32 (from rounded to float) with its slack widened by that rounding
  // (slack32: the dilated piece from from32 holds the one from `from`), against boxes rounded
  // outward; each slab parameter A = fl(fl(x - f) * inv) carries three roundings of relative
  // error u = 2^-24 (inv = fl32(fl(1 / v)) one of them), B = fl(s * |inv|) two, T = A -+ B one:
  // the margin (|A| + B + |T|) 2^-20 (16 u per term) plus 2^-120 (far above any underflow's
  // 2^-149) covers them and its own rounding, as the double test's margin does.
  [[nodiscard]] unsigned entry4(const Node4& node, std::array<double, 4>& t) const {
    using Lanes = Node4::Lanes;
    const auto abs = [](Lanes x) { return x < 0.0f ? -x : x; };
    constexpr float kRelative = 0x1p-20f, kAbsolute = 0x1p-120f;
    Lanes enter{0.0f, 0.0f, 0.0f, 0.0f};
    Lanes leave{t_max32_, t_max32_, t_max32_, t_max32_};
    for (int k = 0; k < 3; ++k) {
      const Lanes near_side = forward_[k] ? node.lo[k] : node.hi[k];
      const Lanes far_side = forward_[k] ? node.hi[k] : node.lo[k];
      const float f = from32_[k], inv = inverse32_[k], widen = widen32_[k];
      const Lanes a_near = (near_side - f) * inv, a_far = (far_side - f) * inv;
      const Lanes near = a_near - widen, far = a_far + widen;
      const Lanes near_margin = (abs(a_near) + widen + abs(near)) * kRelative + kAbsolute;
      const Lanes far_margin = (abs(a_far) + widen + abs(far)) * kRelative + kAbsolute;
      const Lanes near_bound = near - near_margin, far_bound = far + far_margin;
      enter = near_bound > enter ? near_bound : enter;
      leave = far_bound < leave ? far_bound : leave;
    }
    unsigned mask = 0;
    for (int c = 0; c < 4; ++c) {
      t[static_cast<std::size_t>(c)] = enter[c];
      mask |= enter[c] <= leave[c] ? 1u << c : 0u;
    }
    return mask;
  }

  [[nodiscard]] bool entry(const Bounds& b, double* enter_out) const {
    double enter = 0.0;
    double leave = t_max_;
    for (int k = 0; k < 3; ++k) {
      const double lo = b.lo[k], hi = b.hi[k], s = slack_[k];
      if (parallel_[k]) {
        // Parallel to the slab: certainly outside when lo - from_k > s (or from_k - hi > s);
        // fl(lo - from_k) (1 - 2^-50) is below lo - from_k for a positive difference.
        if ((lo - from_[k]) * (1.0 - kSlabRelativeMargin) > s || (from_[k] - hi) * (1.0 - kSlabRelativeMargin) > s)
          return false;
        continue;
      }
      if (free_[k]) continue;
      const double inv = inverse_[k];
      const double a_lo = (lo - from_[k]) * inv, a_hi = (hi - from_[k]) * inv, widen = widen_[k];
      const double a_near = forward_[k] ? a_lo : a_hi, a_far = forward_[k] ? a_hi : a_lo;
      const double near = a_near - widen, far = a_far + widen;
      const double near_margin = (std::fabs(a_near) + widen + std::fabs(near)) * kSlabRelativeMargin + kSlabAbsoluteMargin;
      const double far_margin = (std::fabs(a_far) + widen + std::fabs(far)) * kSlabRelativeMargin + kSlabAbsoluteMargin;
      const double near_bound = near - near_margin, far_bound = far + far_margin;
      if (std::isfinite(near_bound)) enter = std::max(enter, near_bound);
      if (std::isfinite(far_bound)) leave = std::min(leave, far_bound);
    }
    if (enter > leave) return false;
    *enter_out = enter;
    return true;
  }

 private:
  std::array<double, 3> from_{};
  std::array<double, 3> slack_{};
  std::array<double, 3> inverse_{};
  std::array<double, 3> widen_{};
  std::array<bool, 3> parallel_{};
  std::array<bool, 3> free_{};
  std::array<bool, 3> forward_{};
  double t_max_;
  bool fast_ = true;
  std::array<float, 3> from32_{};
  std::array<float, 3> inverse32_{};
  std::array<float, 3> widen32_{};
  float t_max32_ = 0.0f;
  bool fast32_ = false;
};

CGAL::Bbox_3 bbox(const Bounds& b) { return {b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]}; }
Kernel::Point_3 point_3(const Vec3& p) { return {p[0], p[1], p[2]}; }

}  // namespace

// A traversal's pending subtrees with the parameter where the query enters each: a fixed array
// (left uninitialised: Child is trivial) with a vector beyond it for the rare deeper tree, last
// in, first out across both.
struct TraversalEntry {
  Child child;
  double t;
};

template <std::size_t N>
class TraversalStack {
 public:
  void push(const TraversalEntry& e) {
    if (top_ < fixed_.size()) {
      fixed_[top_++] = e;
    } else {
      overflow_.push_back(e);
    }
  }
  // The last pushed entry into *e; false when none is left.
  bool pop(TraversalEntry* e) {
    if (!overflow_.empty()) {
      *e = overflow_.back();
      overflow_.pop_back();
      return true;
    }
    if (top_ == 0) return false;
    *e = fixed_[--top_];
    return true;
  }

 private:
  std::array<TraversalEntry, N> fixed_;
  std::vector<TraversalEntry> overflow_;
  std::size_t top_ = 0;
};

struct BoxTree::Impl {
  LeafTest leaf_test;
  // The arrays are left uninitialised (HugePageBuffer): the build writes every entry before it
  // is read, and huge pages it never reaches (the binary tree's array is sized for the worst
  // case, n - 1 inner nodes) are never faulted in. On ogre's 124K boxes that cut the build's
  // page faults from about 1,300-2,300 to 165, and its growth of the resident set from 25 MB to 19.
  // The build's records as it left them, in leaf order: each box and the caller's id of it
  // (kept, not copied into arrays of boxes and ids: 6.5 MB less of fresh memory on ogre, whose
  // first touch was most of that copy's cost, and a box's id in its cache line).
  HugePageBuffer<Primitive> leaves;
  HugePageBuffer<std::uint32_t> leaf_of;  // leaf_of[id]: where box id lies in leaf order
  HugePageBuffer<Node> nodes;         // the binary tree (freed once collapsed into nodes4)
  std::uint32_t node_count = 0;       // the inner nodes built, nodes[0, node_count)
  Bounds root_box;
  Child root{};                       // count == 0 and no nodes: empty
  bool tame = true;                   // every box coordinate within kTame (Slab::entry_pair)
  HugePageBuffer<Node4> nodes4;       // the same tree, 4 children per node (Node4)
  Child root4{};
  bool tame32 = false;                // every box coordinate within kTame32 (Slab::entry4)

  Impl(const std::vector<Box>& closed, LeafTest test);

  // Builds the subtree over boxes [first, first + count) of `order`, with the bounds of their
  // boxes and of their centres, and returns it as a child.
  Child build(std::uint32_t first, std::uint32_t count, const Bounds& centres, Primitive* prims,
              std::atomic<std::uint32_t>& next_node, int depth);

  // The collapse into nodes4, in parallel: count4 stores in counts[i] the number of Node4s the
  // subtree of binary inner node i becomes (and returns it); fill4 writes that subtree's Node4s
  // depth-first from nodes4[at].
  std::uint32_t count4(std::uint32_t index, std::vector<std::uint32_t>& counts, int depth) const;
  void fill4(std::uint32_t index, std::uint32_t at, const std::vector<std::uint32_t>& counts);

  // Visits the leaves whose boxes the slab may meet, nearest-first with a bound when `bound` is
  // set; `leaf(first, count)` returns false to stop. In floats over nodes4 where both the tree
  // and the query allow it (traverse4), else in doubles over the binary nodes.
  template <typename Leaf>
  void traverse(const Slab& slab, const double* bound, Leaf&& leaf) const;
  template <typename Leaf>
  void traverse4(const Slab& slab, double t, const double* bound, Leaf&& leaf) const;
};

BoxTree::Impl::Impl(const std::vector<Box>& closed, LeafTest test) : leaf_test(test) {
  if (closed.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("BoxTree: more than 2^32 boxes");
  const auto n = static_cast<std::uint32_t>(closed.size());
  if (n == 0) return;
  // The build's records on huge pages (core/huge_page_advice.h), as every array of the tree: a
  // 124K-box tree spent a third of its build in first-touch page faults.
  HugePageBuffer<Primitive> prims(n);
  // Filled in parallel: the first touch of the records' fresh pages (a page fault each) is most
  // of this loop's time, and is then shared by the threads.
  struct Extent {
    Bounds boxes, centres;
  };
  const Extent extent = tbb::parallel_reduce(
      tbb::blocked_range<std::uint32_t>(0, n, kParallelFill), Extent{},
      [&](const tbb::blocked_range<std::uint32_t>& r, Extent e) {
        for (std::uint32_t i = r.begin(); i != r.end(); ++i) {
          Primitive& p = prims[i];
          for (int k = 0; k < 3; ++k) {
            p.box.lo[k] = closed[i].lo[k];
            p.box.hi[k] = closed[i].hi[k];
          }
          p.id = i;
          p.bin = 0;
          e.boxes.grow(p.box);
          e.centres.grow(p.centre());
        }
        return e;
      },
      [](Extent a, const Extent& b) {
        a.boxes.grow(b.boxes);
        a.centres.grow(b.centres);
        return a;
      });
  root_box = extent.boxes;
  const Bounds& centres = extent.centres;
  nodes = HugePageBuffer<Node>(n);  // a binary tree over n >= 1 leaves has fewer than n inner nodes
  std::atomic<std::uint32_t> next_node{0};
  root = build(0, n, centres, prims.data(), next_node, 0);
  node_count = next_node.load();
  leaves = std::move(prims);
  leaf_of = HugePageBuffer<std::uint32_t>(n);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, n, kParallelFill), [&](const tbb::blocked_range<std::uint32_t>& r) {
    for (std::uint32_t i = r.begin(); i != r.end(); ++i) leaf_of[leaves[i].id] = i;
  });
  for (int k = 0; k < 3; ++k) tame = tame && shadowcert::detail::tame(root_box.lo[k]) && shadowcert::detail::tame(root_box.hi[k]);
  tame32 = true;
  for (int k = 0; k < 3; ++k)
    tame32 = tame32 && std::fabs(root_box.lo[k]) <= kTame32 && std::fabs(root_box.hi[k]) <= kTame32;
  if (tame32) {  // the binary nodes only serve the collapse
    if (root.count != 0) {
      root4 = root;
    } else {
      std::vector<std::uint32_t> counts(node_count);
      nodes4 = HugePageBuffer<Node4>(count4(root.index, counts, 0));
      fill4(root.index, 0, counts);
      root4 = {0, 0};
    }
    nodes = HugePageBuffer<Node>();
    node_count = 0;
  }
}

// The children of a Node4 over binary inner node `index`: its two, the inner one of largest area
// opened into its two children while fewer than 4.
struct Node4Entries {
  std::array<Child, 4> child;
  std::array<Bounds, 4> box;
  std::size_t size = 0;
};

Node4Entries node4_entries(const Node* nodes, std::uint32_t index) {
  Node4Entries e;
  const Node& top = nodes[index];
  e.child = {top.child[0], top.child[1]};
  e.box[0] = top.box(0);
  e.box[1] = top.box(1);
  e.size = 2;
  while (e.size < 4) {
    std::size_t open = e.size;
    double area = -1.0;
    for (std::size_t i = 0; i < e.size; ++i)
      if (e.child[i].count == 0 && e.box[i].half_area() > area) {
        open = i;
        area = e.box[i].half_area();
      }
    if (open == e.size) break;
    const Node& inner = nodes[e.child[open].index];
    e.child[e.size] = inner.child[1];
    e.box[e.size++] = inner.box(1);
    e.child[open] = inner.child[0];
    e.box[open] = inner.box(0);
  }
  return e;
}

// Below this many Node4s a subtree is counted or filled on the calling thread.
inline constexpr std::uint32_t kParallelCollapse = 2048;

std::uint32_t BoxTree::Impl::count4(std::uint32_t index, std::vector<std::uint32_t>& counts, int depth) const {
  const Node4Entries e = node4_entries(nodes.data(), index);
  std::array<std::uint32_t, 4> sub{};
  const auto count_child = [&](std::size_t i) {
    if (i < e.size && e.child[i].count == 0) sub[i] = count4(e.child[i].index, counts, depth + 1);
  };
  if (depth < 6) {  // the top levels' subtrees side by side (their sizes are not known yet)
    tbb::parallel_invoke([&] { count_child(0); }, [&] { count_child(1); }, [&] { count_child(2); },
                         [&] { count_child(3); });
  } else {
    for (std::size_t i = 0; i < e.size; ++i) count_child(i);
  }
  return counts[index] = 1 + sub[0] + sub[1] + sub[2] + sub[3];
}

void BoxTree::Impl::fill4(std::uint32_t index, std::uint32_t at, const std::vector<std::uint32_t>& counts) {
  const Node4Entries e = node4_entries(nodes.data(), index);
  Node4& node = nodes4[at];
  node.size = static_cast<std::uint32_t>(e.size);
  std::array<std::uint32_t, 4> first{};  // where each inner child's subtree goes (depth-first order)
  std::uint32_t next = at + 1;
  for (std::size_t i = 0; i < e.size; ++i) {
    first[i] = next;
    if (e.child[i].count == 0) next += counts[e.child[i].index];
  }
  for (std::size_t i = 0; i < 4; ++i) {
    const std::size_t c = std::min(i, e.size - 1);  // unused lanes repeat a child (masked)
    node.child[i] = e.child[c].count != 0 ? e.child[c] : Child{first[c], 0};
    for (int k = 0; k < 3; ++k) {
      node.lo[k][i] = round_down_to_float(e.box[c].lo[k]);
      node.hi[k][i] = round_up_to_float(e.box[c].hi[k]);
    }
  }
  const auto fill_child = [&](std::size_t i) {
    if (i < e.size && e.child[i].count == 0) fill4(e.child[i].index, first[i], counts);
  };
  if (counts[index] >= kParallelCollapse) {
    tbb::parallel_invoke([&] { fill_child(0); }, [&] { fill_child(1); }, [&] { fill_child(2); },
                         [&] { fill_child(3); });
  } else {
    for (std::size_t i = 0; i < e.size; ++i) fill_child(i);
  }
}

Child BoxTree::Impl::build(std::uint32_t first, std::uint32_t count, const Bounds& centres,
                           Primitive* prims, std::atomic<std::uint32_t>& next_node, int depth) {
  if (count <= kLeafSize) return {first, count};
  Primitive* const begin = prims + first;
  Primitive* const end = begin + count;
  // Binned SAH on the centres along their longest axis; the cheapest split wins, and its sides'
  // boxes come from the bins. Past kMaxSahDepth (centres spread so unevenly that the SAH keeps
  // cutting off a few boxes) the median of the longest axis, so that the depth stays
  // logarithmic. One axis at every node: binning all three at nodes of up to 256 boxes took a
  // quarter of the build (ogre's 124K boxes: 49-52 -> 37-41 ms on one thread) and made no query
  // of the exact image measurably faster (docs/diff.md, "A lighter tree stage").
  std::uint32_t middle = first + count / 2;
  std::array<Bounds, 2> side_box, centre_box;
  bool sides_known = false;  // side_box from the bins
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (centres.hi[k] - centres.lo[k] > centres.hi[axis] - centres.lo[axis]) axis = k;
  const double extent = centres.hi[axis] - centres.lo[axis];
  const double scale = extent > 0.0 && std::isfinite(kBins / extent) ? kBins / extent : 0.0;
  if (depth < kMaxSahDepth && scale > 0.0) {
    // Each bin's box and count, for the SAH; the sides' centre bounds (which only scale the
    // children's bins) come from the partition below.
    struct Bin {
      Bounds box;
      std::uint32_t count = 0;
    };
    std::array<Bin, kBins> bins{};
    for (auto it = begin; it != end; ++it) {
      // Clamped in double before the conversion: a difference that overflows (coordinates near
      // the double range) or an inf * 0 would make the cast undefined; a NaN clamps to 0. As
      // conditionals of this form (maxsd, minsd: no branch on the box's side of the split).
      const double x = (it->centre(axis) - centres.lo[axis]) * scale;
      const double above = x > 0.0 ? x : 0.0;
      const double clamped = above < static_cast<double>(kBins - 1) ? above : static_cast<double>(kBins - 1);
      const auto b = static_cast<std::uint32_t>(clamped);
      bins[b].box.grow(it->box);
      ++bins[b].count;
      it->bin = b;
    }
    int best_bin = -1;
    double best_cost = kInfinity;
    std::array<double, kBins> right_cost{};
    Bounds right;
    std::uint32_t right_count = 0;
    for (int b = kBins - 1; b > 0; --b) {
      right.grow(bins[b].box);
      right_count += bins[b].count;
      right_cost[b] = right.half_area() * right_count;
    }
    Bounds left;
    std::uint32_t left_count = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      left.grow(bins[b].box);
      left_count += bins[b].count;
      const double cost = left.half_area() * left_count + right_cost[b + 1];
      if (left_count > 0 && left_count < count && cost < best_cost) {
        best_cost = cost;
        best_bin = b;
      }
    }
    if (best_bin >= 0) {
      // A partition by the chosen bin (as binned) that also bounds each side's centres: each
      // record is read once here, not once more after the split.
      const auto left_side = [&](const Primitive& p) { return static_cast<int>(p.bin) <= best_bin; };
      Primitive* lo = begin;
      Primitive* hi = end;
      for (;;) {
        while (lo < hi && left_side(*lo)) centre_box[0].grow((lo++)->centre());
        while (lo < hi && !left_side(*(hi - 1))) centre_box[1].grow((--hi)->centre());
        if (hi - lo < 2) break;
        std::swap(*lo, *(hi - 1));
      }
      middle = static_cast<std::uint32_t>(lo - prims);
      for (int b = 0; b < kBins; ++b) side_box[b <= best_bin ? 0 : 1].grow(bins[b].box);
      sides_known = true;
    }
  } else if (scale > 0.0) {
    std::nth_element(begin, prims + middle, end,
                     [axis](const Primitive& a, const Primitive& b) { return a.centre(axis) < b.centre(axis); });
  }
  // Every centre alike (or the median split): halves by count, their boxes and centres by one
  // pass.
  if (!sides_known) {
    if (middle == first || middle == first + count) middle = first + count / 2;
    for (std::uint32_t i = first; i < first + count; ++i) {
      const int side = i < middle ? 0 : 1;
      side_box[side].grow(prims[i].box);
      centre_box[side].grow(prims[i].centre());
    }
  }

  const std::uint32_t index = next_node.fetch_add(1);
  Node& node = nodes[index];
  node.set_box(0, side_box[0]);
  node.set_box(1, side_box[1]);
  const auto left = [&] { node.child[0] = build(first, middle - first, centre_box[0], prims, next_node, depth + 1); };
  const auto right = [&] {
    node.child[1] = build(middle, first + count - middle, centre_box[1], prims, next_node, depth + 1);
  };
  if (count >= kParallelBuild) {
    tbb::parallel_invoke(left, right);
  } else {
    left();
    right();
  }
  return {index, 0};
}

template <typename Leaf>
void BoxTree::Impl::traverse(const Slab& slab, const double* bound, Leaf&& leaf) const {
  if (leaves.size() == 0) return;
  double t = 0.0;
  if (!slab.entry(root_box, &t) || (bound != nullptr && t > *bound)) return;
  if (tame32) {
    traverse4(slab, t, bound, leaf);
    return;
  }
  using Entry = TraversalEntry;
  TraversalStack<128> stack;  // depth <= 2 log2(n) for the SAH splits
  Entry current{root, t};
  const bool fast = tame && slab.fast();
  for (;;) {
    if (bound == nullptr || current.t <= *bound) {
      if (current.child.count != 0) {
        if (!leaf(current.child.index, current.child.count)) return;
      } else {
        const Node& node = nodes[current.child.index];
        std::array<bool, 2> in{};
        std::array<double, 2> ts{};
        if (fast) {
          slab.entry_pair(node, in, ts);
        } else {
          in[0] = slab.entry(node.box(0), &ts[0]);
          in[1] = slab.entry(node.box(1), &ts[1]);
        }
        const double t0 = ts[0], t1 = ts[1];
        const bool in0 = in[0] && (bound == nullptr || t0 <= *bound);
        const bool in1 = in[1] && (bound == nullptr || t1 <= *bound);
        if (in0 && in1) {
          // The nearer first; the other waits on the stack.
          const bool first_near = t0 <= t1;
          stack.push(first_near ? Entry{node.child[1], t1} : Entry{node.child[0], t0});
          current = first_near ? Entry{node.child[0], t0} : Entry{node.child[1], t1};
          continue;
        }
        if (in0 || in1) {
          current = in0 ? Entry{node.child[0], t0} : Entry{node.child[1], t1};
          continue;
        }
      }
    }
    if (!stack.pop(&current)) return;
  }
}

template <typename Leaf>
void BoxTree::Impl::traverse4(const Slab& slab, double t, const double* bound, Leaf&& leaf) const {
  using Entry = TraversalEntry;
  TraversalStack<256> stack;  // up to 3 per level
  Entry current{root4, t};
  const bool fast = slab.fast32();
  for (;;) {
    if (bound == nullptr || current.t <= *bound) {
      if (current.child.count != 0) {
        if (!leaf(current.child.index, current.child.count)) return;
      } else {
        const Node4& node = nodes4[current.child.index];
        std::array<double, 4> ts{};
        unsigned mask = 0;
        if (fast) {
          mask = slab.entry4(node, ts) & ((1u << node.size) - 1u);
        } else {
          // A query the float test does not cover: the general double test on each child's
          // float box (exactly a double box, holding the child's own).
          for (std::uint32_t c = 0; c < node.size; ++c) {
            Bounds b;
            for (int k = 0; k < 3; ++k) {
              b.lo[k] = node.lo[k][c];
              b.hi[k] = node.hi[k][c];
            }
            if (slab.entry(b, &ts[c])) mask |= 1u << c;
          }
        }
        if (bound == nullptr) {
          // Unbounded (every box met is reported): no order to keep, the children as they come.
          if (mask == 0) {
            if (!stack.pop(&current)) return;
            continue;
          }
          auto c = static_cast<std::size_t>(__builtin_ctz(mask));
          for (mask &= mask - 1; mask != 0; mask &= mask - 1) {
            stack.push({node.child[c], ts[c]});
            c = static_cast<std::size_t>(__builtin_ctz(mask));
          }
          current = {node.child[c], ts[c]};
          continue;
        }
        std::array<Entry, 4> met;
        std::size_t count = 0;
        for (; mask != 0; mask &= mask - 1) {
          const auto c = static_cast<std::size_t>(__builtin_ctz(mask));
          const double tc = ts[c];
          if (bound != nullptr && tc > *bound) continue;
          // Nearest last: the farther ones wait on the stack, the nearest is visited next.
          std::size_t i = count++;
          for (; i > 0 && met[i - 1].t < tc; --i) met[i] = met[i - 1];
          met[i] = {node.child[c], tc};
        }
        if (count > 0) {
          for (std::size_t i = 0; i + 1 < count; ++i) stack.push(met[i]);
          current = met[count - 1];
          continue;
        }
      }
    }
    if (!stack.pop(&current)) return;
  }
}

BoxTree::BoxTree(const std::vector<Box>& boxes, LeafTest leaf_test)
    : impl_(std::make_unique<Impl>(boxes, leaf_test)) {}
BoxTree::~BoxTree() = default;

void BoxTree::segment_query(const Vec3& from, const Vec3& to, void* visit, Callback callback) const {
  const Impl& tree = *impl_;
  const Slab slab(from, {to[0] - from[0], to[1] - from[1], to[2] - from[2]}, 1.0, Vec3{});
  const Kernel::Segment_3 segment(point_3(from), point_3(to));
  tree.traverse(slab, nullptr, [&](std::uint32_t first, std::uint32_t count) {
    for (std::uint32_t i = first; i < first + count; ++i) {
      double t = 0.0;
      if (!slab.entry(tree.leaves[i].box, &t)) continue;
      if (tree.leaf_test == LeafTest::exact && !CGAL::do_intersect(segment, bbox(tree.leaves[i].box))) continue;
      if (!callback(visit, tree.leaves[i].id)) return false;
    }
    return true;
  });
}

void BoxTree::ray_query(const Vec3& from, const Vec3& direction, void* visit, Callback callback) const {
  const Impl& tree = *impl_;
  const Slab slab(from, direction, kInfinity, Vec3{});
  const Kernel::Ray_3 ray(point_3(from), Kernel::Direction_3(direction[0], direction[1], direction[2]));
  tree.traverse(slab, nullptr, [&](std::uint32_t first, std::uint32_t count) {
    for (std::uint32_t i = first; i < first + count; ++i) {
      double t = 0.0;
      if (!slab.entry(tree.leaves[i].box, &t)) continue;
      if (tree.leaf_test == LeafTest::exact && !CGAL::do_intersect(ray, bbox(tree.leaves[i].box))) continue;
      if (!callback(visit, tree.leaves[i].id)) return false;
    }
    return true;
  });
}

namespace {

// The leaves' boxes a slab query may meet (at t <= *bound when bounded), each tested itself.
template <typename Tree>
void visit_slab(const Tree& tree, const Slab& slab, const double* bound, void* visit,
                bool (*callback)(void*, std::uint32_t)) {
  const bool fast = tree.tame && slab.fast();
  tree.traverse(slab, bound, [&](std::uint32_t first, std::uint32_t count) {
    for (std::uint32_t i = first; i < first + count; ++i) {
      double t = 0.0;
      const bool in = fast ? slab.entry_fast(tree.leaves[i].box, &t) : slab.entry(tree.leaves[i].box, &t);
      if (!in || (bound != nullptr && t > *bound)) continue;
      if (!callback(visit, tree.leaves[i].id)) return false;
    }
    return true;
  });
}

}  // namespace

void BoxTree::dilated_segment_query(const Vec3& from, const Vec3& to, const Vec3& slack, void* visit,
                                    Callback callback) const {
  const Slab slab(from, {to[0] - from[0], to[1] - from[1], to[2] - from[2]}, 1.0, slack);
  visit_slab(*impl_, slab, nullptr, visit, callback);
}

void BoxTree::dilated_segment_query(const Vec3& from, const Vec3& to, const Vec3& slack,
                                    std::span<const std::uint32_t> ids, void* visit, Callback callback) const {
  const Impl& tree = *impl_;
  const Slab slab(from, {to[0] - from[0], to[1] - from[1], to[2] - from[2]}, 1.0, slack);
  const bool fast = tree.tame && slab.fast();
  for (const std::uint32_t id : ids) {
    if (id >= tree.leaf_of.size())
      throw std::invalid_argument("BoxTree::dilated_segment_query: id " + std::to_string(id) + " of " +
                                  std::to_string(tree.leaf_of.size()) + " boxes");
    // The walk's own leaf test (visit_slab), on the listed boxes only.
    const Bounds& box = tree.leaves[tree.leaf_of[id]].box;
    double t = 0.0;
    if (!(fast ? slab.entry_fast(box, &t) : slab.entry(box, &t))) continue;
    if (!callback(visit, id)) return;
  }
}

void BoxTree::dilated_ray_query(const Vec3& from, const Vec3& direction, const Vec3& slack, void* visit,
                                Callback callback) const {
  const Slab slab(from, direction, kInfinity, slack);
  visit_slab(*impl_, slab, nullptr, visit, callback);
}

void BoxTree::nearest_first_ray_query(const Vec3& from, const Vec3& direction, const double* bound, void* visit,
                                      Callback callback) const {
  if (direction[0] == 0.0 && direction[1] == 0.0 && direction[2] == 0.0)
    throw std::invalid_argument("BoxTree::nearest_first_ray_query: zero direction");
  const Slab slab(from, direction, kInfinity, Vec3{});
  visit_slab(*impl_, slab, bound, visit, callback);
}

}  // namespace shadowcert::detail
