// The count lists of a point light's grid (reference/detail/light_grid.h): every listed triangle
// that the open segment from a point of a box to the light meets (an exact test) is in the
// box's reach with a key above its threshold, for lights on each of the six sides of random
// soups; no grid where no axis separates the light from the scene; a wide floor listed apart;
// `listed` of the wrong size refused.
#include "reference/detail/light_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <set>
#include <stdexcept>
#include <span>
#include <string>
#include <vector>

#include "exact/face_crossing.h"
#include "exact/light_orientation.h"
#include "exact/orient_unchecked.h"

namespace {

using namespace shadowcert;
using detail::LightGrid;

// The ids of `reach`'s lists (each once).
std::set<std::uint32_t> reached(const LightGrid& grid, const LightGrid::Reach& reach) {
  std::set<std::uint32_t> ids;
  grid.visit(reach, [&](std::uint32_t id) { ids.insert(id); });
  return ids;
}

// Random triangles in [0, 1]^3: mostly small (a mesh's), some long (across many cells), some
// slivers and some with a vertex repeated (no area), over a floor of two wide triangles.
Soup random_soup(std::mt19937_64& rng, std::size_t count) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), step(-0.04, 0.04);
  Soup soup;
  soup.vertices = {{-1.0, 0.0, -1.0}, {2.0, 0.0, -1.0}, {2.0, 0.0, 2.0}, {-1.0, 0.0, 2.0}};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}};
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3 a{unit(rng), 0.05 + 0.95 * unit(rng), unit(rng)};
    const double reach = k % 10 == 0 ? 15.0 : 1.0;
    const auto near = [&] {
      Vec3 p = a;
      for (double& x : p) x = std::clamp(x + reach * step(rng), 0.0, 1.0);
      return p;
    };
    const auto first = static_cast<std::uint32_t>(soup.vertices.size());
    soup.vertices.push_back(a);
    soup.vertices.push_back(near());
    soup.vertices.push_back(k % 17 == 0 ? a : near());
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  return soup;
}

// Whether the open segment P -> L meets the closed triangle t, exactly, for P and L off its
// plane (the closed segment's meeting, at neither end).
bool open_segment_meets(const Soup& soup, std::uint32_t t, const Vec3& p, const Vec3& l) {
  const Vec3 &a = soup.vertices[soup.triangles[t][0]], &b = soup.vertices[soup.triangles[t][1]],
             &c = soup.vertices[soup.triangles[t][2]];
  return detail::segment_meets_triangle(finite_point(p), finite_point(l), a, b, c).meeting != detail::Meeting::apart;
}

TEST(LightGrid, RandomSoupsLitFromEachSide_EveryMetTriangleIsReached) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const Soup soup = random_soup(rng, 400);
    const Box scene = bounding_box(soup.vertices);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    // The light beyond one side of the scene's box: axis seed % 3, above or below.
    const std::size_t axis = seed % 3;
    Vec3 light{-0.5 + 2.0 * unit(rng), -0.5 + 2.0 * unit(rng), -0.5 + 2.0 * unit(rng)};
    light[axis] = seed % 2 == 0 ? scene.hi[axis] + 0.01 + unit(rng) : scene.lo[axis] - 0.01 - unit(rng);
    // Every triangle listed but those whose plane holds the light, and a few left out.
    std::vector<std::uint8_t> listed(soup.triangles.size());
    for (std::uint32_t t = 0; t < listed.size(); ++t) {
      const auto& tri = soup.triangles[t];
      listed[t] = t % 23 != 5 && detail::orient_unchecked(finite_point(soup.vertices[tri[0]]),
                                                          finite_point(soup.vertices[tri[1]]),
                                                          finite_point(soup.vertices[tri[2]]),
                                                          finite_point(light)) != Sign::zero;
    }
    const std::optional<LightGrid> grid = LightGrid::build(soup, light, scene, listed);
    ASSERT_TRUE(grid.has_value());
    EXPECT_GT(grid->cells(), 1u);
    std::uniform_real_distribution<double> radius(0.0, 0.05);
    std::size_t met = 0;
    for (int k = 0; k < 300; ++k) {
      // A box around a point of the scene (within its box, off the light's side), and a point P
      // in it, on a triangle's plane up to rounding where k is even (as a hit point is).
      Vec3 p{unit(rng), unit(rng), unit(rng)};
      if (k % 2 == 0) {
        const auto& tri = soup.triangles[2 + rng() % (soup.triangles.size() - 2)];
        const double s = unit(rng), t = unit(rng) * (1.0 - s);
        for (std::size_t i = 0; i < 3; ++i)
          p[i] = soup.vertices[tri[0]][i] + s * (soup.vertices[tri[1]][i] - soup.vertices[tri[0]][i]) +
                 t * (soup.vertices[tri[2]][i] - soup.vertices[tri[0]][i]);
      }
      Vec3 lo = p, hi = p;
      if (k % 3 == 0)
        for (std::size_t i = 0; i < 3; ++i) {
          lo[i] = std::max(scene.lo[i], p[i] - radius(rng));
          hi[i] = std::min(scene.hi[i], p[i] + radius(rng));
        }
      const std::optional<LightGrid::Reach> reach = grid->reach(lo, hi);
      ASSERT_TRUE(reach.has_value()) << "a box inside the scene's box";
      const std::set<std::uint32_t> ids = reached(*grid, *reach);
      for (std::uint32_t t = 0; t < soup.triangles.size(); ++t) {
        if (listed[t] == 0) {
          EXPECT_EQ(ids.count(t), 0u) << "unlisted triangle " << t;
          continue;
        }
        const auto& tri = soup.triangles[t];
        if (detail::orient_unchecked(finite_point(soup.vertices[tri[0]]), finite_point(soup.vertices[tri[1]]),
                                     finite_point(soup.vertices[tri[2]]), finite_point(p)) == Sign::zero)
          continue;  // P on its plane: the open segment misses it (count_at passes it by)
        if (!open_segment_meets(soup, t, p, light)) continue;
        ++met;
        EXPECT_EQ(ids.count(t), 1u) << "triangle " << t << " meets the segment from point " << k << " but is not reached";
      }
    }
    EXPECT_GT(met, 100u) << "the segments should meet triangles";
  }
}

