// core/near_plane.h: the distance to a triangle, and the near plane fitted to a scene (what GL
// clips at and the diff's depth band assumes).
#include "core/near_plane.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using namespace shadowcert;

Soup one_triangle(const Vec3& a, const Vec3& b, const Vec3& c) { return Soup{{a, b, c}, {{0, 1, 2}}, {}}; }

double fitted(const Soup& soup, const Vec3& eye) {
  const Soup* soups[] = {&soup};
  return fitted_near_plane(soups, eye);
}

// The smallest distance from p to points a + s (b - a) + t (c - a) on a fine barycentric grid:
// an upper bound of the true distance, within the grid's spacing of it.
double sampled_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  constexpr int kSteps = 200;
  double best = INFINITY;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; i + j <= kSteps; ++j) {
      const double s = double(i) / kSteps, t = double(j) / kSteps;
      Vec3 q{};
      for (std::size_t k = 0; k < 3; ++k) q[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]);
      const Vec3 d = difference(p, q);
      best = std::min(best, std::sqrt(dot(d, d)));
    }
  return best;
}

TEST(DistanceToTriangle, EachVoronoiRegion_GivesTheEuclideanDistance) {
  const Vec3 a{0, 0, 0}, b{2, 0, 0}, c{0, 2, 0};
  EXPECT_DOUBLE_EQ(distance_to_triangle({0.5, 0.5, 3}, a, b, c), 3.0);             // above the face
  EXPECT_DOUBLE_EQ(distance_to_triangle({-3, -4, 0}, a, b, c), 5.0);               // vertex a
  EXPECT_DOUBLE_EQ(distance_to_triangle({5, -4, 0}, a, b, c), 5.0);                // vertex b
  EXPECT_DOUBLE_EQ(distance_to_triangle({1, -2, 0}, a, b, c), 2.0);                // edge ab
  EXPECT_DOUBLE_EQ(distance_to_triangle({2, 2, 0}, a, b, c), std::sqrt(2.0));      // edge bc
  EXPECT_DOUBLE_EQ(distance_to_triangle({-1, 1, 1}, a, b, c), std::sqrt(2.0));     // edge ca
}

TEST(DistanceToTriangle, DegenerateTriangles_GiveTheDistanceToTheirSegment) {
  // Collinear (c between a and b) and a point triangle.
  EXPECT_DOUBLE_EQ(distance_to_triangle({1, 3, 0}, {0, 0, 0}, {4, 0, 0}, {2, 0, 0}), 3.0);
  EXPECT_DOUBLE_EQ(distance_to_triangle({6, 0, 0}, {0, 0, 0}, {4, 0, 0}, {2, 0, 0}), 2.0);
  EXPECT_DOUBLE_EQ(distance_to_triangle({1, 1, 1}, {1, 1, 0}, {1, 1, 0}, {1, 1, 0}), 1.0);
}

TEST(DistanceToTriangle, RandomTriangles_MatchDenseSampling) {
  const unsigned seed = 20261201;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  const auto point = [&] { return Vec3{coordinate(random), coordinate(random), coordinate(random)}; };
  for (int n = 0; n < 200; ++n) {
    const Vec3 a = point(), b = point(), c = point(), p = point();
    const double exact = distance_to_triangle(p, a, b, c);
    const double sampled = sampled_distance(p, a, b, c);
    // The grid's points are on the triangle (sampled >= exact) and within one cell of the
    // closest point (a cell's diameter is at most the longest edge / 200).
    EXPECT_LE(exact, sampled + 1e-12) << n;
    EXPECT_GE(exact, sampled - 2.0 * 3.5 / 200) << n;
  }
}

TEST(FittedNearPlane, UnitScene_KeepsTheDefault) {
  const Soup floor = one_triangle({-5, 0, -5}, {5, 0, -5}, {0, 0, 5});
  EXPECT_EQ(fitted(floor, {0, 4, 8}), kDefaultNearPlane);
}

TEST(FittedNearPlane, FarScene_KeepsTheFarthestVertexWithin2048NearDistances) {
  // fuzz --gl seed 101 case 227's scale: a soup at 2^17 seen from 1.3e6 away; the default near
  // plane put it at window depth 1 - 8e-9, which rounds to the cleared depth 1.
  const Soup soup = one_triangle({-1343019.75, -453212.625, -949803.8125}, {-1343019.75, -453212.625, 1343019.75},
                                 {949803.8125, -453212.625, 1343019.75});
  const Vec3 eye{402535.674998733, 748929.5937484162, 995466.233331644};
  const double near = fitted(soup, eye);
  double farthest = 0.0;
  for (const Vec3& v : soup.vertices) farthest = std::max(farthest, std::sqrt(dot(difference(v, eye), difference(v, eye))));
  EXPECT_GT(near, kDefaultNearPlane);
  EXPECT_LE(farthest / near, kFarOverNear * (1.0 + 1e-12));
  // In float, as GL computes it, the farthest vertex's window depth stays below 1.
  EXPECT_LT(1.0f - static_cast<float>(near / farthest), 1.0f);
  EXPECT_LE(near, kNearClipShare * distance_to_triangle(eye, soup.vertices[0], soup.vertices[1], soup.vertices[2]));
}

TEST(FittedNearPlane, EyeCloseToATriangle_ClipsNothing) {
  const Soup room = one_triangle({-1000, 0, -1000}, {1000, 0, -1000}, {0, 0, 1000});
  const double near = fitted(room, {0, 0.004, 0});  // 4 mm over a 2 km floor
  EXPECT_LE(near, 0.002);
  EXPECT_GT(near, 0.0);
}

TEST(FittedNearPlane, TinyScene_ShrinksBelowTheDefault) {
  const Soup speck = one_triangle({0, 0, 0}, {1e-6, 0, 0}, {0, 1e-6, 0});
  const double near = fitted(speck, {0, 0, 1e-5});
  EXPECT_LE(near, 0.5e-5);
  EXPECT_GT(near, 0.0);
}

TEST(FittedNearPlane, Translation_LeavesItUnchanged) {
  const Soup soup = one_triangle({3e4, 1e4, 0}, {4e4, 1e4, 0}, {3e4, 2e4, 5e3});
  const Vec3 eye{9e4, 6e4, 7e4};
  const double near = fitted(soup, eye);
  Soup moved = soup;
  const Vec3 offset{1024.0, -2048.0, 512.0};  // exact in double at these magnitudes
  for (Vec3& v : moved.vertices) v = {v[0] + offset[0], v[1] + offset[1], v[2] + offset[2]};
  EXPECT_DOUBLE_EQ(fitted(moved, {eye[0] + offset[0], eye[1] + offset[1], eye[2] + offset[2]}), near);
}

TEST(FittedNearPlane, EyeOnATriangle_StaysPositive) {
  const Soup floor = one_triangle({-1, 0, -1}, {1, 0, -1}, {0, 0, 1});
  const double near = fitted(floor, {0, 0, 0});
  EXPECT_GT(near, 0.0);
  EXPECT_EQ(near, kDefaultNearPlane);
}

TEST(FittedNearPlane, EmptyScene_GivesTheDefault) {
  const Soup empty;
  EXPECT_EQ(fitted(empty, {1, 2, 3}), kDefaultNearPlane);
}

}  // namespace
