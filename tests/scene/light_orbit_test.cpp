// scene/light_orbit.h: `shadowcert track`'s default light path.
#include "scene/light_orbit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace {

using namespace shadowcert;

TEST(LightOrbit, Default_CentredOnTheBoxAtTwiceItsHalfDiagonalAndHalfAboveIt) {
  const LightOrbit o = default_light_orbit(Box{{-1, 0, -3}, {1, 2, 1}});  // half sizes 1, 1, 2
  EXPECT_EQ(o.center, (Vec3{0, 1, -1}));
  EXPECT_DOUBLE_EQ(o.radius, 2.0 * std::sqrt(6.0));
  EXPECT_DOUBLE_EQ(o.height, 0.5 * std::sqrt(6.0));
  EXPECT_EQ(o.turns, 1.0);
  const LightOrbit point = default_light_orbit(Box{{3, 3, 3}, {3, 3, 3}});
  EXPECT_EQ(point.radius, kOrbitRadiusScale);
}

TEST(LightOrbit, Lights_CircleTheAxisAtTheRadiusAndHeight) {
  const LightOrbit o{{1, 2, 3}, 4.0, 0.5, 2.0};
  const std::vector<Light> lights = orbit_lights(o, 8);
  ASSERT_EQ(lights.size(), 8u);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const auto& l = lights[i].position;
    EXPECT_EQ(l[3], 1.0);
    EXPECT_DOUBLE_EQ(l[1], 2.5);
    EXPECT_NEAR(std::hypot(l[0] - 1, l[2] - 3), 4.0, 1e-12);
    const double angle = 2.0 * 3.141592653589793 * 2.0 * static_cast<double>(i) / 8.0;  // two turns
    EXPECT_NEAR(l[0], 1 + 4 * std::cos(angle), 1e-12);
    EXPECT_NEAR(l[2], 3 + 4 * std::sin(angle), 1e-12);
  }
  EXPECT_NEAR(lights[4].position[0], lights[0].position[0], 1e-12);  // a turn in four frames
}

TEST(LightOrbit, BadOrbits_Throw) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)orbit_lights(LightOrbit{}, 0), std::invalid_argument);
  EXPECT_THROW((void)orbit_lights(LightOrbit{{0, 0, 0}, 0.0, 0.0, 1.0}, 4), std::invalid_argument);
  EXPECT_THROW((void)orbit_lights(LightOrbit{{0, 0, 0}, nan, 0.0, 1.0}, 4), std::invalid_argument);
  EXPECT_THROW((void)orbit_lights(LightOrbit{{0, 0, 0}, 1.0, nan, 1.0}, 4), std::invalid_argument);
  EXPECT_THROW((void)orbit_lights(LightOrbit{{nan, 0, 0}, 1.0, 0.0, 1.0}, 4), std::invalid_argument);
}

}  // namespace
