// exact/box_tree.h: the BVH reports every box a query meets (the exact queries exactly those),
// on axis-aligned segments and rays, where the exact answer is a comparison of coordinates:
// random boxes on a small integer grid (shared faces, touching corners, zero-width boxes), at
// unit scale, scaled by 2^-900 and 2^900 (the slab test's general path), enough of them for the
// parallel build; and the nearest-first query never skips a box entered before its bound. Oblique
// queries on a lattice, offset and scaled, against an integer brute force: the float traversal.
#include "exact/box_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <cmath>
#include <random>
#include <set>
#include <span>
#include <stdexcept>
#include <vector>

namespace {

using namespace shadowcert;
using detail::BoxTree;
using detail::LeafTest;

std::vector<Box> grid_boxes(std::mt19937_64& rng, std::size_t count, double scale) {
  std::uniform_int_distribution<int> coordinate(-20, 20), size(0, 3);
  std::vector<Box> boxes(count);
  for (Box& b : boxes)
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = coordinate(rng) * scale;
      b.hi[k] = b.lo[k] + size(rng) * scale;
    }
  return boxes;
}

// An axis-aligned query: along `axis` from `from` to `to` (to = +-infinity for a ray), the other
// coordinates fixed; the boxes dilated by `slack` it meets, exactly.
struct AxisQuery {
  Vec3 point{};
  int axis = 0;
  double from = 0.0;
  double to = 0.0;
};

std::set<std::uint32_t> expected(const std::vector<Box>& boxes, const AxisQuery& q, double slack) {
  std::set<std::uint32_t> out;
  const double lo = std::min(q.from, q.to), hi = std::max(q.from, q.to);
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    bool meets = boxes[i].lo[q.axis] - slack <= hi && lo <= boxes[i].hi[q.axis] + slack;
    for (int k = 0; k < 3; ++k)
      if (k != q.axis) meets = meets && boxes[i].lo[k] - slack <= q.point[k] && q.point[k] <= boxes[i].hi[k] + slack;
    if (meets) out.insert(i);
  }
  return out;
}

AxisQuery draw_query(std::mt19937_64& rng, double scale, bool ray) {
  std::uniform_int_distribution<int> coordinate(-22, 22), axis(0, 2), direction(0, 1);
  AxisQuery q;
  for (double& x : q.point) x = coordinate(rng) * scale;
  q.axis = axis(rng);
  q.from = q.point[q.axis];
  const double sign = direction(rng) == 0 ? -1.0 : 1.0;
  q.to = ray ? sign * INFINITY : q.from + sign * (1 + coordinate(rng) % 10 + 10) * scale;
  return q;
}

Vec3 end_point(const AxisQuery& q) {
  Vec3 to = q.point;
  to[q.axis] = q.to;
  return to;
}

Vec3 direction_of(const AxisQuery& q) {
  Vec3 d{};
  d[q.axis] = q.to > q.from ? 1.0 : -1.0;
  return d;
}

TEST(BoxTree, AxisQueries_ReportExactlyTheBoxesMet) {
  std::mt19937_64 rng(24);
  for (double scale : {1.0, std::ldexp(1.0, -900), std::ldexp(1.0, 900)}) {
    const std::vector<Box> boxes = grid_boxes(rng, 6000, scale);
    const BoxTree exact(boxes, LeafTest::exact);
    const BoxTree skip(boxes, LeafTest::skip);
    for (int i = 0; i < 300; ++i) {
      const bool ray = i % 2 == 1;
      const AxisQuery q = draw_query(rng, scale, ray);
      const std::set<std::uint32_t> want = expected(boxes, q, 0.0);
      std::set<std::uint32_t> got, superset, dilated;
      const auto into = [](std::set<std::uint32_t>& s) {
        return [&s](std::uint32_t id) {
          s.insert(id);
          return true;
        };
      };
      if (ray) {
        exact.ray_query(q.point, direction_of(q), into(got));
        skip.ray_query(q.point, direction_of(q), into(superset));
      } else {
        exact.segment_query(q.point, end_point(q), into(got));
        skip.segment_query(q.point, end_point(q), into(superset));
      }
      // Rays at 2^900: the exact leaf test (CGAL's Do_intersect_3 of Ray_3 and Bbox_3, as before
      // the BVH) misses boxes a ray meets (DISABLED_HugeRays_ExactLeafTestReportsEveryBox): only
      // the superset is held there.
      if (ray && scale > 1.0) {
        EXPECT_TRUE(std::includes(want.begin(), want.end(), got.begin(), got.end())) << "query " << i;
      } else {
        EXPECT_EQ(got, want) << "scale " << scale << ", query " << i;
      }
      EXPECT_TRUE(std::includes(superset.begin(), superset.end(), want.begin(), want.end())) << "skip, query " << i;
      // Dilated by half a grid step: a superset of the boxes the dilated query meets.
      const double slack = 0.5 * scale;
      const Vec3 slacks{slack, slack, slack};
      if (ray) {
        exact.dilated_ray_query(q.point, direction_of(q), slacks, into(dilated));
      } else {
        exact.dilated_segment_query(q.point, end_point(q), slacks, into(dilated));
      }
      const std::set<std::uint32_t> want_dilated = expected(boxes, q, slack);
      EXPECT_TRUE(std::includes(dilated.begin(), dilated.end(), want_dilated.begin(), want_dilated.end()))
          << "dilated, scale " << scale << ", query " << i;
    }
  }
}

