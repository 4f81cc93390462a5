#pragma once
// A point light circling a scene (`shadowcert track`'s default light path; docs/smoothies.md,
// "Silhouette tracking"): around the vertical axis (y) through `center`, at `height` above it
// and `radius` from the axis. Frame i of n is at angle a = 2 pi turns i / n from +x towards +z:
// center + (radius cos a, height, radius sin a).
#include <cstddef>
#include <vector>

#include "core/box.h"
#include "core/light.h"

namespace shadowcert {

// The default orbit's size relative to the bounds' half diagonal r: radius 2 r, height r / 2.
inline constexpr double kOrbitRadiusScale = 2.0;
inline constexpr double kOrbitHeightScale = 0.5;

struct LightOrbit {
  Vec3 center{0.0, 0.0, 0.0};
  double radius = 1.0;  // > 0
  double height = 0.0;  // above the centre (negative: below)
  double turns = 1.0;   // any finite number; negative turns run the other way
};

// Centred on the box, with the sizes above (a point box gets radius 1).
[[nodiscard]] LightOrbit default_light_orbit(const Box& bounds);

// `frames` point lights along the orbit. Throws std::invalid_argument("orbit_lights: ...") when
// frames is 0, the radius is not positive and finite, or another value is not finite.
[[nodiscard]] std::vector<Light> orbit_lights(const LightOrbit& orbit, std::size_t frames);

}  // namespace shadowcert
