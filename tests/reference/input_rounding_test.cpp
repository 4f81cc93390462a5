// The scene as a float renderer receives it (reference/input_rounding.h): rounding, and the pixels
// whose exact answer it changes. docs/definitions.md#hard-cases's floor lit one double ulp above its plane is
// lit exactly, but in float the light lies on the floor: every floor pixel becomes ambiguous.
#include "reference/input_rounding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/certificate_test_support.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

Camera small_camera() {
  Camera camera;
  camera.eye = {0.5, 4.0, 6.0};
  camera.target = {0.0, 1.0, 0.0};
  camera.width = 48;
  camera.height = 36;
  return camera;
}

Soup floor_at_height_one() {
  Soup soup = floor_quad(4.0);
  for (Vec3& v : soup.vertices) v[1] = 1.0;
  test_support::append(soup, box({-0.5, 1.5, -0.5}, {0.5, 2.5, 0.5}));
  return soup;
}

std::size_t marked(const ExactImage& image, std::size_t light) {
  std::size_t n = 0;
  for (std::uint8_t a : image.lights.at(light).ambiguity) n += (a & kInputRounding) != 0;
  return n;
}

TEST(InputRounding, FloatRounded_RoundsEachCoordinateToTheNearestFloat) {
  Soup soup = test_support::soup_of({{0.1, 1.0 + 0x1p-52, -1e6 - 0.001}}, {});
  const Soup r = float_rounded(soup);
  ASSERT_NE(static_cast<double>(0.1f), 0.1);
  EXPECT_EQ(r.vertices[0][0], static_cast<double>(0.1f));
  EXPECT_EQ(r.vertices[0][1], 1.0);
  EXPECT_EQ(r.vertices[0][2], -1e6);
  const Light l = float_rounded(Light{{0.1, 2.0, 3.0, 0.0}});
  EXPECT_EQ(l.position[0], static_cast<double>(0.1f));
  EXPECT_EQ(l.position[3], 0.0);
}

TEST(InputRounding, LightOneUlpAboveTheFloor_MakesTheFloorAmbiguous) {
  const Soup soup = floor_at_height_one();
  const std::vector<Light> lights{test_support::point_light(0.25, 1.0 + 0x1p-52, 3.0)};
  ExactImage exact = exact_image(soup, lights, small_camera());
  // Exactly, the floor faces the light: lit, unambiguous floor pixels exist.
  std::size_t lit_floor = 0;
  for (std::size_t p = 0; p < exact.hit_triangles.size(); ++p)
    lit_floor += exact.hit_triangles[p] <= 1 && exact.lights[0].ambiguity[p] == 0 && exact.lights[0].counts[p] == 0;
  ASSERT_GT(lit_floor, 500u);
  const ExactImage rounded = exact_image(float_rounded(soup), std::vector<Light>{float_rounded(lights[0])}, small_camera());
  mark_input_rounding(exact, rounded);
  // In float the light is in the floor's plane: the terminator, on every floor pixel. The
  // ones the exact image found unambiguous are the ones rounding marks.
  for (std::size_t p = 0; p < exact.hit_triangles.size(); ++p) {
    if (exact.hit_triangles[p] <= 1) {
      EXPECT_NE(exact.lights[0].ambiguity[p], 0) << "pixel " << p;
    }
  }
  EXPECT_EQ(marked(exact, 0), lit_floor);
}

TEST(InputRounding, FloatExactScene_MarksNothing) {
  const Soup soup = floor_at_height_one();  // every coordinate a float
  const std::vector<Light> lights{test_support::point_light(0.25, 6.0, 3.0)};
  ExactImage exact = exact_image(soup, lights, small_camera());
  const ExactImage again = exact_image(float_rounded(soup), std::vector<Light>{float_rounded(lights[0])}, small_camera());
  mark_input_rounding(exact, again);
  EXPECT_EQ(marked(exact, 0), 0u);
}

TEST(InputRounding, DifferentImages_Throw) {
  const Soup soup = floor_at_height_one();
  ExactImage exact = exact_image(soup, std::vector<Light>{test_support::point_light(0, 6, 0)}, small_camera());
  const ExactImage none = exact_image(soup, std::vector<Light>{}, small_camera());
  EXPECT_THROW(mark_input_rounding(exact, none), std::invalid_argument);
}

}  // namespace