TEST(BoxTree, NearestFirst_VisitsEveryBoxEnteredBeforeTheBound) {
  std::mt19937_64 rng(5);
  const std::vector<Box> boxes = grid_boxes(rng, 5000, 1.0);
  const BoxTree tree(boxes, LeafTest::exact);
  for (int i = 0; i < 300; ++i) {
    const AxisQuery q = draw_query(rng, 1.0, true);
    const double bound = 1.0 + i % 17;  // t along a unit direction: distance
    AxisQuery piece = q;
    piece.to = q.from + (q.to > q.from ? bound : -bound);
    const std::set<std::uint32_t> want = expected(boxes, piece, 0.0);
    std::set<std::uint32_t> got;
    tree.nearest_first_ray_query(q.point, direction_of(q), &bound, [&](std::uint32_t id) {
      got.insert(id);
      return true;
    });
    EXPECT_TRUE(std::includes(got.begin(), got.end(), want.begin(), want.end())) << "query " << i;
  }
}

// Found while testing the BVH (issue 24), and older than it: with coordinates near 2^900 (a
// scene the campaign never draws; its scales stop at 2^20) an exact ray query loses boxes the ray
// meets, the leaf test being CGAL's Ray_3 / Bbox_3 predicate, whose double evaluation overflows.
// Segments at the same scale are right. Kept as the reproducer until the leaf test is exact there.
TEST(BoxTree, DISABLED_HugeRays_ExactLeafTestReportsEveryBox) {
  std::mt19937_64 rng(24);
  const double scale = std::ldexp(1.0, 900);
  const std::vector<Box> boxes = grid_boxes(rng, 6000, scale);
  const BoxTree exact(boxes, LeafTest::exact);
  for (int i = 0; i < 100; ++i) {
    const AxisQuery q = draw_query(rng, scale, true);
    std::set<std::uint32_t> got;
    exact.ray_query(q.point, direction_of(q), [&](std::uint32_t id) {
      got.insert(id);
      return true;
    });
    EXPECT_EQ(got, expected(boxes, q, 0.0)) << "query " << i;
  }
}

// Oblique queries between lattice points, where the float traversal (4 children per node, boxes
// rounded outward to floats, exact/box_tree.cpp) runs: the exact answer from integer arithmetic
// (each slab's parameter interval a fraction, compared by cross-multiplication), the lattice
// translated by an offset floats cannot hold (2^30 + k, 2^39 + k: every box and query point is
// rounded) and scaled (2^-20: large inverses). Queries touch box corners, edges and faces exactly.
struct Lattice {
  double offset = 0.0;
  double scale = 1.0;
  [[nodiscard]] double at(std::int64_t k) const { return offset + static_cast<double>(k) * scale; }
};

// `count` random boxes with even lattice coordinates in [-80, 80] (so that half a step, the
// dilation the tests use, is a lattice step), sides of 0 to 12: their integer corners and the
// boxes themselves.
struct LatticeBoxes {
  std::vector<std::array<std::int64_t, 3>> lo, hi;
  std::vector<Box> boxes;
};
LatticeBoxes lattice_boxes(std::mt19937_64& rng, std::size_t count, const Lattice& lattice) {
  std::uniform_int_distribution<int> coordinate(-40, 40), size(0, 6);
  LatticeBoxes out{std::vector<std::array<std::int64_t, 3>>(count), std::vector<std::array<std::int64_t, 3>>(count),
                   std::vector<Box>(count)};
  for (std::size_t i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k) {
      out.lo[i][k] = 2 * coordinate(rng);
      out.hi[i][k] = out.lo[i][k] + 2 * size(rng);
      out.boxes[i].lo[k] = lattice.at(out.lo[i][k]);
      out.boxes[i].hi[k] = lattice.at(out.hi[i][k]);
    }
  return out;
}

