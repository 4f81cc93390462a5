// pipeline/contour_error.h: a smooth-silhouette method's shadow boundary against the analytic
// conic, as bench/smooth_silhouette_bench.cpp measures it (docs/smooth-silhouettes.md's table).
#include "pipeline/contour_error.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "scene/framed_scene.h"
#include "scene/procedural_mesh.h"

namespace shadowcert {
namespace {

const Plane kFloor{{0.0, kAnalyticFloorHeight, 0.0}, {0.0, 1.0, 0.0}};

Scene shape(std::size_t index, const Light& light) {
  return analytic_shape_scene(analytic_shapes().at(index), light, 64, 48);
}

TEST(ContourError, Sphere8x4PointLight_TheTableFigures) {
  const Scene scene = shape(0, kAnalyticPointLight);
  const std::optional<ContourError> discrete = contour_error(scene, 0, gpu::ShadowMethod::discrete, 0.01, kFloor);
  const std::optional<ContourError> smooth = contour_error(scene, 0, gpu::ShadowMethod::smooth, 0.01, kFloor);
  ASSERT_TRUE(discrete && smooth);
  // docs/smooth-silhouettes.md: 0.1951 / 0.0978 and 0.0259 / 0.0112.
  EXPECT_NEAR(discrete->max, 0.1951, 5e-4);
  EXPECT_NEAR(discrete->mean, 0.0978, 5e-4);
  EXPECT_NEAR(smooth->max, 0.0259, 5e-4);
  EXPECT_NEAR(smooth->mean, 0.0112, 5e-4);
  EXPECT_EQ(discrete->casters, 1u);
  EXPECT_GT(smooth->points, discrete->points);
  // smooth-gpu casts smooth's contour.
  const std::optional<ContourError> gpu_smooth = contour_error(scene, 0, gpu::ShadowMethod::smooth_gpu, 0.01, kFloor);
  ASSERT_TRUE(gpu_smooth);
  EXPECT_DOUBLE_EQ(gpu_smooth->max, smooth->max);
}

TEST(ContourError, FinerSphere_SmallerError) {
  const double coarse = contour_error(shape(0, kAnalyticSun), 0, gpu::ShadowMethod::discrete, 0.01, kFloor)->max;
  const double fine = contour_error(shape(3, kAnalyticSun), 0, gpu::ShadowMethod::discrete, 0.01, kFloor)->max;
  EXPECT_LT(fine, coarse / 5);
}

TEST(ContourError, NoEllipsoidCaster_Nullopt) {
  Scene scene = shape(0, kAnalyticPointLight);
  scene.meshes[1].ellipsoid.reset();
  EXPECT_FALSE(contour_error(scene, 0, gpu::ShadowMethod::smooth, 0.01, kFloor).has_value());
}

TEST(ContourError, BadArguments_Throw) {
  const Scene scene = shape(0, kAnalyticPointLight);
  EXPECT_THROW((void)contour_error(scene, 0, gpu::ShadowMethod::cs, 0.01, kFloor), std::invalid_argument);
  EXPECT_THROW((void)contour_error(scene, 1, gpu::ShadowMethod::smooth, 0.01, kFloor), std::invalid_argument);
  EXPECT_THROW((void)contour_error(scene, 0, gpu::ShadowMethod::smooth, 0.0, kFloor), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert
