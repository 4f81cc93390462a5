#include "pipeline/scene_smoothies.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/float_rounding.h"
#include "core/sign.h"
#include "exact/edge_multiplicity.h"

namespace shadowcert {
namespace {

// Whether triangle t runs the edge from u to v (u's successor in its order is v).
bool runs_forward(const Triangle& t, std::uint32_t u, std::uint32_t v) {
  for (int k = 0; k < 3; ++k)
    if (t[k] == u) return t[(k + 1) % 3] == v;
  return false;
}

int sign_value(Sign s) { return to_int(s); }

}  // namespace

SmoothieEdges smoothie_edges(const Soup& soup, const EdgeTable& table, const Light& light) {
  const std::vector<Sign> signs =
      edge_entry_signs(MultiplicityMethod::exact, soup, table, light, Precision::float64);
  SmoothieEdges out;
  out.first_face.push_back(0);
  for (std::size_t e = 0; e < table.size(); ++e) {
    const std::uint32_t first = table.first_opposite[e], last = table.first_opposite[e + 1];
    int sum = 0;  // -m
    for (std::uint32_t k = first; k < last; ++k) sum += sign_value(signs[k]);
    if (sum == 0) continue;
    const int side = sum > 0 ? 1 : -1;
    const auto [u, v] = table.edges[e];
    const bool manifold = last - first == 2 &&
                          runs_forward(soup.triangles[table.opposite_triangle[first]], u, v) !=
                              runs_forward(soup.triangles[table.opposite_triangle[first + 1]], u, v);
    out.edges.push_back({u, v});
    out.occluder_side.push_back(static_cast<std::int8_t>(side));
    for (std::uint32_t k = first; k < last; ++k) {
      const int s = sign_value(signs[k]);
      if (s == side || (manifold && s == 0)) out.face_opposite.push_back(table.opposite_vertex[k]);
    }
    out.first_face.push_back(static_cast<std::uint32_t>(out.face_opposite.size()));
  }
  return out;
}

SceneSmoothies scene_smoothies(const Soup& canonical, const EdgeTable& table, std::span<const Light> lights,
                               const gpu::SceneBounds& bounds, const SceneSmoothieOptions& options) {
  if (!std::isfinite(options.width) || options.width < 0.0)
    throw std::invalid_argument("scene_smoothies: the width must be finite and >= 0 (0: the default), got " +
                                std::to_string(options.width));
  const Vec3 diagonal{bounds.hi[0] - bounds.lo[0], bounds.hi[1] - bounds.lo[1], bounds.hi[2] - bounds.lo[2]};
  const double diagonal_length =
      std::sqrt(diagonal[0] * diagonal[0] + diagonal[1] * diagonal[1] + diagonal[2] * diagonal[2]);
  const Vec3 centre{0.5 * (bounds.lo[0] + bounds.hi[0]), 0.5 * (bounds.lo[1] + bounds.hi[1]),
                    0.5 * (bounds.lo[2] + bounds.hi[2])};

  SceneSmoothies out;
  out.space = options.space;
  out.width = options.width > 0.0 ? options.width : kDefaultSmoothieWidthFraction * diagonal_length;
  if (!(out.width > 0.0))
    throw std::invalid_argument("scene_smoothies: the scene's bounds are a point, so there is no default width");
  // As GL receives the casters (and as cpu's chain is taken): every coordinate rounded to float.
  const Soup rounded = float_rounded(canonical);
  for (const Light& light : lights) {
    const Light l = float_rounded(light);
    SmoothieOptions smoothie;
    smoothie.width = out.width;
    smoothie.space = options.space;
    smoothie.link_corners = options.link_corners;
    smoothie.shrink_concave_corners = options.shrink_concave_corners;
    if (options.space == SmoothieSpace::light && !l.directional()) {
      const Vec3 to_centre{centre[0] - l.position[0], centre[1] - l.position[1], centre[2] - l.position[2]};
      smoothie.reference_distance =
          std::sqrt(to_centre[0] * to_centre[0] + to_centre[1] * to_centre[1] + to_centre[2] * to_centre[2]);
      // A light at the centre (a lamp in a room, drawn with a cube map) aims at no point: the
      // width is D at half the diagonal, the distance to the bounds' corners.
      if (!(smoothie.reference_distance > 0.0)) smoothie.reference_distance = 0.5 * diagonal_length;
    }
    Smoothies s = build_smoothies(rounded.vertices, smoothie_edges(rounded, table, l), l, smoothie);
    out.per_light.push_back(std::move(s.mesh));
    out.stats.push_back(s.stats);
  }
  return out;
}

}  // namespace shadowcert