// random_soup's 300 triangles over a floor 100 times wider than the rest: without setting it
// apart (big()) the cells would spread over it.
Soup soup_over_wide_floor(std::mt19937_64& rng) {
  Soup soup = random_soup(rng, 300);
  for (Vec3& v : std::span(soup.vertices).first(4)) {
    v[0] *= 100.0;
    v[2] *= 100.0;
  }
  return soup;
}

TEST(LightGrid, WideFloorUnderSmallTriangles_ListedApartAndCellsFitTheRest) {
  std::mt19937_64 rng(5);
  const Soup soup = soup_over_wide_floor(rng);
  const Box scene = bounding_box(soup.vertices);
  const std::vector<std::uint8_t> listed(soup.triangles.size(), 1);
  const std::optional<LightGrid> grid = LightGrid::build(soup, {0.5, 3.0, 0.5}, scene, listed);
  ASSERT_TRUE(grid.has_value());
  const std::set<std::uint32_t> big(grid->big().begin(), grid->big().end());
  EXPECT_EQ(big.count(0), 1u);
  EXPECT_EQ(big.count(1), 1u);
  // The floor lies below every other triangle: a box above it does not reach the floor (no
  // point of it is nearer to the light than the box), a box below it does.
  const std::optional<LightGrid::Reach> on_floor = grid->reach({0.5, 1e-3, 0.5}, {0.5, 1e-3, 0.5});
  ASSERT_TRUE(on_floor.has_value());
  EXPECT_EQ(reached(*grid, *on_floor).count(0), 0u);
  const std::optional<LightGrid::Reach> below = grid->reach({0.5, -1.0, 0.5}, {0.5, -1.0, 0.5});
  ASSERT_TRUE(below.has_value());
  EXPECT_EQ(reached(*grid, *below).count(0), 1u);
  EXPECT_EQ(reached(*grid, *below).count(1), 1u);
  // The cells cover the small triangles' projections, not the floor's: a point among them
  // reaches one cell of a few dozen triangles at most (over the floor's projection, one cell
  // would hold nearly all of them).
  const std::optional<LightGrid::Reach> middle = grid->reach({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5});
  ASSERT_TRUE(middle.has_value());
  EXPECT_TRUE(middle->one_cell());
  EXPECT_LT(grid->list(middle->c0, middle->r0).size(), 60u);
}

