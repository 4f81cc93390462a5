// reference/ellipsoid_occlusion.h: the exact analytic-shadow test of a point against an
// ellipsoid, on cases whose answer is known by hand (inside and outside a sphere's shadow
// cone, a segment that stops short, the light inside), the tangent segments whose sign is an
// exact zero (one the interval filter cannot decide), translation, and random points against
// dense sampling of the segment away from the boundary.
#include "reference/ellipsoid_occlusion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>

#include "core/vector3.h"

namespace {

using namespace shadowcert;

const Ellipsoid kUnitSphere{};
const Light kLightAbove{{0.0, 4.0, 0.0, 1.0}};
const Light kSunAbove{{0.0, 1.0, 0.0, 0.0}};

TEST(EllipsoidOcclusion, PointBelowTheSphere_IsShadowed) {
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {0.0, -2.0, 0.0}, kLightAbove), Sign::positive);
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {0.3, -2.0, -0.2}, kSunAbove), Sign::positive);
}

TEST(EllipsoidOcclusion, PointBesideTheShadowCone_IsLit) {
  // The cone from (0, 4, 0) tangent to the unit sphere has sin(angle) = 1/4; 6 below the light
  // its radius is 6 / sqrt(15) = 1.55, so x = 2 is outside; under the sun the shadow is x^2 + z^2 < 1.
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {2.0, -2.0, 0.0}, kLightAbove), Sign::negative);
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {1.2, -2.0, 0.0}, kSunAbove), Sign::negative);
}

TEST(EllipsoidOcclusion, SegmentThatStopsBeforeTheSphere_IsLit) {
  // The light between the point and the sphere: the segment never reaches it.
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {0.0, -4.0, 0.0}, Light{{0.0, -2.0, 0.0, 1.0}}), Sign::negative);
  // A point beyond the light (the sphere behind the point, seen from the light's side).
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {0.0, 6.0, 0.0}, kLightAbove), Sign::negative);
}

TEST(EllipsoidOcclusion, PointOrLightInside_IsShadowed) {
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {0.1, 0.2, 0.3}, kLightAbove), Sign::positive);
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {5.0, 5.0, 5.0}, Light{{0.0, 0.5, 0.0, 1.0}}), Sign::positive);
}

TEST(EllipsoidOcclusion, TangentSegmentOfSmallIntegers_IsAnExactZero) {
  // y = 1 touches the unit sphere at (0, 1, 0): every quantity is a small integer.
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {-2.0, 1.0, 0.0}, Light{{2.0, 1.0, 0.0, 1.0}}), Sign::zero);
  // The sun straight up past the sphere's side: the vertical line x = 1 touches it.
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {1.0, -5.0, 0.0}, kSunAbove), Sign::zero);
  // A point on the surface whose segment leaves it outwards: touches, does not enter.
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {0.0, 1.0, 0.0}, kLightAbove), Sign::zero);
  // On the surface facing away: the segment enters.
  EXPECT_EQ(ellipsoid_occlusion(kUnitSphere, {0.0, -1.0, 0.0}, kLightAbove), Sign::positive);
}

// Whether a - b is not a double (TwoSum's error term): then an interval enclosure of it has
// width, and every interval computed from it too.
bool subtraction_rounds(double a, double b) {
  const double s = a - b;
  const double bb = s - a;
  return (a - (s - bb)) + (-b - bb) != 0.0;
}

TEST(EllipsoidOcclusion, TangentSegmentTheFilterCannotDecide_IsAnExactZero) {
  // Hand-checked: the sphere of radius 1 around c = (0.1, 0.5, 0.3) and the segment from
  // P = (0.1 - 2.75, 1.5, 0.3) to L = (0.1 + 3.25, 1.5, 0.3). Both ends lie in the plane
  // y = c_y + 1 (0.5 + 1 = 1.5 exactly) and z = c_z, so the segment touches the sphere at
  // (0.1, 1.5, 0.3), inside the segment: q's minimum is exactly 0 (a c0 - b^2 = 0). But
  // P_x - c_x is not a double, so its interval has width and so has a c0 - b^2: the filter
  // cannot decide and the exact stage says zero.
  const Ellipsoid e{{0.1, 0.5, 0.3}, {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}};
  const Vec3 p{0.1 - 2.75, 1.5, 0.3};
  const Light l{{0.1 + 3.25, 1.5, 0.3, 1.0}};
  ASSERT_TRUE(subtraction_rounds(p[0], e.centre[0]));
  ASSERT_TRUE(subtraction_rounds(l.position[0], p[0]) || subtraction_rounds(l.position[0], e.centre[0]));
  EXPECT_EQ(ellipsoid_occlusion(e, p, l), Sign::zero);
  // One ulp of height either way: the segment enters or misses.
  EXPECT_EQ(ellipsoid_occlusion(e, {p[0], std::nextafter(1.5, 0.0), p[2]},
                                Light{{l.position[0], std::nextafter(1.5, 0.0), l.position[2], 1.0}}),
            Sign::positive);
  EXPECT_EQ(ellipsoid_occlusion(e, {p[0], std::nextafter(1.5, 2.0), p[2]},
                                Light{{l.position[0], std::nextafter(1.5, 2.0), l.position[2], 1.0}}),
            Sign::negative);
}

