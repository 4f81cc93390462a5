#include "exact/triangle_soup_self_intersections.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace shadowcert {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle3 = Kernel::Triangle_3;

Point point(const Vec3& v) { return {v[0], v[1], v[2]}; }

// Box coordinates in float halve the memory that CGAL's box sweep streams through (measured:
// docs/caster-diagnostics.md). Any rounding of a double to a float is monotone (a <= b gives
// f(a) <= f(b)), so two boxes that overlap in doubles still overlap in floats and no pair is
// lost; the extra pairs that rounding may add are rejected by the exact test. Out-of-range
// conversions are undefined behaviour, hence the explicit (still monotone) clamps.
float monotone_float(double x) {
  constexpr double max = std::numeric_limits<float>::max();
  if (x > max) return std::numeric_limits<float>::infinity();
  if (x < -max) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(x);
}

// The axis-aligned box of one triangle, in the interface CGAL's box_intersection_d expects,
// carrying the triangle's indices so that the pair test does not fetch them again. Boxes
// are closed (CGAL::Box_intersection_d::CLOSED), so triangles touching at one point pair up.
struct TriangleBox {
  using NT = float;
  using ID = std::size_t;
  std::array<float, 3> lo;
  std::array<float, 3> hi;
  std::uint32_t triangle;
  Triangle corners;

  static int dimension() { return 3; }
  [[nodiscard]] float min_coord(int d) const { return lo[d]; }
  [[nodiscard]] float max_coord(int d) const { return hi[d]; }
  // The triangle index is unique, and CGAL uses the id only to report each pair once.
  [[nodiscard]] ID id() const { return triangle; }
};

TriangleBox box_of(const Soup& soup, std::uint32_t t) {
  const Triangle& tri = soup.triangles[t];
  TriangleBox box{};
  box.triangle = t;
  box.corners = tri;
  for (int d = 0; d < 3; ++d) {
    const double lo = std::min({soup.vertices[tri[0]][d], soup.vertices[tri[1]][d], soup.vertices[tri[2]][d]});
    const double hi = std::max({soup.vertices[tri[0]][d], soup.vertices[tri[1]][d], soup.vertices[tri[2]][d]});
    box.lo[d] = monotone_float(lo);
    box.hi[d] = monotone_float(hi);
  }
  return box;
}

std::vector<TriangleBox> boxes_of_proper_triangles(const Soup& soup, std::span<const TriangleShape> shapes) {
  std::vector<TriangleBox> boxes;
  boxes.reserve(soup.triangles.size());
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (shapes[t] == TriangleShape::Proper) boxes.push_back(box_of(soup, static_cast<std::uint32_t>(t)));
  return boxes;
}

// Which corners two triangles (with pairwise distinct indices each) have in common.
struct Sharing {
  int count = 0;
  std::array<int, 3> corner_in_a{};  // corner_in_a[i] is shared with corner_in_b[i], i < count
  std::array<int, 3> corner_in_b{};
};

Sharing sharing_of(const Triangle& a, const Triangle& b) {
  Sharing s;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) {
        s.corner_in_a[s.count] = i;
        s.corner_in_b[s.count] = j;
        ++s.count;
      }
  return s;
}

// The corner of a triangle that is neither c0 nor c1.
int third_corner(int c0, int c1) { return 3 - c0 - c1; }

// The coordinate axis along which triangle (p, q, r) projects largest, from a rounded
// normal. Only a choice of projection: every decision below stays an exact sign, and any
// axis would be correct (a degenerate projection just answers "don't know").
int dominant_axis(const Point& p, const Point& q, const Point& r) {
  const Kernel::Vector_3 n = CGAL::cross_product(q - p, r - p);
  const std::array<double, 3> a{std::abs(n.x()), std::abs(n.y()), std::abs(n.z())};
  return a[0] >= a[1] ? (a[0] >= a[2] ? 0 : 2) : (a[1] >= a[2] ? 1 : 2);
}

Kernel::Point_2 dropping(const Point& p, int axis) {
  return axis == 0 ? Kernel::Point_2(p.y(), p.z()) : axis == 1 ? Kernel::Point_2(p.z(), p.x())
                                                                : Kernel::Point_2(p.x(), p.y());
}

