#include "gpu/camera_transform.h"

#include <cmath>
#include <stdexcept>

#include "core/pixel_ray.h"

namespace shadowcert::gpu {
namespace {

glm::dvec3 to_glm(const Vec3& v) { return {v[0], v[1], v[2]}; }

}  // namespace

// GLM's lookAt matrix (rows right, up, -forward; the eye at the origin), built from
// core/pixel_ray.h's frame so that the exact image's pixel rays are this camera's.
glm::dmat4 view_matrix(const Camera& camera) {
  const CameraFrame f = camera_frame(camera, "view_matrix");
  glm::dmat4 m(1.0);
  for (int k = 0; k < 3; ++k) {
    m[k][0] = f.right[k];
    m[k][1] = f.up[k];
    m[k][2] = -f.forward[k];
  }
  m[3][0] = -shadowcert::dot(f.right, f.eye);
  m[3][1] = -shadowcert::dot(f.up, f.eye);
  m[3][2] = shadowcert::dot(f.forward, f.eye);
  return m;
}

// GLM's infinitePerspective (right-handed, clip z in [-w, w]) with the frame's half extents:
// view-space x / -z = half_width maps to NDC x = 1, as pixel_ray assumes.
glm::dmat4 projection_matrix(const Camera& camera) {
  const CameraFrame f = camera_frame(camera, "projection_matrix");
  const double z_near = camera.near_plane;
  if (!(z_near > 0.0) || !std::isfinite(z_near))
    throw std::invalid_argument("projection_matrix: the camera's near plane must be finite and > 0");
  glm::dmat4 m(0.0);
  m[0][0] = 1.0 / f.half_width;
  m[1][1] = 1.0 / f.half_height;
  m[2][2] = -1.0;
  m[2][3] = -1.0;
  m[3][2] = -2.0 * z_near;
  return m;
}

glm::dvec2 project_to_image(const Camera& camera, const Vec3& point) {
  const glm::dvec4 clip = projection_matrix(camera) * view_matrix(camera) * glm::dvec4(to_glm(point), 1.0);
  if (!(clip.w > 0.0)) throw std::invalid_argument("project_to_image: point not in front of the camera");
  const glm::dvec2 ndc(clip.x / clip.w, clip.y / clip.w);
  // NDC [-1, 1] -> window [0, size] (glViewport), then y flipped to the top-down image.
  const double x = (ndc.x + 1.0) * 0.5 * camera.width;
  const double y_window = (ndc.y + 1.0) * 0.5 * camera.height;
  return {x, camera.height - y_window};
}

}  // namespace shadowcert::gpu
