#include "gpu/camera_transform.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <stdexcept>

namespace shadowcert::gpu {
namespace {

glm::dvec3 to_glm(const Vec3& v) { return {v[0], v[1], v[2]}; }

void check(const Camera& camera, const char* function) {
  const glm::dvec3 forward = to_glm(camera.target) - to_glm(camera.eye);
  if (glm::length(forward) == 0.0) throw std::invalid_argument(std::string(function) + ": eye == target");
  if (glm::length(glm::cross(forward, to_glm(camera.up))) == 0.0) {
    throw std::invalid_argument(std::string(function) + ": up is parallel to the view direction");
  }
  if (!(camera.fov_y_degrees > 0.0 && camera.fov_y_degrees < 180.0)) {
    throw std::invalid_argument(std::string(function) + ": fov_y_degrees outside (0, 180)");
  }
  if (camera.width == 0 || camera.height == 0) throw std::invalid_argument(std::string(function) + ": empty image");
}

}  // namespace

glm::dmat4 view_matrix(const Camera& camera) {
  check(camera, "view_matrix");
  return glm::lookAt(to_glm(camera.eye), to_glm(camera.target), to_glm(camera.up));
}

glm::dmat4 projection_matrix(const Camera& camera, double z_near) {
  check(camera, "projection_matrix");
  if (!(z_near > 0.0)) throw std::invalid_argument("projection_matrix: z_near must be > 0");
  const double aspect = static_cast<double>(camera.width) / static_cast<double>(camera.height);
  return glm::infinitePerspective(glm::radians(camera.fov_y_degrees), aspect, z_near);
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
