// contour/smooth_contour.h: the Hermite displacement and adaptive subdivision, held to the true
// silhouette of a sphere (the circle where the light's tangent cone touches it): the smooth
// contour is nearer to it than the accurate silhouette, nearer as epsilon falls, and nearly
// independent of the tessellation.
#include "contour/smooth_contour.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/vector3.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

constexpr double kLightDistance = 4.0;  // a point light on +z, 4 radii from the unit sphere's centre

SmoothCaster sphere_caster(std::uint32_t slices, std::uint32_t stacks) {
  return *smooth_caster(uv_sphere({0, 0, 0}, 1.0, slices, stacks)).caster;
}

const Light kLight{{0.0, 0.0, kLightDistance, 1.0}};

// Distance from p to the unit sphere's silhouette circle for kLight: z = 1/d, radius sqrt(1 - 1/d^2).
double circle_distance(const Vec3& p) {
  const double z0 = 1.0 / kLightDistance, r0 = std::sqrt(1.0 - z0 * z0);
  const double rho = std::hypot(p[0], p[1]);
  return std::hypot(rho - r0, p[2] - z0);
}

double accurate_error(const std::vector<SilhouetteLoop>& loops) {
  double worst = 0.0;
  for (const auto& loop : loops)
    for (const auto& p : loop.points) worst = std::max(worst, circle_distance(p.position));
  return worst;
}

double smooth_error(const std::vector<SmoothContour>& contours) {
  double worst = 0.0;
  for (const auto& contour : contours)
    for (const auto& p : contour.points) worst = std::max(worst, circle_distance(p.position));
  return worst;
}

TEST(HermiteCurve, EndsAtItsEndPoints_AndFollowsACircleArc) {
  const Vec3 p0{1, 0, 0}, p1{0, 1, 0};
  const Vec3 t0 = hermite_tangent(p0, p1, {1, 0, 0}), t1 = hermite_tangent(p0, p1, {0, 1, 0});
  EXPECT_NEAR(t0[1], std::sqrt(2.0), 1e-15);
  EXPECT_EQ(hermite_point(p0, p1, t0, t1, 0.0), p0);
  EXPECT_EQ(hermite_point(p0, p1, t0, t1, 1.0), p1);
  for (double u : {0.25, 0.5, 0.75}) {
    const Vec3 p = hermite_point(p0, p1, t0, t1, u);
    // Within 5% of a quarter circle: tangents of length |e| (the paper's scale) undershoot the
    // arc's 4 tan(pi / 8) = 1.66 a little, so the midpoint lies 4.3% inside.
    EXPECT_NEAR(std::sqrt(dot(p, p)), 1.0, 0.05) << u;
  }
  EXPECT_EQ(hermite_tangent(p0, p0, {1, 0, 0}), (Vec3{0, 0, 0}));  // a zero-length segment
}

TEST(SmoothContour, CoarseSphere_IsNearerTheTrueSilhouetteThanTheAccurateOne) {
  const SmoothCaster c = sphere_caster(12, 6);
  const auto loops = accurate_silhouette(c, kLight);
  const auto contours = smooth_contour(c, loops, 0.01);
  ASSERT_EQ(contours.size(), 1u);
  EXPECT_TRUE(contours[0].closed);
  EXPECT_GT(contours[0].points.size(), loops[0].points.size());
  const double accurate = accurate_error(loops), smooth = smooth_error(contours);
  EXPECT_GT(accurate, 0.02);   // the chords of a 12 x 6 sphere cut deep
  EXPECT_LT(smooth, 0.5 * accurate);
}

TEST(SmoothContour, ErrorFallsAsEpsilonFalls) {
  const SmoothCaster c = sphere_caster(16, 8);
  const auto loops = accurate_silhouette(c, kLight);
  double previous = INFINITY;
  std::size_t previous_points = 0;
  for (double eps : {0.1, 0.03, 0.01, 0.003}) {
    const auto contours = smooth_contour(c, loops, eps);
    const double error = smooth_error(contours);
    EXPECT_LE(error, previous * 1.05) << eps;  // Hermite points move little once dense
    EXPECT_GE(contours[0].points.size(), previous_points) << eps;
    previous = error;
    previous_points = contours[0].points.size();
  }
}

TEST(SmoothContour, ErrorIsNearlyIndependentOfTheTessellation) {
  // The paper's claim: the smooth contour of an 8 x 4 sphere is about as near the truth as that
  // of a 64 x 32 one, where the accurate silhouettes differ by far more.
  double smooth_worst = 0.0, smooth_best = INFINITY, accurate_coarse = 0.0, accurate_fine = 0.0;
  for (const auto& [slices, stacks] : {std::pair{8u, 4u}, {16u, 8u}, {32u, 16u}, {64u, 32u}}) {
    const SmoothCaster c = sphere_caster(slices, stacks);
    const auto loops = accurate_silhouette(c, kLight);
    const double s = smooth_error(smooth_contour(c, loops, 0.01));
    smooth_worst = std::max(smooth_worst, s);
    smooth_best = std::min(smooth_best, s);
    if (slices == 8) accurate_coarse = accurate_error(loops);
    if (slices == 64) accurate_fine = accurate_error(loops);
  }
  EXPECT_GT(accurate_coarse, 10.0 * accurate_fine);
  EXPECT_LT(smooth_worst, 0.05);
}

TEST(SmoothContour, PartnersStayOnTheMeshAndStartAsTheLoopPoints) {
  const SmoothCaster c = sphere_caster(12, 6);
  const auto loops = accurate_silhouette(c, kLight);
  const auto contours = smooth_contour(c, loops, 0.003);
  std::size_t matched = 0;
  for (const ContourPoint& p : contours[0].points) {
    EXPECT_LE(std::sqrt(dot(p.partner, p.partner)), 1.0 + 1e-12);  // inside the sphere: on its chords
    EXPECT_NEAR(dot(p.normal, p.normal), 1.0, 1e-12);
    for (const SilhouettePoint& s : loops[0].points) matched += s.position == p.partner;
  }
  EXPECT_EQ(matched, loops[0].points.size());
}

TEST(SmoothContour, BadEpsilon_Throws) {
  const SmoothCaster c = sphere_caster(8, 4);
  const auto loops = accurate_silhouette(c, kLight);
  for (double eps : {0.0, -1.0, double(NAN), double(INFINITY)}) EXPECT_THROW((void)smooth_contour(c, loops, eps), std::invalid_argument);
}

}  // namespace
