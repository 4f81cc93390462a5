#include "pipeline/smooth_caster_arrays.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "contour/smooth_contour.h"

namespace shadowcert {

// The shader's subdivision stack is sized for contour/'s depth bound: both builds stop at the
// same depth.
static_assert(gpu::kSmoothGpuMaxSubdivisionDepth == kMaxSubdivisionDepth);
static_assert(gpu::kNoTriangleAcross == kBorder);

void append_smooth_caster(gpu::SmoothCasterArrays& arrays, const SmoothCaster& caster, double epsilon,
                          double cap_offset) {
  if (!(std::isfinite(epsilon) && epsilon > 0.0))
    throw std::invalid_argument("append_smooth_caster: epsilon must be finite and > 0");
  if (!(std::isfinite(cap_offset) && cap_offset >= 0.0))
    throw std::invalid_argument("append_smooth_caster: the cap offset must be finite and >= 0");
  constexpr std::size_t kMax = std::numeric_limits<std::uint32_t>::max() - 1;
  if (arrays.vertices.size() + caster.vertices.size() > kMax ||
      arrays.triangles.size() + caster.triangles.size() > kMax ||
      arrays.wedge_normals.size() + caster.wedge_normal.size() > kMax)
    throw std::invalid_argument("append_smooth_caster: more than 32-bit indices");
  const auto vertex_offset = static_cast<std::uint32_t>(arrays.vertices.size());
  const auto triangle_offset = static_cast<std::uint32_t>(arrays.triangles.size());
  const auto wedge_offset = static_cast<std::uint32_t>(arrays.wedge_normals.size());
  arrays.vertices.insert(arrays.vertices.end(), caster.vertices.begin(), caster.vertices.end());
  arrays.wedge_normals.insert(arrays.wedge_normals.end(), caster.wedge_normal.begin(), caster.wedge_normal.end());
  for (std::size_t t = 0; t < caster.triangles.size(); ++t) {
    std::array<std::uint32_t, 3> v{}, w{}, across{};
    std::uint8_t crease = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      v[k] = caster.triangles[t][k] + vertex_offset;
      w[k] = caster.wedge[t][k] + wedge_offset;
      across[k] = caster.across[t][k] == kBorder ? gpu::kNoTriangleAcross : caster.across[t][k] + triangle_offset;
      if (caster.crease[t][k]) crease = static_cast<std::uint8_t>(crease | (1u << k));
    }
    arrays.triangles.push_back(v);
    arrays.wedges.push_back(w);
    arrays.across.push_back(across);
    arrays.crease_bits.push_back(crease);
    arrays.epsilon.push_back(static_cast<float>(epsilon));
    arrays.cap_offset.push_back(static_cast<float>(cap_offset));
  }
}

}  // namespace shadowcert
