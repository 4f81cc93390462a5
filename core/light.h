#pragma once
// A light in homogeneous coordinates L = (l, w), DESIGN.md §1:
//   w = 1: point light at l;  w = 0: directional light, l points towards the light.
#include <array>
#include <cmath>

namespace shadowcert {

struct Light {
  std::array<double, 4> position{0.0, 10.0, 0.0, 1.0};  // x, y, z, w with w in {0, 1}

  [[nodiscard]] bool directional() const { return position[3] == 0.0; }

  // DESIGN.md §1's form: finite l and w exactly 0 or 1.
  [[nodiscard]] bool well_formed() const {
    return std::isfinite(position[0]) && std::isfinite(position[1]) && std::isfinite(position[2]) &&
           (position[3] == 0.0 || position[3] == 1.0);
  }
  // A light every predicate is defined for: well formed, and a directional light has a
  // nonzero direction. Callers that report the two failures apart test well_formed() first.
  [[nodiscard]] bool defined() const {
    return well_formed() && !(position[3] == 0.0 && position[0] == 0.0 && position[1] == 0.0 && position[2] == 0.0);
  }
};

}  // namespace shadowcert
