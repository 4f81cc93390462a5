#pragma once
// The camera's frame and its pixel rays, in double: the one definition of "which ray a pixel
// samples" that the GL path (gpu/camera_transform.cpp builds its view and projection matrices
// from camera_frame) and the exact image (reference/exact_image.h) share, so both agree by
// construction (docs/definitions.md#pixel-protocol).
//
// Pixel convention (docs/gpu.md): image pixel (i, r), row r = 0 at the TOP, covers
// [i, i+1) x [r, r+1) in image coordinates (x right, y down); its centre is (i + 0.5, r + 0.5)
// and its corners are the integer points. GL samples the centre.
//
// The frame is GLM's lookAt basis (right-handed, the camera looks along -z of its view space):
//   forward = normalize(target - eye), right = normalize(forward x up), up' = right x forward,
// and the image plane at distance 1 along forward spans [-half_width, half_width] along right
// and [-half_height, half_height] along up', half_height = tan(fov_y / 2) and
// half_width = half_height * width / height.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/camera.h"
#include "core/portable_math.h"
#include "core/soup.h"
#include "core/vector3.h"

namespace shadowcert {

struct CameraFrame {
  Vec3 eye{};
  Vec3 right{};    // unit, image x grows along it
  Vec3 up{};       // unit, image y grows against it (rows run top to bottom)
  Vec3 forward{};  // unit, from the eye towards the target
  double half_width = 0.0;   // the image plane's half extents at distance 1 along forward
  double half_height = 0.0;
  std::uint32_t width = 0;   // image size in pixels, from the camera
  std::uint32_t height = 0;
};

// A ray from `origin` along `direction` (not unit length; nonzero). Both are plain doubles:
// the exact image decides everything about this very ray, never about a rounded copy of it.
struct PixelRay {
  Vec3 origin{};
  Vec3 direction{};
};


// Throws std::invalid_argument naming `function` (default "camera_frame") for a degenerate
// camera: a non-finite vector, eye == target, up parallel to the view direction, fov_y outside
// (0, 180) degrees, or an empty image.
[[nodiscard]] inline CameraFrame camera_frame(const Camera& camera, const char* function = "camera_frame") {
  const auto fail = [function](const char* what) { throw std::invalid_argument(std::string(function) + ": " + what); };
  for (const Vec3* v : {&camera.eye, &camera.target, &camera.up})
    for (double x : *v)
      if (!std::isfinite(x)) fail("camera eye, target and up must be finite");
  const Vec3 view{camera.target[0] - camera.eye[0], camera.target[1] - camera.eye[1], camera.target[2] - camera.eye[2]};
  if (dot(view, view) == 0.0) fail("eye == target");
  const Vec3 side = cross(view, camera.up);
  if (dot(side, side) == 0.0) fail("up is parallel to the view direction");
  if (!(camera.fov_y_degrees > 0.0 && camera.fov_y_degrees < 180.0)) fail("fov_y_degrees outside (0, 180)");
  if (camera.width == 0 || camera.height == 0) fail("empty image");

  CameraFrame frame;
  frame.eye = camera.eye;
  frame.forward = normalized(view);
  frame.right = normalized(cross(frame.forward, camera.up));
  frame.up = cross(frame.right, frame.forward);
  constexpr double kPi = 3.14159265358979323846;
  frame.half_height = portable::tan(camera.fov_y_degrees * (kPi / 180.0) / 2.0);
  // The aspect first, as GLM's perspective does: a square image gets half_width == half_height.
  frame.half_width = frame.half_height * (static_cast<double>(camera.width) / static_cast<double>(camera.height));
  frame.width = camera.width;
  frame.height = camera.height;
  return frame;
}

// The ray through image point (x, y) (x right, y down; pixel (i, r)'s centre is
// (i + 0.5, r + 0.5)): origin = eye, direction = forward + a right + b up with
// a = (2x / width - 1) half_width and b = (1 - 2y / height) half_height, each rounded once
// in double. Any finite (x, y) is allowed (corners of border pixels included).
// Its parts, for callers that keep a and b per column and row (the exact image's ray grid):
// pixel_ray(frame, x, y) == pixel_ray_through(frame, pixel_ray_a(frame, x), pixel_ray_b(frame, y)).
[[nodiscard]] inline double pixel_ray_a(const CameraFrame& frame, double x) {
  return (2.0 * x / frame.width - 1.0) * frame.half_width;
}
[[nodiscard]] inline double pixel_ray_b(const CameraFrame& frame, double y) {
  return (1.0 - 2.0 * y / frame.height) * frame.half_height;
}
[[nodiscard]] inline PixelRay pixel_ray_through(const CameraFrame& frame, double a, double b) {
  PixelRay ray;
  ray.origin = frame.eye;
  for (int k = 0; k < 3; ++k) ray.direction[k] = frame.forward[k] + a * frame.right[k] + b * frame.up[k];
  return ray;
}
[[nodiscard]] inline PixelRay pixel_ray(const CameraFrame& frame, double x, double y) {
  return pixel_ray_through(frame, pixel_ray_a(frame, x), pixel_ray_b(frame, y));
}

}  // namespace shadowcert
