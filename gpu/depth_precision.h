#pragma once
// How precisely the stencil pass orders a volume face against the visible surface
// (docs/definitions.md#pixel-protocol): the diff's model of GL's depth test, for reference/'s
// ExactImageOptions::depth_band.
//
// The depth buffer is 24-bit fixed point (gpu/offscreen_target.h, DEPTH24_STENCIL8) behind the
// infinite projection of gpu/camera_transform.h, whose window depth is 1 - near / D for view
// depth D: one step of 2^-24 in window depth is D^2 / near * 2^-24 in view depth. The float
// clip coordinates and the interpolation of depth over long volume triangles (reaching to
// infinity) add errors of the same order. Within kDepthBandFactor such steps of the visible
// point, a volume face may pass the depth test or not whatever the exact order is.
#include "gpu/camera_transform.h"

namespace shadowcert::gpu {

// Window-depth resolution of a 24-bit depth buffer.
inline constexpr double kDepthQuantum = 1.0 / 16777216.0;  // 2^-24
// How many depth steps the band spans. Measured: on data/scenes/default.json at 640x480 the
// exact chain itself (render --method cpu) miscounted pixels whose count changes 5e-4 to 1e-3
// along the view ray at depth 12, i.e. 0.6 to 1.2 steps; 16 leaves a wide margin for the
// interpolation over long, thin volume triangles.
inline constexpr double kDepthBandFactor = 16.0;

// The half-width, in view depth, of the band around a visible point at view depth
// `view_depth` (> 0), for the projection's near plane `z_near` (Camera::near_plane).
[[nodiscard]] constexpr double depth_band(double view_depth, double z_near) {
  return kDepthBandFactor * view_depth * view_depth / z_near * kDepthQuantum;
}

}  // namespace shadowcert::gpu
