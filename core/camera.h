#pragma once
// A pinhole camera: what the GL path renders and the exact image samples (DESIGN.md §5).
#include <array>
#include <cstdint>

#include "core/soup.h"

namespace shadowcert {

struct Camera {
  Vec3 eye{0.0, 4.0, 8.0};
  Vec3 target{0.0, 0.0, 0.0};
  Vec3 up{0.0, 1.0, 0.0};
  double fov_y_degrees = 45.0;  // vertical field of view, in (0, 180)
  std::uint32_t width = 1024;   // image size in pixels, >= 1
  std::uint32_t height = 768;
};

}  // namespace shadowcert
