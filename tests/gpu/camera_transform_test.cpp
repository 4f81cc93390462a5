// The GL camera (gpu/camera_transform.h) and the exact image's pixel rays (core/pixel_ray.h)
// are one camera (docs/definitions.md#pixel-protocol): a point on the ray of image point (x, y) projects back to
// (x, y). Pure double math: no GL context needed.
#include "gpu/camera_transform.h"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <string>

#include "core/pixel_ray.h"
#include "square_test_camera.h"

namespace shadowcert::gpu {
namespace {

// Both sides compute in double: the frame once, the matrices and the projection each with a
// few dozen roundings of relative size 2^-53 on coordinates below 1e3, amplified by at most
// the image size (1024 px per unit of NDC); 1e-9 px is far above that and far below any
// pixel-scale disagreement.
constexpr double kProjectionTolerancePx = 1e-9;

void expect_rays_project_to_their_pixels(const Camera& camera) {
  const CameraFrame frame = camera_frame(camera);
  for (std::uint32_t r : {0u, camera.height / 3, camera.height - 1})
    for (std::uint32_t i : {0u, camera.width / 2, camera.width - 1})
      for (double t : {0.5, 3.0, 100.0}) {
        const double x = i + 0.5, y = r + 0.5;
        const PixelRay ray = pixel_ray(frame, x, y);
        const Vec3 p{ray.origin[0] + t * ray.direction[0], ray.origin[1] + t * ray.direction[1],
                     ray.origin[2] + t * ray.direction[2]};
        const glm::dvec2 image = project_to_image(camera, p);
        EXPECT_NEAR(image.x, x, kProjectionTolerancePx) << "pixel " << i << "," << r << " t " << t;
        EXPECT_NEAR(image.y, y, kProjectionTolerancePx) << "pixel " << i << "," << r << " t " << t;
      }
  // Corners of the image: image points (0, 0) and (width, height).
  for (const std::array<double, 2>& corner : {std::array<double, 2>{0.0, 0.0},
                                              std::array<double, 2>{double(camera.width), double(camera.height)}}) {
    const PixelRay ray = pixel_ray(frame, corner[0], corner[1]);
    const Vec3 p{ray.origin[0] + 2.0 * ray.direction[0], ray.origin[1] + 2.0 * ray.direction[1],
                 ray.origin[2] + 2.0 * ray.direction[2]};
    const glm::dvec2 image = project_to_image(camera, p);
    EXPECT_NEAR(image.x, corner[0], kProjectionTolerancePx);
    EXPECT_NEAR(image.y, corner[1], kProjectionTolerancePx);
  }
}

TEST(CameraTransform, DefaultSceneCamera_PixelRaysProjectToTheirPixelCentres) {
  Camera camera;
  camera.eye = {0.0, 6.0, 10.0};
  camera.target = {0.0, 0.8, -0.5};
  expect_rays_project_to_their_pixels(camera);
}

TEST(CameraTransform, RandomCameras_PixelRaysProjectToTheirPixelCentres) {
  const std::uint64_t seed = 5;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0), fov(10.0, 120.0);
  std::uniform_int_distribution<std::uint32_t> side(1, 2000);
  for (int k = 0; k < 20; ++k) {
    Camera camera;
    camera.eye = {coordinate(rng), coordinate(rng), coordinate(rng)};
    camera.target = {coordinate(rng), coordinate(rng), coordinate(rng)};
    camera.fov_y_degrees = fov(rng);
    camera.width = side(rng);
    camera.height = side(rng);
    expect_rays_project_to_their_pixels(camera);
  }
}

TEST(CameraTransform, ViewMatrix_IsTheFramesBasis) {
  Camera camera;
  camera.eye = {1.0, 2.0, 3.0};
  camera.target = {-2.0, 0.5, 0.0};
  const CameraFrame frame = camera_frame(camera);
  const glm::dmat4 view = view_matrix(camera);
  for (int k = 0; k < 3; ++k) {  // rows right, up, -forward (column-major storage)
    EXPECT_EQ(view[k][0], frame.right[k]);
    EXPECT_EQ(view[k][1], frame.up[k]);
    EXPECT_EQ(view[k][2], -frame.forward[k]);
  }
  // The eye maps to the origin, up to the rounding of three-term dot products of a unit vector
  // with coordinates below 4: a few ulps of 4.
  constexpr double kEyeRounding = 1e-14;
  const glm::dvec4 eye = view * glm::dvec4(1.0, 2.0, 3.0, 1.0);
  EXPECT_NEAR(eye.x, 0.0, kEyeRounding);
  EXPECT_NEAR(eye.y, 0.0, kEyeRounding);
  EXPECT_NEAR(eye.z, 0.0, kEyeRounding);
}

TEST(CameraTransform, ProjectsWithTheDocumentedPixelConvention) {
  const Camera camera = square_test_camera();
  const auto apex = project_to_image(camera, {0.0, 2.5, 0.0});
  EXPECT_NEAR(apex.x, 32.0, kProjectionTolerancePx);
  EXPECT_NEAR(apex.y, 16.0, kProjectionTolerancePx);  // y grows downwards: row 16 is near the top
  const auto left = project_to_image(camera, {-2.5, -2.5, 0.0});
  EXPECT_NEAR(left.x, 16.0, kProjectionTolerancePx);
  EXPECT_NEAR(left.y, 48.0, kProjectionTolerancePx);
}

TEST(CameraTransform, RejectsDegenerateCameras) {
  Camera camera = square_test_camera();
  camera.target = camera.eye;
  EXPECT_THROW((void)view_matrix(camera), std::invalid_argument);
  camera = square_test_camera();
  camera.up = {0.0, 0.0, -1.0};
  EXPECT_THROW((void)view_matrix(camera), std::invalid_argument);
  camera = square_test_camera();
  camera.fov_y_degrees = 180.0;
  EXPECT_THROW((void)projection_matrix(camera), std::invalid_argument);
}
}  // namespace
}  // namespace shadowcert::gpu