// True if r and s lie strictly on opposite sides of line pq once one coordinate is dropped.
// Then the triangles cannot overlap beyond pq: were the four points coplanar, a projection
// that keeps pq a line preserves sides (and one that does not gives zero signs here).
bool opposite_in_projection(const Point& p, const Point& q, const Point& r, const Point& s) {
  const int axis = dominant_axis(p, q, r);
  const CGAL::Orientation o_r = CGAL::orientation(dropping(p, axis), dropping(q, axis), dropping(r, axis));
  const CGAL::Orientation o_s = CGAL::orientation(dropping(p, axis), dropping(q, axis), dropping(s, axis));
  return o_r != CGAL::COLLINEAR && o_s != CGAL::COLLINEAR && o_r != o_s;
}

// Common edge pq, opposite vertices r (of one triangle) and s (of the other); both triangles
// span planes. Off the common plane the triangles meet only along pq; in it they overlap iff
// r and s lie on the same side of pq (CGAL PMP do_faces_intersect, shared-edge branch). The
// projected test first settles, with 2D signs, the folds and hinges of ordinary meshes,
// including the nearly coplanar quads whose 3D coplanarity test needs exact arithmetic.
bool overlap_beyond_common_edge(const Point& p, const Point& q, const Point& r, const Point& s) {
  if (opposite_in_projection(p, q, r, s)) return false;
  if (CGAL::orientation(p, q, r, s) != CGAL::COPLANAR) return false;
  switch (CGAL::coplanar_orientation(p, q, r, s)) {
    case CGAL::POSITIVE: return true;   // same side: a fold-back onto itself
    case CGAL::NEGATIVE: return false;  // opposite sides: a flat hinge
    case CGAL::COLLINEAR: break;        // s on line pq would make its triangle collinear
  }
  throw std::logic_error("overlap_beyond_common_edge: a degenerate triangle reached the shared-edge test");
}

// True iff the triangle (v, b1, b2) minus v lies strictly on one side of plane (v, a1, a2):
// then the two triangles can meet only at v. A cheap exact filter before the full test.
bool strictly_one_side(const Point& v, const Point& a1, const Point& a2, const Point& b1, const Point& b2) {
  const CGAL::Orientation o1 = CGAL::orientation(v, a1, a2, b1);
  if (o1 == CGAL::COPLANAR) return false;
  return CGAL::orientation(v, a1, a2, b2) == o1;
}

// Common vertex v, triangles (v, a1, a2) and (v, b1, b2). Both are star-shaped from v, so a
// common point other than v exists iff one triangle meets the other's edge opposite v
// (CGAL PMP do_faces_intersect, shared-vertex branch).
bool meet_beyond_common_vertex(const Point& v, const Point& a1, const Point& a2, const Point& b1,
                               const Point& b2) {
  if (strictly_one_side(v, a1, a2, b1, b2) || strictly_one_side(v, b1, b2, a1, a2)) return false;
  return CGAL::do_intersect(Triangle3(v, a1, a2), Segment(b1, b2)) ||
         CGAL::do_intersect(Triangle3(v, b1, b2), Segment(a1, a2));
}

bool intersect_illegitimately(const Soup& soup, const Triangle& a, const Triangle& b) {
  const auto pa = [&](int k) { return point(soup.vertices[a[k]]); };
  const auto pb = [&](int k) { return point(soup.vertices[b[k]]); };
  const Sharing s = sharing_of(a, b);
  switch (s.count) {
    case 0:
      return CGAL::do_intersect(Triangle3(pa(0), pa(1), pa(2)), Triangle3(pb(0), pb(1), pb(2)));
    case 1: {
      const int i = s.corner_in_a[0];
      const int j = s.corner_in_b[0];
      return meet_beyond_common_vertex(pa(i), pa((i + 1) % 3), pa((i + 2) % 3), pb((j + 1) % 3), pb((j + 2) % 3));
    }
    case 2: {
      const int r = third_corner(s.corner_in_a[0], s.corner_in_a[1]);
      const int q = third_corner(s.corner_in_b[0], s.corner_in_b[1]);
      return overlap_beyond_common_edge(pa(s.corner_in_a[0]), pa(s.corner_in_a[1]), pa(r), pb(q));
    }
    default:  // the same three points: a duplicate (either orientation) covers itself
      return true;
  }
}

using PairBuckets = tbb::enumerable_thread_specific<std::vector<TrianglePair>>;
using BoxSpan = std::span<TriangleBox>;

// CGAL's default cutoff (10) suits cheap callbacks; PMP's self_intersections uses 2000.
constexpr std::ptrdiff_t box_cutoff = 2000;
// Below this many boxes a part is not split further: the split costs more than it saves.
constexpr std::size_t smallest_split = 1 << 14;

int widest_axis(BoxSpan boxes) {
  std::array<float, 3> lo{boxes[0].lo}, hi{boxes[0].hi};
  for (const TriangleBox& b : boxes)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], b.lo[d]);
      hi[d] = std::max(hi[d], b.hi[d]);
    }
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (hi[d] - lo[d] > hi[axis] - lo[axis]) axis = d;
  return axis;
}