// Whether the segment a + t (b - a), t in [0, 1] (t >= 0 for a ray), meets the box [lo - s, hi + s]
// (integer coordinates), exactly.
bool lattice_meets(const std::array<std::int64_t, 3>& a, const std::array<std::int64_t, 3>& b,
                   const std::array<std::int64_t, 3>& lo, const std::array<std::int64_t, 3>& hi, std::int64_t s,
                   bool ray) {
  // The interval of t as fractions enter_n / enter_d <= t <= leave_n / leave_d (denominators > 0;
  // every product below 2^20).
  std::int64_t enter_n = 0, enter_d = 1, leave_n = 1, leave_d = ray ? 0 : 1;  // leave_d 0: +infinity
  for (int k = 0; k < 3; ++k) {
    const std::int64_t d = b[k] - a[k], l = lo[k] - s - a[k], h = hi[k] + s - a[k];
    if (d == 0) {
      if (l > 0 || h < 0) return false;
      continue;
    }
    std::int64_t n0 = d > 0 ? l : h, n1 = d > 0 ? h : l, den = d > 0 ? d : -d;
    if (d < 0) {
      n0 = -n0;
      n1 = -n1;
    }
    if (n0 * enter_d > enter_n * den) {
      enter_n = n0;
      enter_d = den;
    }
    if (leave_d == 0 || n1 * leave_d < leave_n * den) {
      leave_n = n1;
      leave_d = den;
    }
  }
  return leave_d == 0 || enter_n * leave_d <= leave_n * enter_d;
}

TEST(BoxTree, ObliqueLatticeQueries_FloatTraversalLosesNoBox) {
  std::mt19937_64 rng(2024);
  std::uniform_int_distribution<int> coordinate(-40, 40), step(-9, 9);
  for (const Lattice lattice : {Lattice{0.0, 1.0}, Lattice{0x1p30, 1.0}, Lattice{0x1p39, 1.0}, Lattice{0.0, 0x1p-20}}) {
    SCOPED_TRACE("offset " + std::to_string(lattice.offset) + " scale " + std::to_string(lattice.scale));
    const auto [lo, hi, boxes] = lattice_boxes(rng, 6000, lattice);
    const BoxTree tree(boxes, LeafTest::exact);
    const auto point = [&](const std::array<std::int64_t, 3>& p) {
      return Vec3{lattice.at(p[0]), lattice.at(p[1]), lattice.at(p[2])};
    };
    for (int i = 0; i < 400; ++i) {
      std::array<std::int64_t, 3> a{}, d{};
      for (int k = 0; k < 3; ++k) {
        a[k] = 2 * coordinate(rng);
        d[k] = 2 * step(rng);
      }
      if (d == std::array<std::int64_t, 3>{}) d[0] = 2;
      const std::array<std::int64_t, 3> b{a[0] + d[0], a[1] + d[1], a[2] + d[2]};
      const Vec3 direction{static_cast<double>(d[0]), static_cast<double>(d[1]), static_cast<double>(d[2])};
      std::set<std::uint32_t> segment, ray, dilated, nearest, want_segment, want_ray, want_dilated;
      for (std::uint32_t j = 0; j < boxes.size(); ++j) {
        if (lattice_meets(a, b, lo[j], hi[j], 0, false)) want_segment.insert(j);
        if (lattice_meets(a, b, lo[j], hi[j], 0, true)) want_ray.insert(j);
        if (lattice_meets(a, b, lo[j], hi[j], 1, false)) want_dilated.insert(j);
      }
      const auto into = [](std::set<std::uint32_t>& s) {
        return [&s](std::uint32_t id) {
          s.insert(id);
          return true;
        };
      };
      tree.segment_query(point(a), point(b), into(segment));
      tree.ray_query(point(a), direction, into(ray));
      const Vec3 slack{lattice.scale, lattice.scale, lattice.scale};
      tree.dilated_segment_query(point(a), point(b), slack, into(dilated));
      // Along d scaled to the lattice, up to t = 1: the segment's boxes at least.
      const Vec3 scaled{direction[0] * lattice.scale, direction[1] * lattice.scale, direction[2] * lattice.scale};
      const double one = 1.0;
      tree.nearest_first_ray_query(point(a), scaled, &one, into(nearest));
      EXPECT_EQ(segment, want_segment) << "segment query " << i;
      EXPECT_EQ(ray, want_ray) << "ray query " << i;
      EXPECT_TRUE(std::includes(dilated.begin(), dilated.end(), want_dilated.begin(), want_dilated.end()))
          << "dilated query " << i;
      EXPECT_TRUE(std::includes(nearest.begin(), nearest.end(), want_segment.begin(), want_segment.end()))
          << "nearest-first query " << i;
    }
  }
}

