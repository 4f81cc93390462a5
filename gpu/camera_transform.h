#pragma once
// core::Camera to GL matrices (GLM, computed in double) and the pixel convention shared with
// the exact module (docs/definitions.md#pixel-protocol, docs/gpu.md):
//   image pixel (i, r), row r = 0 at the TOP, covers [i, i+1) x [r, r+1) in image
//   coordinates; its centre is (i + 0.5, r + 0.5). In GL window coordinates (origin at the
//   bottom left) that centre is (i + 0.5, height - r - 0.5): GL samples exactly there, and
//   readback (gpu/offscreen_target.h) flips rows so that row 0 is the top one.
// Both matrices are built from core/pixel_ray.h's camera_frame, the basis the exact image
// (reference/exact_image.h) casts its pixel rays with: the two sides share one camera by
// construction (tests/gpu/camera_transform_test.cpp).
#include <glm/glm.hpp>

#include "core/camera.h"
#include "core/soup.h"

namespace shadowcert::gpu {

// Throws std::invalid_argument naming the function for a degenerate camera (eye == target,
// up parallel to the view direction, fov outside (0, 180), empty image).
[[nodiscard]] glm::dmat4 view_matrix(const Camera& camera);
// The projection's near plane is camera.near_plane (core/near_plane.h fits it to a scene); its
// far plane is at infinity, so that back caps (w = 0) are never clipped.
[[nodiscard]] glm::dmat4 projection_matrix(const Camera& camera);

// Where a world point lands in image coordinates (x right, y DOWN, pixel (i, r)'s centre at
// (i + 0.5, r + 0.5)); for tests. The point must be in front of the camera.
[[nodiscard]] glm::dvec2 project_to_image(const Camera& camera, const Vec3& point);

}  // namespace shadowcert::gpu
