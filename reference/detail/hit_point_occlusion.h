#pragma once
// Internal to reference/: reference/ellipsoid_occlusion.h's sign at a ray's hit point P, which
// is never rounded: the interval filter runs on P's enclosure (detail::HitPoint's box), the
// exact stage on P's homogeneous coordinates X / W (reference/detail/hit_point_coordinates.h;
// W > 0, so q's signs are those of W^2 q with M (X - W c) and M (W L - X) in place of
// M (P - c) and M (L - P)).
#include "core/ellipsoid.h"
#include "core/sign.h"
#include "exact/light_orientation.h"
#include "reference/detail/ray_hit.h"

namespace shadowcert::detail {

// `hit`: the hit's parameter; `point`: the HitPoint built from it. Preconditions (unchecked):
// the ellipsoid passes require_proper, the light is defined (w in {0, 1}, a directional one
// nonzero).
[[nodiscard]] Sign hit_point_occlusion(const Ellipsoid& ellipsoid, const RayParameter& hit, const HitPoint& point,
                                       const HomogeneousPoint& light);

}  // namespace shadowcert::detail