// The dilated segment query over a list (a cone's candidates): it reports, in the list's order,
// exactly the listed boxes the walk reports (so every listed box the dilated segment meets),
// nothing unlisted, stops when the visitor says so, and refuses an id out of range.
TEST(BoxTree, ListedDilatedSegment_ReportsTheListedBoxesTheWalkReports) {
  std::mt19937_64 rng(2026);
  std::uniform_int_distribution<int> coordinate(-40, 40), step(-9, 9);
  for (const Lattice lattice : {Lattice{0.0, 1.0}, Lattice{0x1p30, 1.0}, Lattice{0.0, 0x1p-20}}) {
    SCOPED_TRACE("offset " + std::to_string(lattice.offset) + " scale " + std::to_string(lattice.scale));
    const auto [lo, hi, boxes] = lattice_boxes(rng, 3000, lattice);
    const BoxTree tree(boxes, LeafTest::exact);
    const auto point = [&](const std::array<std::int64_t, 3>& p) {
      return Vec3{lattice.at(p[0]), lattice.at(p[1]), lattice.at(p[2])};
    };
    const Vec3 slack{lattice.scale, lattice.scale, lattice.scale};
    std::size_t met = 0;
    for (int i = 0; i < 200; ++i) {
      std::array<std::int64_t, 3> a{}, b{};
      for (int k = 0; k < 3; ++k) {
        a[k] = 2 * coordinate(rng);
        b[k] = a[k] + 2 * step(rng);
      }
      if (a == b) b[0] += 2;
      std::set<std::uint32_t> walk;
      tree.dilated_segment_query(point(a), point(b), slack, [&](std::uint32_t id) { return walk.insert(id), true; });
      // A list of about half the boxes, shuffled: those the dilated segment meets among them
      // (the lattice's exact answer) must come, and in the list's order.
      std::vector<std::uint32_t> list;
      for (std::uint32_t j = 0; j < boxes.size(); ++j)
        if (rng() % 2 == 0) list.push_back(j);
      std::shuffle(list.begin(), list.end(), rng);
      std::vector<std::uint32_t> got;
      tree.dilated_segment_query(point(a), point(b), slack, std::span<const std::uint32_t>(list),
                                 [&](std::uint32_t id) { return got.push_back(id), true; });
      std::size_t cursor = 0;
      for (const std::uint32_t id : got) {
        while (cursor < list.size() && list[cursor] != id) ++cursor;
        ASSERT_LT(cursor, list.size()) << "query " << i << ": box " << id << " unlisted or out of order";
        ++cursor;
      }
      const std::set<std::uint32_t> reported(got.begin(), got.end());
      EXPECT_EQ(reported.size(), got.size()) << "query " << i << ": a box reported twice";
      for (const std::uint32_t id : list) {
        // The walk's own leaf test: the listed boxes the walk reports, and no other.
        EXPECT_EQ(reported.count(id), walk.count(id)) << "query " << i << ": box " << id;
        if (lattice_meets(a, b, lo[id], hi[id], 1, false)) {
          EXPECT_EQ(reported.count(id), 1u) << "query " << i << ": box " << id << " met";
          ++met;
        }
      }
      // The visitor stops it.
      if (got.size() >= 2) {
        std::size_t visits = 0;
        tree.dilated_segment_query(point(a), point(b), slack, std::span<const std::uint32_t>(list),
                                   [&](std::uint32_t) { return ++visits < 2; });
        EXPECT_EQ(visits, 2u);
      }
    }
    EXPECT_GT(met, 100u);
  }
  const BoxTree tree(std::vector<Box>(3), LeafTest::exact);
  const std::vector<std::uint32_t> out_of_range{0, 3};
  EXPECT_THROW(tree.dilated_segment_query({0, 0, 0}, {1, 1, 1}, {0, 0, 0}, std::span<const std::uint32_t>(out_of_range),
                                          [](std::uint32_t) { return true; }),
               std::invalid_argument);
}

TEST(BoxTree, NoBoxes_ReportsNothing) {
  const BoxTree tree({}, LeafTest::exact);
  int visits = 0;
  tree.segment_query({0, 0, 0}, {1, 1, 1}, [&](std::uint32_t) { return ++visits, true; });
  tree.nearest_first_ray_query({0, 0, 0}, {1, 0, 0}, nullptr, [&](std::uint32_t) { return ++visits, true; });
  EXPECT_EQ(visits, 0);
}

}  // namespace
