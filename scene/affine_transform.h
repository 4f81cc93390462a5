#pragma once
// Affine placement of a soup in world space, in double: p' = A p + t. The scene format builds
// one from a row-major matrix or from translate / scale / rotate_deg (docs/scene-format.md).
#include <array>

#include "core/ellipsoid.h"
#include "core/soup.h"

namespace shadowcert {

struct AffineTransform {
  std::array<std::array<double, 3>, 3> linear{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};  // A, row-major
  Vec3 translation{0, 0, 0};                                                        // t
};

// p' = T * Rz * Ry * Rx * S * p: scale first, then rotate about X, then Y, then Z (degrees,
// right-handed, counter-clockwise looking down the axis towards the origin), then translate.
// Multiples of 90 degrees use exact sines and cosines, so axis-aligned rotations stay exact.
[[nodiscard]] AffineTransform compose_trs(const Vec3& translate, const Vec3& scale, const Vec3& rotate_degrees);

[[nodiscard]] bool is_identity(const AffineTransform& transform);

// Positions by A p + t; normals by the inverse transpose of A, renormalised; when det A < 0 the
// triangles are reversed so that outward-oriented meshes stay outward after a mirror.
// Throws std::invalid_argument("transformed: ...") when det A == 0.
[[nodiscard]] Soup transformed(const Soup& soup, const AffineTransform& transform);

// The image of an ellipsoid x = c + B u (|u| <= 1): centre A c + t, axes the columns of A B.
// Throws std::invalid_argument("transformed: ...") when det A == 0.
[[nodiscard]] Ellipsoid transformed(const Ellipsoid& ellipsoid, const AffineTransform& transform);

}  // namespace shadowcert
