#include "contour/silhouette_loop.h"

#include <stdexcept>

#include "contour/detail/lit_boundary.h"
#include "core/vector3.h"

namespace shadowcert {

std::vector<std::array<double, 3>> corner_light_values(const SmoothCaster& caster, const Light& light) {
  require_defined(light, "corner_light_values");
  const auto& l = light.position;
  std::vector<std::array<double, 3>> f(caster.triangles.size());
  for (std::size_t t = 0; t < f.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& v = caster.vertices[caster.triangles[t][k]];
      const Vec3 towards{l[0] - l[3] * v[0], l[1] - l[3] * v[1], l[2] - l[3] * v[2]};
      f[t][k] = dot(caster.normals[t][k], towards);
    }
  return f;
}

std::vector<SilhouetteLoop> discrete_silhouette(const SmoothCaster& caster, std::span<const std::uint8_t> lit_triangles) {
  if (lit_triangles.size() != caster.triangles.size())
    throw std::invalid_argument("discrete_silhouette: one lit flag per triangle is needed");
  const detail::LitBoundary boundary = detail::discrete_boundary(caster, lit_triangles);
  return detail::loops_of(boundary, detail::chain(boundary));
}

std::vector<SilhouetteLoop> accurate_silhouette(const SmoothCaster& caster, const Light& light) {
  require_defined(light, "accurate_silhouette");
  const detail::LitBoundary boundary = detail::accurate_boundary(caster, detail::CornerValues(caster, light));
  return detail::loops_of(boundary, detail::chain(boundary));
}

}  // namespace shadowcert
