#pragma once
// A pinhole camera: what the GL path renders and the exact image samples (docs/definitions.md#pixel-protocol).
#include <array>
#include <cstdint>

#include "core/soup.h"

namespace shadowcert {

// The GL near plane when nothing fits one (core/near_plane.h fits it to a scene): the far plane
// is at infinity, so that the shadow-volume back caps (points at infinity, w = 0) are never
// clipped (z-fail).
inline constexpr double kDefaultNearPlane = 0.01;

struct Camera {
  Vec3 eye{0.0, 4.0, 8.0};
  Vec3 target{0.0, 0.0, 0.0};
  Vec3 up{0.0, 1.0, 0.0};
  double fov_y_degrees = 45.0;  // vertical field of view, in (0, 180)
  std::uint32_t width = 1024;   // image size in pixels, in [1, kMaxImageSide]
  std::uint32_t height = 768;
  // GL only: the distance from the eye to the near clipping plane, > 0 (gpu/camera_transform.h).
  // The exact image ignores it but for the diff's model of the depth buffer (gpu/depth_precision.h).
  double near_plane = kDefaultNearPlane;
};

// The largest image side anything accepts (scene files, --size): GL_MAX_RENDERBUFFER_SIZE of
// llvmpipe and of every NVIDIA driver we target, so that a scene that reads can be rendered.
inline constexpr std::uint32_t kMaxImageSide = 16384;

}  // namespace shadowcert
