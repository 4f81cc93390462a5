#pragma once
// Shared by the tests of contour/ (tests/contour/): a soup's smooth caster, and each caster
// triangle's light side in double (the tests' lights stay far from every plane, so double
// decides them as exact/light_orientation.h would).
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "contour/smooth_caster.h"
#include "core/light.h"
#include "core/sign.h"
#include "core/vector3.h"

namespace shadowcert::test_support {

// The caster of `soup`; throws std::runtime_error with the qualification when it does not qualify.
inline SmoothCaster caster_of(const Soup& soup, const SmoothCasterOptions& options = {}) {
  SmoothCasterResult r = smooth_caster(soup, options);
  if (!r.caster) throw std::runtime_error(r.qualification.summary());
  return *r.caster;
}

// sign ((b - a) x (c - a)) . (l - w a) per triangle.
inline std::vector<Sign> face_sides(const SmoothCaster& c, const Light& light) {
  std::vector<Sign> sides(c.triangles.size());
  const auto& l = light.position;
  for (std::size_t t = 0; t < sides.size(); ++t) {
    const Vec3& a = c.vertices[c.triangles[t][0]];
    const Vec3 n = cross(difference(c.vertices[c.triangles[t][1]], a), difference(c.vertices[c.triangles[t][2]], a));
    sides[t] = sign_of(dot(n, Vec3{l[0] - l[3] * a[0], l[1] - l[3] * a[1], l[2] - l[3] * a[2]}));
  }
  return sides;
}

// 1 where face_sides is positive (discrete_silhouette's flags).
inline std::vector<std::uint8_t> lit_faces(const SmoothCaster& c, const Light& light) {
  std::vector<std::uint8_t> lit;
  for (Sign s : face_sides(c, light)) lit.push_back(s == Sign::positive);
  return lit;
}

}  // namespace shadowcert::test_support
