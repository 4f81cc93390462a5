// reference/ellipsoid_shadow.h: the analytic shadow boundary of an ellipsoid on a plane, held
// to closed forms (a sphere's shadow circles, an axis-aligned ellipsoid's ellipse), and the
// boundary distance.
#include "reference/ellipsoid_shadow.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/vector3.h"

namespace {

using namespace shadowcert;

const Plane kFloor{{0, -2, 0}, {0, 1, 0}};

TEST(EllipsoidShadow, SphereUnderAnOverheadSun_IsAUnitCircle) {
  const auto boundary = ellipsoid_shadow_boundary({}, Light{{0, 1, 0, 0}}, kFloor, 64);
  ASSERT_EQ(boundary.size(), 64u);
  for (const Vec3& p : boundary) {
    EXPECT_NEAR(p[1], -2.0, 1e-12);
    EXPECT_NEAR(std::hypot(p[0], p[2]), 1.0, 1e-12);
  }
}

TEST(EllipsoidShadow, SphereUnderAPointLight_IsTheConesCircle) {
  // Light 4 above the centre, floor 6 below the light: radius 6 tan(asin(1/4)) = 6 / sqrt(15).
  const auto boundary = ellipsoid_shadow_boundary({}, Light{{0, 4, 0, 1}}, kFloor, 64);
  for (const Vec3& p : boundary) EXPECT_NEAR(std::hypot(p[0], p[2]), 6.0 / std::sqrt(15.0), 1e-12);
}

TEST(EllipsoidShadow, AxisAlignedEllipsoidUnderTheSun_IsItsEllipse) {
  const Ellipsoid e{{1, 0, -1}, {{{2, 0, 0}, {0, 1, 0}, {0, 0, 0.5}}}};
  const auto boundary = ellipsoid_shadow_boundary(e, Light{{0, 1, 0, 0}}, kFloor, 64);
  for (const Vec3& p : boundary) {
    const double x = (p[0] - 1.0) / 2.0, z = (p[2] + 1.0) / 0.5;
    EXPECT_NEAR(x * x + z * z, 1.0, 1e-12);
  }
}

TEST(EllipsoidShadow, EveryBoundaryRayIsTangent) {
  // Rotated, sheared ellipsoid under a point light: the line from the light to each boundary
  // point touches the ellipsoid (in the sphere's frame it stays at distance 1 from the centre).
  const Ellipsoid e{{0.2, 0.5, 0.1}, {{{1.2, 0.3, 0.0}, {-0.2, 0.8, 0.1}, {0.1, 0.0, 0.6}}}};
  const Light light{{1.0, 5.0, 0.5, 1.0}};
  for (const Vec3& p : ellipsoid_shadow_boundary(e, light, kFloor, 32)) {
    // Sample the segment light -> p densely: the closest approach to the ellipsoid's surface,
    // measured as min |A^-1 (x - c)|, is 1.
    double nearest = INFINITY;
    const double det = det3(e.axes[0], e.axes[1], e.axes[2]);
    for (int i = 0; i <= 20000; ++i) {
      const double s = i / 20000.0;
      const Vec3 x{light.position[0] + s * (p[0] - light.position[0]), light.position[1] + s * (p[1] - light.position[1]),
                   light.position[2] + s * (p[2] - light.position[2])};
      const Vec3 r = difference(x, e.centre);
      const Vec3 u{det3(r, e.axes[1], e.axes[2]) / det, det3(e.axes[0], r, e.axes[2]) / det,
                   det3(e.axes[0], e.axes[1], r) / det};
      nearest = std::min(nearest, std::sqrt(dot(u, u)));
    }
    EXPECT_NEAR(nearest, 1.0, 1e-6);
  }
}

TEST(BoundaryDistance, OfACircleToALargerOne_IsTheirRadiiDifference) {
  const auto unit = ellipsoid_shadow_boundary({}, Light{{0, 1, 0, 0}}, kFloor, 1024);
  const Ellipsoid wide{{0, 0, 0}, {{{1.1, 0, 0}, {0, 1, 0}, {0, 0, 1.1}}}};
  const auto larger = ellipsoid_shadow_boundary(wide, Light{{0, 1, 0, 0}}, kFloor, 256);
  const BoundaryDistance d = boundary_distance(larger, true, unit);
  EXPECT_NEAR(d.max, 0.1, 1e-5);  // the 1024-gon truth sags by 5e-6
  EXPECT_NEAR(d.mean, 0.1, 1e-3);  // chords of the 256-gon dip by up to 1.1 (1 - cos(pi/256))
  EXPECT_LT(boundary_distance(unit, true, unit).max, 1e-12);
}

TEST(EllipsoidShadow, BadInput_Throws) {
  EXPECT_THROW((void)ellipsoid_shadow_boundary({}, Light{{0, 0.5, 0, 1}}, kFloor, 16), std::invalid_argument);
  EXPECT_THROW((void)ellipsoid_shadow_boundary({}, Light{{0, 1, 0, 0}}, kFloor, 2), std::invalid_argument);
  // A sun along the floor: the tangent rays never reach it.
  EXPECT_THROW((void)ellipsoid_shadow_boundary({}, Light{{1, 0, 0, 0}}, kFloor, 16), std::invalid_argument);
  EXPECT_THROW((void)boundary_distance(std::vector<Vec3>{{0, 0, 0}}, true, std::vector<Vec3>(3)), std::invalid_argument);
}

}  // namespace
