#include "pipeline/analytic_comparison.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/vector3.h"

namespace shadowcert {
namespace {

// The ellipsoid's outward normal direction at x: A^-T A^-1 (x - c), up to a positive factor:
// with M = adj(A) (rows r_i), sum_i (r_i . (x - c)) r_i.
Vec3 ellipsoid_normal(const Ellipsoid& e, const Vec3& x) {
  const Vec3 r0 = cross(e.axes[1], e.axes[2]), r1 = cross(e.axes[2], e.axes[0]), r2 = cross(e.axes[0], e.axes[1]);
  const Vec3 d = difference(x, e.centre);
  const double u0 = dot(r0, d), u1 = dot(r1, d), u2 = dot(r2, d);
  return {u0 * r0[0] + u1 * r1[0] + u2 * r2[0], u0 * r0[1] + u1 * r1[1] + u2 * r2[1], u0 * r0[2] + u1 * r1[2] + u2 * r2[2]};
}

}  // namespace

AnalyticCounts& AnalyticCounts::operator+=(const AnalyticCounts& o) {
  receiver_agree += o.receiver_agree;
  receiver_disagree += o.receiver_disagree;
  receiver_ambiguous += o.receiver_ambiguous;
  caster_agree += o.caster_agree;
  caster_disagree += o.caster_disagree;
  caster_band += o.caster_band;
  caster_ambiguous += o.caster_ambiguous;
  return *this;
}

bool has_analytic_caster(const Scene& scene) {
  return std::any_of(scene.meshes.begin(), scene.meshes.end(),
                     [](const SceneMesh& m) { return m.casts && m.ellipsoid.has_value(); });
}

AnalyticShadowImage analytic_reference(const Scene& scene, double crease_angle_degrees,
                                       const AnalyticImageOptions& options) {
  AnalyticImageOptions with_normals = options;
  with_normals.corner_normals.resize(scene.meshes.size());
  SmoothCasterOptions caster_options;
  caster_options.crease_angle_degrees = crease_angle_degrees;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const SceneMesh& mesh = scene.meshes[m];
    if (!mesh.casts || !mesh.ellipsoid || !with_normals.corner_normals[m].empty()) continue;
    SmoothCasterResult caster = smooth_caster(mesh.soup, caster_options);
    if (caster.caster) {
      with_normals.corner_normals[m] = std::move(caster.caster->normals);
    } else if (mesh.soup.normals.size() != mesh.soup.vertices.size() || mesh.soup.vertices.empty()) {
      std::vector<std::array<Vec3, 3>>& normals = with_normals.corner_normals[m];
      normals.resize(mesh.soup.triangles.size());
      for (std::size_t t = 0; t < normals.size(); ++t)
        for (std::size_t k = 0; k < 3; ++k)
          normals[t][k] = ellipsoid_normal(*mesh.ellipsoid, mesh.soup.vertices[mesh.soup.triangles[t][k]]);
    }  // else: analytic_shadow_image takes the soup's normals
  }
  return analytic_shadow_image(scene, with_normals);
}

AnalyticCounts compare_analytic(const AnalyticShadowImage& truth, std::size_t light, const gpu::StencilShadowFrame& frame) {
  if (light >= truth.lights.size()) throw std::invalid_argument("compare_analytic: light out of range");
  const std::size_t pixels = std::size_t{truth.width} * truth.height;
  if (frame.colour.width != truth.width || frame.colour.height != truth.height ||
      frame.first_lit_mask.pixels.size() != pixels || frame.colour.pixels.size() != 4 * pixels)
    throw std::invalid_argument("compare_analytic: the frame is " + std::to_string(frame.colour.width) + "x" +
                                std::to_string(frame.colour.height) + ", the truth " + std::to_string(truth.width) +
                                "x" + std::to_string(truth.height));
  AnalyticCounts c;
  const std::vector<AnalyticPixel>& t = truth.lights[light];
  for (std::size_t p = 0; p < pixels; ++p) {
    const bool covered = frame.colour.pixels[4 * p + 3] != 0;
    const bool lit = covered && frame.first_lit_mask.pixels[p] != 0;
    switch (t[p]) {
      case AnalyticPixel::none:
        break;
      case AnalyticPixel::lit:
      case AnalyticPixel::shadowed:
        ++(covered && lit == (t[p] == AnalyticPixel::lit) ? c.receiver_agree : c.receiver_disagree);
        break;
      case AnalyticPixel::ambiguous:
        ++c.receiver_ambiguous;
        break;
      case AnalyticPixel::caster_lit:
      case AnalyticPixel::caster_shadowed:
        ++(covered && lit == (t[p] == AnalyticPixel::caster_lit) ? c.caster_agree : c.caster_disagree);
        break;
      case AnalyticPixel::caster_band:
        ++c.caster_band;
        break;
      case AnalyticPixel::caster_ambiguous:
        ++c.caster_ambiguous;
        break;
    }
  }
  return c;
}

}  // namespace shadowcert
