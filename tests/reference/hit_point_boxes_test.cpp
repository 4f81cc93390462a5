// The exact image's per-ray hit-point boxes (reference/detail/hit_point_boxes.h): each box read
// back encloses the box set (so every point it enclosed that lies in the scene's box), in floats
// for a moderate scene and exactly, in doubles, beyond float's range.
#include "reference/detail/hit_point_boxes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace {

using shadowcert::Vec3;
using shadowcert::detail::HitPointBoxes;

bool encloses(const HitPointBoxes::Box& outer, const Vec3& p) {
  for (std::size_t a = 0; a < 3; ++a)
    if (!(outer[0][a] <= p[a] && p[a] <= outer[1][a])) return false;
  return true;
}

TEST(HitPointBoxes, ModerateScene_FloatBoxesEncloseEveryPointAndStayTight) {
  const std::uint64_t seed = 77;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  const Vec3 lo{-3.0, 0.0, -1e-3}, hi{5.0, 2.5, 7e4};
  HitPointBoxes boxes(1000, {lo, hi});
  ASSERT_TRUE(boxes.in_float());
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> points(1000);
  for (std::size_t k = 0; k < points.size(); ++k) {
    for (std::size_t a = 0; a < 3; ++a) points[k][a] = lo[a] + (hi[a] - lo[a]) * unit(rng);
    if (k % 10 == 0) points[k][1] = 0.0;  // on the floor, at the scene box's face
    // A box a few ulps around the point, as semi_static_hit_box gives; every tenth one wider
    // than the scene (a grazing ray's HitPoint box), cut back to it.
    HitPointBoxes::Box b;
    for (std::size_t a = 0; a < 3; ++a) {
      const double ulps = std::fabs(points[k][a]) * 0x1p-50 + 0x1p-1000;
      b[0][a] = k % 10 == 5 ? -1e300 : points[k][a] - ulps;
      b[1][a] = k % 10 == 5 ? 1e300 : points[k][a] + ulps;
    }
    boxes.set(k, b);
  }
  for (std::size_t k = 0; k < points.size(); ++k) {
    const HitPointBoxes::Box b = boxes[k];
    EXPECT_TRUE(encloses(b, points[k])) << "ray " << k;
    for (std::size_t a = 0; a < 3; ++a) {
      ASSERT_TRUE(std::isfinite(b[0][a]) && std::isfinite(b[1][a])) << "ray " << k;
      // Within the scene's box, give or take the float rounding.
      EXPECT_GE(b[0][a], lo[a] - std::fabs(lo[a]) * 0x1p-20 - 0x1p-140);
      EXPECT_LE(b[1][a], hi[a] + std::fabs(hi[a]) * 0x1p-20 + 0x1p-140);
      // Tight where the box set was: a few float steps of the coordinate.
      if (k % 10 != 5) {
        EXPECT_LE(b[1][a] - b[0][a], std::fabs(points[k][a]) * 0x1p-19 + 0x1p-140) << "ray " << k;
      }
    }
  }
}

TEST(HitPointBoxes, SceneBeyondFloatRange_KeepsTheDoublesExactly) {
  for (const double scale : {0x1p200, 0x1p-200}) {
    SCOPED_TRACE("scale " + std::to_string(std::log2(scale)));
    const Vec3 lo{-scale, -scale, 0.0}, hi{scale, scale, scale};
    HitPointBoxes boxes(3, {lo, hi});
    EXPECT_FALSE(boxes.in_float());
    const HitPointBoxes::Box b{Vec3{0.25 * scale, -0.5 * scale, 0.125 * scale},
                               Vec3{std::nextafter(0.25 * scale, 1e308), -0.5 * scale, 0.125 * scale}};
    boxes.set(1, b);
    EXPECT_EQ(boxes[1], b);
  }
}

}  // namespace
