#pragma once
// A light in homogeneous coordinates L = (l, w), DESIGN.md §1:
//   w = 1: point light at l;  w = 0: directional light, l points towards the light.
#include <array>

namespace shadowcert {

struct Light {
  std::array<double, 4> position{0.0, 10.0, 0.0, 1.0};  // x, y, z, w with w in {0, 1}

  [[nodiscard]] bool directional() const { return position[3] == 0.0; }
};

}  // namespace shadowcert
