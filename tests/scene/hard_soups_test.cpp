// scene/hard_soups.h: the builders the exact hard-case tests certify (tests/exact/hard_cases_test.cpp
// through tests/support/hard_case_scenes.h) and the hard-scene campaign places; here what those
// do not check: unwelded's float vertices, one triple per triangle, and half_fan's count.
#include "scene/hard_soups.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>

namespace shadowcert {
namespace {

TEST(HardSoups, Unwelded_EveryTriangleItsOwnFloatVertices) {
  Soup s;
  s.vertices = {{0.1, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 1.0 / 3.0}, {1.0, 1.0, 0.0}};
  s.triangles = {{0, 1, 2}, {1, 3, 2}};
  const Soup u = unwelded(s);
  ASSERT_EQ(u.vertices.size(), 6u);
  ASSERT_EQ(u.triangles.size(), 2u);
  for (std::uint32_t t = 0; t < 2; ++t)
    for (std::uint32_t k = 0; k < 3; ++k) {
      EXPECT_EQ(u.triangles[t][k], 3 * t + k);
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(u.vertices[3 * t + k][c], static_cast<double>(static_cast<float>(s.vertices[s.triangles[t][k]][c])));
    }
  EXPECT_NE(u.vertices[0][0], 0.1);  // 0.1 is not a float
  EXPECT_THROW((void)half_fan(0), std::invalid_argument);
  EXPECT_EQ(half_fan(256).triangles.size(), 256u);
}

}  // namespace
}  // namespace shadowcert
