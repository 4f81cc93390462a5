// campaign/soup_shrinker.h: delta debugging keeps the failure, ends 1-minimal, compacts vertices,
// and respects its test budget.
#include "campaign/soup_shrinker.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <set>

#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

// True iff the soup holds a triangle whose first vertex lies at `p`.
bool has_triangle_at(const Soup& s, const Vec3& p) {
  return std::any_of(s.triangles.begin(), s.triangles.end(), [&](const Triangle& t) { return s.vertices[t[0]] == p; });
}

TEST(SoupShrinker, OneCulpritTriangle_ShrunkToItAloneWithItsVertices) {
  const Soup soup = random_soup(11, 100, 1.0);
  const Vec3 culprit = soup.vertices[soup.triangles[37][0]];
  const ShrinkResult r = shrink_soup(soup, [&](const Soup& s) { return has_triangle_at(s, culprit); });
  ASSERT_EQ(r.soup.triangles.size(), 1u);
  EXPECT_EQ(r.soup.vertices.size(), 3u);  // compacted: only the culprit's vertices
  EXPECT_EQ(r.soup.vertices[r.soup.triangles[0][0]], culprit);
  EXPECT_TRUE(r.minimal);
  EXPECT_LT(r.tests, 40u);  // ddmin finds one element among 100 in O(log n) tests
}

TEST(SoupShrinker, FailureNeedsTwoFarApartTriangles_KeepsExactlyThose) {
  const Soup soup = random_soup(12, 64, 1.0);
  const Vec3 a = soup.vertices[soup.triangles[3][0]], b = soup.vertices[soup.triangles[60][0]];
  const ShrinkResult r =
      shrink_soup(soup, [&](const Soup& s) { return has_triangle_at(s, a) && has_triangle_at(s, b); });
  ASSERT_EQ(r.soup.triangles.size(), 2u);
  EXPECT_TRUE(has_triangle_at(r.soup, a) && has_triangle_at(r.soup, b));
  EXPECT_TRUE(r.minimal);
}

TEST(SoupShrinker, FailureNeedsManyTriangles_ResultIsOneMinimal) {
  // Fails while at least 5 triangles remain: every 5-subset is 1-minimal.
  const Soup soup = random_soup(13, 50, 1.0);
  auto fails = [](const Soup& s) { return s.triangles.size() >= 5; };
  const ShrinkResult r = shrink_soup(soup, fails);
  EXPECT_EQ(r.soup.triangles.size(), 5u);
  EXPECT_TRUE(r.minimal);
  for (std::size_t drop = 0; drop < r.soup.triangles.size(); ++drop) {
    Soup smaller = r.soup;
    smaller.triangles.erase(smaller.triangles.begin() + static_cast<std::ptrdiff_t>(drop));
    EXPECT_FALSE(fails(smaller));
  }
}

TEST(SoupShrinker, SoupThatPasses_ComesBackUnchanged) {
  const Soup soup = random_soup(14, 10, 1.0);
  const ShrinkResult r = shrink_soup(soup, [](const Soup&) { return false; });
  EXPECT_EQ(r.soup.triangles, soup.triangles);
  EXPECT_EQ(r.soup.vertices, soup.vertices);
  EXPECT_EQ(r.tests, 1u);
  EXPECT_FALSE(r.minimal);
}

TEST(SoupShrinker, TestBudget_NeverExceededAndReported) {
  const Soup soup = random_soup(15, 200, 1.0);
  std::size_t calls = 0;
  const ShrinkResult r = shrink_soup(
      soup,
      [&](const Soup& s) {
        ++calls;
        return s.triangles.size() >= 150;
      },
      6);
  EXPECT_LE(calls, 6u);
  EXPECT_EQ(r.tests, calls);
  EXPECT_FALSE(r.minimal);
  EXPECT_GE(r.soup.triangles.size(), 150u);  // whatever it kept still fails
}

TEST(SoupShrinker, SubsetOfTheInput_InTheInputsOrder) {
  const Soup soup = nonmanifold_fan(40);
  const std::vector<std::uint32_t> wanted{5, 17, 33};
  std::set<Vec3> needed;
  for (std::uint32_t i : wanted) needed.insert(soup.vertices[soup.triangles[i][2]]);
  const ShrinkResult r = shrink_soup(soup, [&](const Soup& s) {
    std::set<Vec3> apexes;
    for (const Triangle& t : s.triangles) apexes.insert(s.vertices[t[2]]);
    return std::includes(apexes.begin(), apexes.end(), needed.begin(), needed.end());
  });
  ASSERT_EQ(r.soup.triangles.size(), 3u);
  for (std::size_t k = 0; k < wanted.size(); ++k)
    EXPECT_EQ(r.soup.vertices[r.soup.triangles[k][2]], soup.vertices[soup.triangles[wanted[k]][2]]) << k;
}

TEST(SoupShrinker, BadArguments_Throw) {
  Soup bad = random_soup(16, 2, 1.0);
  bad.triangles[1][2] = 99;
  EXPECT_THROW((void)shrink_soup(bad, [](const Soup&) { return true; }), std::invalid_argument);
  EXPECT_THROW((void)shrink_soup(
                   random_soup(16, 2, 1.0), [](const Soup&) { return true; }, 0),
               std::invalid_argument);
}

}  // namespace
