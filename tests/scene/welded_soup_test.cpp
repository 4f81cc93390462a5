#include "scene/welded_soup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

using shadowcert::Soup;
using shadowcert::weld_soup;

TEST(WeldSoup, BitwiseEqualPositions_Merge) {
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}};
  s.triangles = {{0, 1, 2}, {4, 3, 2}};
  const auto w = weld_soup(s);
  ASSERT_EQ(w.soup.vertices.size(), 3u);
  EXPECT_EQ(w.welded_id, (std::vector<std::uint32_t>{0, 1, 2, 1, 0}));
  EXPECT_EQ(w.soup.triangles[1], (shadowcert::Triangle{0, 1, 2}));
}

TEST(WeldSoup, NegativeZero_EqualsPositiveZero) {
  Soup s;
  s.vertices = {{0.0, -0.0, 1.0}, {-0.0, 0.0, 1.0}, {0.0, 0.0, -0.0}};
  s.triangles = {{0, 1, 2}};
  const auto w = weld_soup(s);
  EXPECT_EQ(w.soup.vertices.size(), 2u);
  EXPECT_EQ(w.welded_id[0], w.welded_id[1]);
}

TEST(WeldSoup, OneUlpApart_StaysApart) {
  Soup s;
  const double x = 1.0;
  s.vertices = {{x, 0, 0}, {std::nextafter(x, 2.0), 0, 0}, {0, 1, 0}};
  s.triangles = {{0, 1, 2}};
  EXPECT_EQ(weld_soup(s).soup.vertices.size(), 3u);
}

TEST(WeldSoup, UnreferencedVertices_Kept) {
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};
  s.triangles = {{0, 1, 2}};
  EXPECT_EQ(weld_soup(s).soup.vertices.size(), 4u);
}

TEST(WeldSoup, NormalsOfFirstOccurrence_Kept) {
  Soup s;
  s.vertices = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}};
  s.normals = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
  s.triangles = {{0, 1, 2}};
  const auto w = weld_soup(s);
  ASSERT_EQ(w.soup.normals.size(), 2u);
  EXPECT_EQ(w.soup.normals[0], (shadowcert::Normal{0, 1, 0}));
}

TEST(WeldSoup, IndexOutOfRange_ThrowsNamingFunction) {
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.triangles = {{0, 1, 3}};
  try {
    (void)weld_soup(s);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("weld_soup"), std::string::npos);
  }
}
