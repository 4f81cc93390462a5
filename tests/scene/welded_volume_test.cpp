// scene/welded_volume.h: bitwise welding of homogeneous float vertices, -0 and +0 as one,
// first-seen order and bits kept, every triangle kept and renumbered.
#include "scene/welded_volume.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace shadowcert {
namespace {

TEST(WeldVolume, SignedZerosAndRepeats_BecomeOneVertexWithTheFirstBits) {
  HomogeneousMesh m;
  m.vertices = {{-0.0f, 1, 2, 1}, {0.0f, 1, 2, 1}, {3, 4, 5, 0}, {3, 4, 5, 0}, {3, 4, 5, 1}};
  m.triangles = {{0, 2, 4}, {1, 3, 4}};
  const HomogeneousMesh w = weld_volume(m);
  ASSERT_EQ(w.vertices.size(), 3u);  // (±0, 1, 2, 1), (3, 4, 5, 0), (3, 4, 5, 1): w tells them apart
  EXPECT_TRUE(std::signbit(w.vertices[0][0]));  // the first-seen -0 is kept
  ASSERT_EQ(w.triangles.size(), 2u);
  EXPECT_EQ(w.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(w.triangles[1], (std::array<std::uint32_t, 3>{0, 1, 2}));
}

TEST(WeldVolume, NaNPayloads_AreComparedByBits) {
  const float quiet = std::numeric_limits<float>::quiet_NaN();
  const float other = std::bit_cast<float>(std::bit_cast<std::uint32_t>(quiet) | 1u);
  HomogeneousMesh m;
  m.vertices = {{quiet, 0, 0, 1}, {quiet, 0, 0, 1}, {other, 0, 0, 1}};
  m.triangles = {{0, 1, 2}};
  EXPECT_EQ(weld_volume(m).vertices.size(), 2u);
}

TEST(WeldVolume, IndexOutOfRange_Throws) {
  HomogeneousMesh m;
  m.vertices = {{0, 0, 0, 1}};
  m.triangles = {{0, 0, 1}};
  EXPECT_THROW((void)weld_volume(m), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert
