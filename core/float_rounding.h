#pragma once
// A scene as a GL renderer receives it: every coordinate rounded once to the nearest float
// (and back to double, exactly, so the exact predicates can take it). The one definition of
// that rounding, shared by exact/cpu_volume (the chain the GPU draws) and reference/ (the exact
// image of the float input, docs/diff.md).
#include <cstddef>

#include "core/light.h"
#include "core/soup.h"

namespace shadowcert {

// The nearest float (ties to even, the default rounding mode). Through a volatile float: GCC 12
// at -O3 has been seen to fold the double -> float -> double round trip of a vectorised loop away.
[[nodiscard]] inline double float_rounded(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}

// Every vertex coordinate rounded to the nearest float.
[[nodiscard]] inline Soup float_rounded(const Soup& soup) {
  Soup out = soup;
  for (Vec3& v : out.vertices)
    for (double& x : v) x = float_rounded(x);
  return out;
}

// The light's coordinates rounded to the nearest float; w (0 or 1) is exact in float.
[[nodiscard]] inline Light float_rounded(const Light& light) {
  Light out = light;
  for (std::size_t k = 0; k < 3; ++k) out.position[k] = float_rounded(light.position[k]);
  return out;
}

}  // namespace shadowcert
