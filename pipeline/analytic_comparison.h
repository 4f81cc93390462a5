#pragma once
// A GL frame against the analytic shadow (reference/analytic_shadow_image.h): how far a
// smooth-silhouette method's shadow is from the shadow of the ellipsoids its casters
// approximate, pixel by pixel (docs/smooth-silhouettes.md, "Per-pixel error"). `diff` reports
// it next to each silhouette method's exact-image figures, never as a failure; the analytic
// shadow bench (bench/analytic_shadow_bench.cpp) tabulates it.
//
//   if (has_analytic_caster(scene)) {
//     const AnalyticShadowImage truth = analytic_reference(scene, crease_angle);
//     const AnalyticCounts c = compare_analytic(truth, light, frame);  // frame of light `light` alone
//   }
#include <cstddef>
#include <cstdint>

#include "contour/smooth_caster.h"
#include "core/scene.h"
#include "gpu/stencil_shadow_renderer.h"
#include "reference/analytic_shadow_image.h"

namespace shadowcert {

// Pixels of one frame (or a sum of frames) by the analytic truth and the frame's first-light
// lit mask (gpu::StencilShadowFrame::first_lit_mask, where the frame covers the pixel). A pixel
// the truth decides but the frame leaves uncovered is a disagreement; pixels the centre ray
// sees nothing at are not counted.
struct AnalyticCounts {
  // Receivers (meshes that are not analytic casters): the shadow the ellipsoids cast.
  std::uint64_t receiver_agree = 0;
  std::uint64_t receiver_disagree = 0;
  std::uint64_t receiver_ambiguous = 0;  // the footprint straddles a boundary: not compared
  // The analytic casters' own pixels: self-shadowing against the interpolated-normal
  // terminator (the paper's Figure 8).
  std::uint64_t caster_agree = 0;
  std::uint64_t caster_disagree = 0;
  std::uint64_t caster_band = 0;       // within the terminator band: not compared
  std::uint64_t caster_ambiguous = 0;  // another ambiguity: not compared

  AnalyticCounts& operator+=(const AnalyticCounts& other);
};

// Whether some mesh of `scene` casts and knows its ellipsoid (SceneMesh::ellipsoid).
[[nodiscard]] bool has_analytic_caster(const Scene& scene);

// The analytic image of `scene` at its camera (world space, as given), each analytic caster's
// terminator defined by the corner normals the silhouette methods compute for it
// (contour/smooth_caster.h with `crease_angle_degrees`; its file normals when it has them).
// A caster that does not qualify as a smooth caster (the methods then draw its robust chain)
// keeps its soup's normals, or, without any, the ellipsoid's own normals at its vertices.
// Throws what analytic_shadow_image throws.
[[nodiscard]] AnalyticShadowImage analytic_reference(const Scene& scene,
                                                     double crease_angle_degrees = kDefaultCreaseAngleDegrees,
                                                     const AnalyticImageOptions& options = {});

// `frame`, rendered for light `light` alone (its first light), against that light's truth.
// Throws std::invalid_argument("compare_analytic: ...") for a light out of range or a frame
// of another size.
[[nodiscard]] AnalyticCounts compare_analytic(const AnalyticShadowImage& truth, std::size_t light,
                                              const gpu::StencilShadowFrame& frame);

}  // namespace shadowcert
