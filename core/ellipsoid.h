#pragma once
// An ellipsoid: the affine image of the unit ball, x = c + A u with |u| <= 1. A uv_sphere or an
// icosphere caster under any affine transform knows its own (scene/scene_file.h records it), and
// its shadow on a plane is known in closed form (reference/ellipsoid_shadow.h): the analytic
// truth the smooth-silhouette methods are measured against (docs/smooth-silhouettes.md).
#include <array>

#include "core/soup.h"

namespace shadowcert {

struct Ellipsoid {
  Vec3 centre{};
  std::array<Vec3, 3> axes{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};  // the columns of A; independent
};

}  // namespace shadowcert