TEST(EllipsoidOcclusion, ShearedEllipsoid_TangentSunRayIsAnExactZero) {
  // Axes a0 = (2, 0, 0), a1 = (1, 1, 0), a2 = (0, 0, 1) and the sun along a1: in the sphere's
  // frame (u = A^-1 x) the ray is u_P + s e1, which touches the unit sphere iff u0^2 + u2^2 = 1.
  // P = (-1, -3, 0) is u = (1, -3, 0): tangent at s = 3. P = (-1.5, -3, 0) is u0 = 0.75:
  // enters; P = (-0.5, -3, 0) is u0 = 1.25: misses.
  const Ellipsoid e{{0, 0, 0}, {{{2, 0, 0}, {1, 1, 0}, {0, 0, 1}}}};
  EXPECT_EQ(ellipsoid_occlusion(e, {-1.0, -3.0, 0.0}, Light{{1.0, 1.0, 0.0, 0.0}}), Sign::zero);
  EXPECT_EQ(ellipsoid_occlusion(e, {-1.5, -3.0, 0.0}, Light{{1.0, 1.0, 0.0, 0.0}}), Sign::positive);
  EXPECT_EQ(ellipsoid_occlusion(e, {-0.5, -3.0, 0.0}, Light{{1.0, 1.0, 0.0, 0.0}}), Sign::negative);
}

TEST(EllipsoidOcclusion, ExactTranslation_KeepsEverySign) {
  const Ellipsoid e{{0.25, 0.5, -0.75}, {{{1.25, 0.5, 0}, {0, 0.75, 0.25}, {0.5, 0, 1}}}};
  const Light light{{1.5, 6.0, 0.5, 1.0}};
  const Vec3 shift{1024.0, -2048.0, 512.0};
  for (double x = -3.0; x <= 3.0; x += 0.25)
    for (double z = -3.0; z <= 3.0; z += 0.25) {
      const Vec3 p{x, -2.0, z};
      Ellipsoid moved = e;
      for (int k = 0; k < 3; ++k) moved.centre[k] += shift[k];
      const Light moved_light{{light.position[0] + shift[0], light.position[1] + shift[1], light.position[2] + shift[2], 1.0}};
      EXPECT_EQ(ellipsoid_occlusion(e, p, light),
                ellipsoid_occlusion(moved, {p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]}, moved_light))
          << x << ", " << z;
    }
}

// min over the segment of |A^-1 (x - c)|^2 - 1, sampled densely: a double estimate, only used
// where it is far from 0.
double sampled_minimum(const Ellipsoid& e, const Vec3& p, const Light& light) {
  const double det = det3(e.axes[0], e.axes[1], e.axes[2]);
  double best = INFINITY;
  const auto& l = light.position;
  for (int i = 0; i <= 4000; ++i) {
    const double t = light.directional() ? 20.0 * i / 4000.0 : i / 4000.0;
    const Vec3 dir = light.directional() ? Vec3{l[0], l[1], l[2]} : difference(Vec3{l[0], l[1], l[2]}, p);
    const Vec3 x{p[0] + t * dir[0] - e.centre[0], p[1] + t * dir[1] - e.centre[1], p[2] + t * dir[2] - e.centre[2]};
    const Vec3 u{det3(x, e.axes[1], e.axes[2]) / det, det3(e.axes[0], x, e.axes[2]) / det, det3(e.axes[0], e.axes[1], x) / det};
    best = std::min(best, dot(u, u) - 1.0);
  }
  return best;
}

TEST(EllipsoidOcclusion, RandomPoints_AgreeWithDenseSamplingAwayFromTheBoundary) {
  const unsigned seed = std::random_device{}();
  std::cout << "seed " << seed << "\n";
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Ellipsoid e{{0.1, 0.2, -0.1}, {{{1.3, 0.2, 0.0}, {-0.1, 0.7, 0.2}, {0.3, 0.0, 0.9}}}};
  int decided = 0;
  for (int i = 0; i < 400; ++i) {
    const Vec3 p{3.0 * unit(rng), -2.0 + unit(rng), 3.0 * unit(rng)};
    const Light light = i % 2 == 0 ? Light{{2.0 * unit(rng), 5.0 + unit(rng), 2.0 * unit(rng), 1.0}}
                                   : Light{{0.5 * unit(rng), 1.0, 0.5 * unit(rng), 0.0}};
    const double m = sampled_minimum(e, p, light);
    // Sampling overestimates the minimum by at most the step's effect (< 0.05 here); stay clear.
    if (std::abs(m) < 0.1) continue;
    ++decided;
    EXPECT_EQ(ellipsoid_occlusion(e, p, light), m < 0 ? Sign::positive : Sign::negative) << "seed " << seed << ", case " << i;
  }
  EXPECT_GT(decided, 200);
}

TEST(EllipsoidOcclusion, DependentAxesOrBadInput_Throw) {
  const Ellipsoid flat{{0, 0, 0}, {{{1, 0, 0}, {0, 1, 0}, {1, 1, 0}}}};
  EXPECT_THROW((void)ellipsoid_occlusion(flat, {0, -2, 0}, kLightAbove), std::invalid_argument);
  EXPECT_THROW((void)ellipsoid_occlusion(kUnitSphere, {NAN, -2, 0}, kLightAbove), std::invalid_argument);
  EXPECT_THROW((void)ellipsoid_occlusion(kUnitSphere, {0, -2, 0}, Light{{0, 0, 0, 0}}), std::invalid_argument);
  try {
    (void)ellipsoid_occlusion(flat, {0, -2, 0}, kLightAbove);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ellipsoid_occlusion"), std::string::npos);
  }
}

}  // namespace