// cells_list_any says whether the reach's cells list anything above its threshold, as visit()
// finds (big()'s entries apart), and a box inside one whose cells list nothing lists nothing
// either (the count groups then skip their points' own reaches).
TEST(LightGrid, BoxesAroundAndInsideOthers_CellsListAnyAgreesWithVisit) {
  std::mt19937_64 rng(21);
  const Soup soup = soup_over_wide_floor(rng);
  const Box scene = bounding_box(soup.vertices);
  const std::vector<std::uint8_t> listed(soup.triangles.size(), 1);
  const std::optional<LightGrid> grid = LightGrid::build(soup, {0.5, 3.0, 0.5}, scene, listed);
  ASSERT_TRUE(grid.has_value());
  ASSERT_FALSE(grid->big().empty());
  const std::set<std::uint32_t> big(grid->big().begin(), grid->big().end());
  const auto lists_beyond_big = [&](const LightGrid::Reach& reach) {
    const std::set<std::uint32_t> ids = reached(*grid, reach);
    return std::any_of(ids.begin(), ids.end(), [&](std::uint32_t id) { return big.count(id) == 0; });
  };
  std::uniform_real_distribution<double> unit(0.0, 1.0), radius(0.0, 0.2);
  std::size_t empty = 0, listing = 0;
  for (int k = 0; k < 400; ++k) {
    // Boxes at heights from the floor up to above every small triangle (y up to 1.1).
    const Vec3 p{-0.5 + 2.0 * unit(rng), 1.1 * unit(rng), -0.5 + 2.0 * unit(rng)};
    Vec3 lo = p, hi = p;
    for (std::size_t i = 0; i < 3; ++i) {
      lo[i] = std::max(scene.lo[i], p[i] - radius(rng));
      hi[i] = std::min(scene.hi[i], p[i] + radius(rng));
    }
    const std::optional<LightGrid::Reach> reach = grid->reach(lo, hi);
    ASSERT_TRUE(reach.has_value());
    const bool any = grid->cells_list_any(*reach);
    EXPECT_EQ(any, lists_beyond_big(*reach)) << "box " << k;
    (any ? listing : empty) += 1;
    if (any) continue;
    // Boxes inside it: nothing listed beyond big() either.
    for (int j = 0; j < 5; ++j) {
      Vec3 a{}, b{};
      for (std::size_t i = 0; i < 3; ++i) {
        const double x = lo[i] + (hi[i] - lo[i]) * unit(rng), y = lo[i] + (hi[i] - lo[i]) * unit(rng);
        a[i] = std::min(x, y);
        b[i] = std::max(x, y);
      }
      const std::optional<LightGrid::Reach> inner = grid->reach(a, b);
      ASSERT_TRUE(inner.has_value());
      EXPECT_FALSE(grid->cells_list_any(*inner));
      EXPECT_FALSE(lists_beyond_big(*inner)) << "a box inside box " << k;
    }
  }
  EXPECT_GT(empty, 20u) << "boxes above the small triangles list nothing";
  EXPECT_GT(listing, 20u) << "boxes among or below them do";
}

TEST(LightGrid, LightInsideTheScenesBox_NoGrid) {
  std::mt19937_64 rng(9);
  const Soup soup = random_soup(rng, 50);
  const std::vector<std::uint8_t> listed(soup.triangles.size(), 1);
  EXPECT_FALSE(LightGrid::build(soup, {0.5, 0.5, 0.5}, bounding_box(soup.vertices), listed).has_value());
  // On the box's face: no axis has the scene strictly on one side.
  EXPECT_FALSE(LightGrid::build(soup, {0.5, 1.0, 0.5}, bounding_box(soup.vertices), listed).has_value());
}

// The grid of a random soup of 50 triangles (seed) under a light at (0.5, 4, 0.5), with every
// triangle listed (`listed` 1) or none (0).
std::optional<LightGrid> grid_under_light(std::uint64_t seed, std::uint8_t listed) {
  std::mt19937_64 rng(seed);
  const Soup soup = random_soup(rng, 50);
  return LightGrid::build(soup, {0.5, 4.0, 0.5}, bounding_box(soup.vertices),
                          std::vector<std::uint8_t>(soup.triangles.size(), listed));
}

TEST(LightGrid, BoxReachingTheLightsPlane_NoReach) {
  const std::optional<LightGrid> grid = grid_under_light(11, 1);
  ASSERT_TRUE(grid.has_value());
  EXPECT_TRUE(grid->reach({0.0, 0.0, 0.0}, {1.0, 3.9, 1.0}).has_value());
  EXPECT_FALSE(grid->reach({0.0, 0.0, 0.0}, {1.0, 4.0, 1.0}).has_value());
  EXPECT_FALSE(grid->reach({0.0, 4.5, 0.0}, {1.0, 5.0, 1.0}).has_value());
}

TEST(LightGrid, NothingListed_EmptyReach) {
  const std::optional<LightGrid> grid = grid_under_light(13, 0);
  ASSERT_TRUE(grid.has_value());
  const std::optional<LightGrid::Reach> reach = grid->reach({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  ASSERT_TRUE(reach.has_value());
  EXPECT_TRUE(reached(*grid, *reach).empty());
}

TEST(LightGrid, ListedOfAnotherSize_Throws) {
  std::mt19937_64 rng(17);
  const Soup soup = random_soup(rng, 10);
  const std::vector<std::uint8_t> listed(soup.triangles.size() - 1, 1);
  EXPECT_THROW((void)LightGrid::build(soup, {0.5, 4.0, 0.5}, bounding_box(soup.vertices), listed), std::invalid_argument);
}

}  // namespace
