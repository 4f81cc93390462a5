#pragma once
// A light in homogeneous coordinates L = (l, w), docs/definitions.md#inputs:
//   w = 1: point light at l;  w = 0: directional light, l points towards the light.
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

namespace shadowcert {

struct Light {
  std::array<double, 4> position{0.0, 10.0, 0.0, 1.0};  // x, y, z, w with w in {0, 1}

  [[nodiscard]] bool directional() const { return position[3] == 0.0; }

  // docs/definitions.md#inputs's form: finite l and w exactly 0 or 1.
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

// The precondition of every function that takes a light, in one wording: throws
// std::invalid_argument("<function>: the light needs finite coordinates and w = 0 or w = 1")
// or ("<function>: a directional light needs a nonzero direction"). Misuse, not bad input:
// scene and option readers report a bad light themselves, naming the file or the option.
inline void require_well_formed(const Light& light, std::string_view function) {
  if (!light.well_formed())
    throw std::invalid_argument(std::string(function) + ": the light needs finite coordinates and w = 0 or w = 1");
}
inline void require_defined(const Light& light, std::string_view function) {
  require_well_formed(light, function);
  if (!light.defined()) throw std::invalid_argument(std::string(function) + ": a directional light needs a nonzero direction");
}

}  // namespace shadowcert
