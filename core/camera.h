#pragma once
// A pinhole camera: what the GL path renders and the exact image samples (docs/definitions.md#pixel-protocol).
#include <array>
#include <cstdint>

#include "core/soup.h"

namespace shadowcert {

struct Camera {
  Vec3 eye{0.0, 4.0, 8.0};
  Vec3 target{0.0, 0.0, 0.0};
  Vec3 up{0.0, 1.0, 0.0};
  double fov_y_degrees = 45.0;  // vertical field of view, in (0, 180)
  std::uint32_t width = 1024;   // image size in pixels, in [1, kMaxImageSide]
  std::uint32_t height = 768;
};

// The largest image side anything accepts (scene files, --size): GL_MAX_RENDERBUFFER_SIZE of
// llvmpipe and of every NVIDIA driver we target, so that a scene that reads can be rendered.
inline constexpr std::uint32_t kMaxImageSide = 16384;

}  // namespace shadowcert
