#pragma once
// The shadow volume of a smooth caster (Mattausch et al. 2012 §4; docs/smooth-silhouettes.md),
// closed by construction, as the homogeneous triangles every GL method draws and exact/
// certifies (core/homogeneous_mesh.h):
//   X = the caps: each triangle's lit part as it is, and its unlit part reversed (both then face
//       the light), the whole triangle for `discrete`, cut along the accurate segment otherwise,
//       with every partner point of the smooth contour on the cut as a vertex, so that no
//       T-junction opens it; plus for `smooth` the gap strip of quads (p'_k+1, p'_k, p_k, p_k+1)
//       between the accurate silhouette p' and the smooth contour p, once for each part. The
//       unlit part casts too because an open caster's unlit side can face the light through its
//       borders, and a light inside a closed caster sees only unlit faces; on a closed caster
//       lit from outside both parts cast the same shadow, so every shadowed point counts 2, as
//       the exact chain counts a ray that crosses two triangles (docs/definitions.md#counts);
//   every edge of X's boundary (the smooth contour, the lit part's border edges, the strip's
//       ends on a border) extruded to infinity: the edge a -> b gives (b, a, a_inf, b_inf), a
//       triangle (b, a, inf) for a directional light;
//   X at infinity, reversed (the back cap; none for a directional light, whose far points are
//       one point).
// The boundary of the extrusion cancels X's and the back cap's, so the volume is closed for any
// X: the certificate (exact/volume_closure.h) holds whatever the loops look like. X's
// triangles face the light: the caster's triangles are taken to be oriented like its corner
// normals (outwards).
#include <cstdint>
#include <span>
#include <vector>

#include "contour/silhouette_loop.h"
#include "contour/smooth_caster.h"
#include "contour/smooth_contour.h"
#include "core/homogeneous_mesh.h"
#include "core/light.h"
#include "core/sign.h"

namespace shadowcert {

enum class SilhouetteMethod { discrete, accurate, smooth };

// The default approximation error of the smooth contour, in world units (the paper's 0.01 for
// casters of unit size).
inline constexpr double kDefaultContourEpsilon = 0.01;

struct SmoothVolumeOptions {
  SilhouetteMethod method = SilhouetteMethod::smooth;
  double epsilon = kDefaultContourEpsilon;  // smooth only: > 0
  // accurate, smooth: how far behind the surface (along -n) the cut points of the caps lie, in
  // world units, >= 0. A cap piece cut from a triangle lies in its plane but is fanned from
  // other vertices than the triangle the depth pass drew, so their depths round apart and the
  // caster's own shadow stripes near the terminator; set behind by the depth buffer's band
  // (gpu/depth_precision.h), every cap is behind or at the surface, as whole triangles are. The
  // paper offsets by 0.15 along -n for the same kind of leak; 0 leaves the caps on the surface.
  // Only the caps move: the sides are extruded from the contour (accurate's: its loops) on the
  // surface, a strip joining the two, so the shadow's boundary does not move.
  double cap_offset = 0.0;
};

struct SmoothVolume {
  HomogeneousMesh mesh;
  std::vector<SilhouetteLoop> loops;     // discrete or accurate loops the volume was built on
  // smooth: the smooth contours; accurate with a cap offset: the loops themselves (on the surface,
  // joined by a strip to the caps set behind it); else empty.
  std::vector<SmoothContour> contours;
  std::size_t cap_triangles = 0;         // X's triangles (front cap and gap strip)
  std::size_t side_triangles = 0;
};

// `sides`: discrete only, one light side per caster triangle (positive: it faces the light;
// zero: the light is in its plane and it casts nothing), decided by the caller, e.g. exactly
// with exact/light_orientation.h. Throws std::invalid_argument("smooth_shadow_volume: ...") on
// an undefined light, a bad epsilon or, for discrete, sides of the wrong size.
[[nodiscard]] SmoothVolume smooth_shadow_volume(const SmoothCaster& caster, const Light& light,
                                                const SmoothVolumeOptions& options = {},
                                                std::span<const Sign> sides = {});

}  // namespace shadowcert
