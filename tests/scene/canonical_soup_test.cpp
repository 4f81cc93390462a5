#include "scene/canonical_soup.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "scene/procedural_mesh.h"
#include "scene/welded_soup.h"

using shadowcert::canonical_soup;
using shadowcert::Soup;

TEST(CanonicalSoup, Vertices_SortedLexicographicallyAndDistinct) {
  Soup s;
  s.vertices = {{1, 0, 0}, {0, 2, 0}, {0, 1, 5}, {1, 0, 0}, {0, 1, -5}};
  s.triangles = {{0, 1, 2}, {3, 4, 1}};
  const auto c = canonical_soup(s);
  ASSERT_EQ(c.soup.vertices.size(), 4u);
  EXPECT_TRUE(std::is_sorted(c.soup.vertices.begin(), c.soup.vertices.end()));
  EXPECT_EQ(std::adjacent_find(c.soup.vertices.begin(), c.soup.vertices.end()), c.soup.vertices.end());
  EXPECT_EQ(c.canonical_id[0], c.canonical_id[3]);
  // Each triangle keeps its corners' positions, in its own order.
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(c.soup.vertices[c.soup.triangles[t][k]], s.vertices[s.triangles[t][k]]);
}

TEST(CanonicalSoup, NegativeZero_WeldsWithPositiveZero) {
  Soup s;
  s.vertices = {{0.0, 1, 0}, {-0.0, 1, 0}, {1, 1, 1}};
  s.triangles = {{0, 1, 2}};
  const auto c = canonical_soup(s);
  EXPECT_EQ(c.soup.vertices.size(), 2u);
  EXPECT_EQ(c.canonical_id[0], c.canonical_id[1]);
}

TEST(CanonicalSoup, VertexRelabelling_GivesTheSameSoup) {
  const Soup original = shadowcert::random_soup(7, 200, 3.0);
  std::mt19937_64 rng(7);
  std::vector<std::uint32_t> perm(original.vertices.size());
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  Soup relabelled = original;
  for (std::size_t i = 0; i < perm.size(); ++i) relabelled.vertices[perm[i]] = original.vertices[i];
  for (auto& t : relabelled.triangles)
    for (auto& v : t) v = perm[v];
  const auto a = canonical_soup(original);
  const auto b = canonical_soup(relabelled);
  EXPECT_EQ(a.soup.vertices, b.soup.vertices);
  EXPECT_EQ(a.soup.triangles, b.soup.triangles);
}

TEST(CanonicalSoup, SameVertexSetsAsWeldSoup) {
  const Soup s = shadowcert::uv_sphere({0, 0, 0}, 1.0, 16, 8);
  const auto c = canonical_soup(s);
  const auto w = shadowcert::weld_soup(s);
  EXPECT_EQ(c.soup.vertices.size(), w.soup.vertices.size());
  EXPECT_EQ(c.soup.normals.size(), c.soup.vertices.size());
  for (std::size_t i = 0; i < s.vertices.size(); ++i)
    for (std::size_t j = i + 1; j < std::min<std::size_t>(s.vertices.size(), i + 40); ++j)
      EXPECT_EQ(c.canonical_id[i] == c.canonical_id[j], w.welded_id[i] == w.welded_id[j]);
}

TEST(CanonicalSoup, IndexOutOfRange_ThrowsNamingFunction) {
  Soup s;
  s.vertices = {{0, 0, 0}};
  s.triangles = {{0, 0, 1}};
  EXPECT_THROW((void)canonical_soup(s), std::invalid_argument);
}

// The radix passes sort by the leading bits of x alone (scene/canonical_soup.cpp): x values a few
// ulps apart tie there and must still come out in full (x, y, z) order and weld exactly. Runs of
// such ties cross the sort's 65,536-record chunks. With x of both signs every key bit differs
// somewhere and the radix reads the top 33; with x all in [1, 2) the sign and exponent agree, so
// it reads 33 bits lower down, and the ties are still a few ulps apart below them.
TEST(CanonicalSoup, XTiedInTheRadixBits_SortedAndWeldedByFullPosition) {
  for (const bool both_signs : {true, false}) {
    const std::uint64_t seed = both_signs ? 24 : 25;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    Soup s;
    const std::size_t n = 150'000;
    // Two clusters of x a few ulps apart, and x spread over the range between them.
    const double first = both_signs ? 1.0 : 1.25, second = both_signs ? -3.0 : 1.75;
    for (std::size_t i = 0; i < n; ++i) {
      double x = 0.0;
      if (i % 3 == 2) {
        x = both_signs ? std::ldexp(static_cast<double>(rng() % 2001) - 1000.0, -6)
                       : 1.0 + std::ldexp(static_cast<double>(rng() % 1024), -10);
      } else {
        const double base = i % 3 == 0 ? first : second;
        x = std::nextafter(base, 10.0) + std::ldexp(static_cast<double>(rng() % 64), -50);
      }
      s.vertices.push_back({x, static_cast<double>(rng() % 7), static_cast<double>(rng() % 5) - 2.0});
    }
    for (std::size_t t = 0; t < n / 3; ++t)
      s.triangles.push_back({static_cast<std::uint32_t>(rng() % n), static_cast<std::uint32_t>(rng() % n),
                             static_cast<std::uint32_t>(rng() % n)});
    std::vector<shadowcert::Vec3> expected = s.vertices;
    std::sort(expected.begin(), expected.end());
    expected.erase(std::unique(expected.begin(), expected.end()), expected.end());

    const auto c = canonical_soup(s);
    EXPECT_EQ(c.soup.vertices, expected);
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(c.soup.vertices[c.canonical_id[i]], s.vertices[i]) << "vertex " << i;
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) ASSERT_EQ(c.soup.triangles[t][k], c.canonical_id[s.triangles[t][k]]);
  }
}
