#include "scene/light_orbit.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/portable_math.h"

namespace shadowcert {

LightOrbit default_light_orbit(const Box& bounds) {
  LightOrbit orbit;
  double half_diagonal2 = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    orbit.center[i] = 0.5 * (bounds.lo[i] + bounds.hi[i]);
    const double half = 0.5 * (bounds.hi[i] - bounds.lo[i]);
    half_diagonal2 += half * half;
  }
  const double r = half_diagonal2 > 0.0 ? std::sqrt(half_diagonal2) : 1.0;
  orbit.radius = kOrbitRadiusScale * r;
  orbit.height = kOrbitHeightScale * r;
  return orbit;
}

std::vector<Light> orbit_lights(const LightOrbit& orbit, std::size_t frames) {
  if (frames == 0) throw std::invalid_argument("orbit_lights: needs at least one frame");
  if (!(std::isfinite(orbit.radius) && orbit.radius > 0.0))
    throw std::invalid_argument("orbit_lights: the radius must be positive and finite");
  if (!std::isfinite(orbit.height) || !std::isfinite(orbit.turns) || !std::isfinite(orbit.center[0]) ||
      !std::isfinite(orbit.center[1]) || !std::isfinite(orbit.center[2]))
    throw std::invalid_argument("orbit_lights: the centre, height and turns must be finite");
  std::vector<Light> lights;
  lights.reserve(frames);
  for (std::size_t i = 0; i < frames; ++i) {
    const double a = 2.0 * std::numbers::pi * orbit.turns * static_cast<double>(i) / static_cast<double>(frames);
    lights.push_back(Light{{orbit.center[0] + orbit.radius * portable::cos(a), orbit.center[1] + orbit.height,
                            orbit.center[2] + orbit.radius * portable::sin(a), 1.0}});
  }
  return lights;
}

}  // namespace shadowcert
