#pragma once
// The analytic shadow image: what a smooth-silhouette method (docs/smooth-silhouettes.md)
// should show at every pixel when each smooth caster is the ellipsoid its mesh approximates
// (SceneMesh::ellipsoid, a uv_sphere or icosphere under an affine transform), the per-pixel
// truth of "Per-pixel error against the analytic shadow" there.
//
// Per pixel, its centre ray and its four corner rays (core/pixel_ray.h, the GL path's own
// rays; corners shared between pixels) are followed to their first hit on the scene's
// triangles, exactly as reference/exact_image.h does (orientation signs and exact parameter
// comparisons; a touch, a tie or an in-plane contact is a degenerate hit). The visible surface
// is the meshes as drawn; what casts differs:
//   - a mesh whose `ellipsoid` is set and that casts (its *analytic caster*) casts as that
//     ellipsoid: a hit point P on another mesh is shadowed by it iff the open segment
//     P -> light meets the ellipsoid's interior (reference/ellipsoid_occlusion.h, exact; a
//     tangent segment is a zero sign);
//   - every other casting mesh casts as its triangles, as in the exact image: a casting
//     triangle (s != 0) other than the hit one that the open segment crosses shadows P, one it
//     touches is a zero sign;
//   - a mesh that does not cast (SceneMesh::casts) shadows nothing.
// A hit on an analytic caster's own mesh is decided by the interpolated-normal terminator
// (the paper's smooth surface shadowing itself, its Figure 8): n(P) = the barycentric blend of
// the hit triangle's corner normals, lit iff n . (l - w P) > 0 (and no other caster shadows P).
// That test runs in double on a double approximation of P (the only one not exact): its
// pixels within `terminator_band` of the terminator, where rounding or the methods' modelling
// could decide either way, are set apart as caster_band.
//
// A pixel is ambiguous where its footprint straddles a boundary: a footprint ray hits nothing
// or another mesh than the centre's, a hit is degenerate, a zero sign arose (a segment tangent
// to an ellipsoid, touching a triangle), the five rays' verdicts differ, or (on a receiver) the
// light is not strictly on the eye's side of the hit triangle's plane (its self-shadow
// terminator, as in the exact image). On an analytic caster, verdicts that differ only by the
// terminator make the pixel caster_band. Every decision but the terminator's is an exact sign,
// so the receiver pixels do not change under an exact translation of scene and camera.
#include <array>
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "core/soup.h"

namespace shadowcert {

// The truth at one pixel for one light.
enum class AnalyticPixel : std::uint8_t {
  none,              // the centre ray meets nothing
  lit,               // a receiver (not an analytic caster's mesh): no caster shadows the footprint
  shadowed,          // a receiver: a caster shadows the whole footprint
  ambiguous,         // a receiver: the footprint straddles a boundary (above)
  caster_lit,        // an analytic caster's mesh: lit by its terminator, no other caster shadows
  caster_shadowed,   // an analytic caster's mesh: past its terminator, or shadowed by another caster
  caster_band,       // an analytic caster's mesh: its terminator within the band or across the footprint
  caster_ambiguous,  // an analytic caster's mesh: any other ambiguity (footprint on several
                     // surfaces, a degenerate hit, another caster's boundary)
};

// The default half-width of the terminator band, as |n . (l - w P)| / (|n| |l - w P|), the
// cosine between the interpolated normal and the light direction (0.02: about 1.1 degrees).
// It absorbs what the truth leaves to modelling, not rounding (P's double approximation is off
// by far less): a method's caps follow the linear interpolation of the corner values f, not
// n(P) . (l - w P), and are set behind the surface by the depth band
// (SmoothVolumeOptions::cap_offset).
inline constexpr double kDefaultTerminatorBand = 0.02;

struct AnalyticImageOptions {
  // Per mesh of the scene (index), the corner normals that define an analytic caster's
  // terminator: [triangle][corner], in its soup's triangle order (contour/smooth_caster.h's
  // SmoothCaster::normals). Missing or empty for a mesh: the soup's per-vertex normals, which it
  // must then have. Unread for the other meshes.
  std::vector<std::vector<std::array<Vec3, 3>>> corner_normals;
  double terminator_band = kDefaultTerminatorBand;  // in [0, 1)
};

struct AnalyticShadowImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  // The centre ray's mesh (an index into Scene::meshes), or 0xFFFFFFFF where it meets nothing.
  std::vector<std::uint32_t> meshes;
  std::vector<std::vector<AnalyticPixel>> lights;  // per light; pixels row-major, row 0 at the TOP
  std::vector<std::uint32_t> analytic_casters;     // the meshes cast as ellipsoids
  double seconds = 0.0;
};

inline constexpr std::uint32_t kNoMesh = 0xFFFFFFFFu;

// The analytic image of `scene` at its camera, for each of its lights. Parallel over rows
// (TBB). Throws std::invalid_argument("analytic_shadow_image: ...") for a vertex index out of
// range, a non-finite coordinate, an improper ellipsoid (reference/ellipsoid_occlusion.h), a
// light that is not defined, a degenerate camera, an analytic caster without corner normals (or
// with a count that is not one per triangle), or a band outside [0, 1).
[[nodiscard]] AnalyticShadowImage analytic_shadow_image(const Scene& scene, const AnalyticImageOptions& options = {});

}  // namespace shadowcert