// Reorders boxes so that the first half has the smaller lower ends along `axis`. Any
// partition is correct (the straddler step below finds every pair across it); the median
// only balances the work. Lower ends rather than centres: lo + hi would be NaN for a box
// from -inf to +inf, and NaN breaks the strict weak order nth_element needs.
std::size_t split_at_median(BoxSpan boxes, int axis) {
  const std::size_t mid = boxes.size() / 2;
  std::nth_element(boxes.begin(), boxes.begin() + static_cast<std::ptrdiff_t>(mid), boxes.end(),
                   [axis](const TriangleBox& a, const TriangleBox& b) { return a.lo[axis] < b.lo[axis]; });
  return mid;
}

// The boxes of `side` that reach into the slab [from, to] along `axis`: a box of the left
// part overlapping a box of the right part lies in both straddler sets, by construction.
std::vector<TriangleBox> straddlers(BoxSpan side, int axis, float from, float to) {
  std::vector<TriangleBox> out;
  for (const TriangleBox& b : side)
    if (b.hi[axis] >= from && b.lo[axis] <= to) out.push_back(b);
  return out;
}

// All overlapping box pairs of `boxes`, each reported once: the two halves of a median split
// in parallel (recursively, `depth` levels), and the pairs across the split, found among
// the few boxes straddling it. CGAL's own Parallel_tag needs CGAL_LINKED_WITH_TBB and copies
// the ranges 4 times; this split needs neither.
template <class Callback>
void self_overlapping_pairs(BoxSpan boxes, int depth, const Callback& report) {
  if (depth == 0 || boxes.size() < smallest_split) {
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes.begin(), boxes.end(), report, box_cutoff);
    return;
  }
  const int axis = widest_axis(boxes);
  const std::size_t mid = split_at_median(boxes, axis);
  const BoxSpan left = boxes.first(mid);
  const BoxSpan right = boxes.subspan(mid);
  float right_lo = right[0].lo[axis];
  for (const TriangleBox& b : right) right_lo = std::min(right_lo, b.lo[axis]);
  float left_hi = left[0].hi[axis];
  for (const TriangleBox& b : left) left_hi = std::max(left_hi, b.hi[axis]);
  std::vector<TriangleBox> left_cross = straddlers(left, axis, right_lo, left_hi);
  std::vector<TriangleBox> right_cross = straddlers(right, axis, right_lo, left_hi);
  tbb::parallel_invoke([&] { self_overlapping_pairs(left, depth - 1, report); },
                       [&] { self_overlapping_pairs(right, depth - 1, report); },
                       [&] {
                         CGAL::box_intersection_d<CGAL::Sequential_tag>(left_cross.begin(), left_cross.end(),
                                                                        right_cross.begin(), right_cross.end(),
                                                                        report, box_cutoff);
                       });
}

// Two levels give four parts plus three straddler sets: enough tasks to keep a few cores busy.
constexpr int split_depth = 2;

std::vector<TrianglePair> merged_sorted(PairBuckets& buckets) {
  std::vector<TrianglePair> pairs;
  for (auto& bucket : buckets) pairs.insert(pairs.end(), bucket.begin(), bucket.end());
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

std::vector<TrianglePair> find_self_intersecting_pairs(const Soup& welded, std::span<const TriangleShape> shapes) {
  if (shapes.size() != welded.triangles.size())
    throw std::invalid_argument("find_self_intersecting_pairs: " + std::to_string(shapes.size()) +
                                " shapes for " + std::to_string(welded.triangles.size()) + " triangles");
  if (welded.triangles.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("find_self_intersecting_pairs: more than 2^32 - 1 triangles");
  std::vector<TriangleBox> boxes = boxes_of_proper_triangles(welded, shapes);
  PairBuckets buckets;
  const auto report = [&](const TriangleBox& a, const TriangleBox& b) {
    if (!intersect_illegitimately(welded, a.corners, b.corners)) return;
    buckets.local().emplace_back(std::min(a.triangle, b.triangle), std::max(a.triangle, b.triangle));
  };
  self_overlapping_pairs(boxes, split_depth, report);
  return merged_sorted(buckets);
}

std::vector<TrianglePair> find_self_intersecting_pairs(const Soup& welded) {
  const std::vector<TriangleShape> shapes = classify_triangle_shapes(welded);
  return find_self_intersecting_pairs(welded, shapes);
}

}  // namespace shadowcert
