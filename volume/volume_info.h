#pragma once
// Per-volume flags VolumeWorkspace::write returns with the volume (volume/volume_workspace.h):
// how many vertices and triangles it wrote, whether z-pass is proven, the view-independent box
// and, for a view, the depth bounds.
#include <array>
#include <cstdint>

#include "volume/volume_sizes.h"

namespace shadowcert {

// Which stencil count the host may use for this volume.
enum class VolumeStencil : std::uint8_t {
  zfail_needed,  // z-pass is not proven (or was not asked: no VolumeView::tip): count z-fail
  zpass_proven,  // exact/zpass_proof.h proved z-pass counts what z-fail counts at this tip
};

// Why, mirroring exact/zpass_proof.h's verdicts (docs/gpu.md#proven-z-pass).
enum class ZPassReason : std::uint8_t {
  not_asked,         // no VolumeView or no tip
  proven,            // no face of the exact chain meets the tip, and n = 0 there
  camera_in_volume,  // the eye is inside a volume (n > 0 in the tip)
  face_meets_tip,    // a face of the chain meets the tip
  count_undefined,   // the eye is on a volume boundary: n undefined at every probe
};

struct VolumeInfo {
  VolumeSizes written;  // what write() wrote: the first 4 * vertices floats, 3 * triangles indices
  VolumeStencil stencil = VolumeStencil::zfail_needed;
  ZPassReason zpass = ZPassReason::not_asked;

  // View-independent bounds: the box of the finite vertices (w = 1) that a triangle uses, and
  // whether a triangle uses a vertex at infinity (w = 0: the volume is unbounded in the
  // directions away from the light). No triangle (nothing casts): empty, box all zero.
  bool empty = true;
  std::array<float, 3> finite_min{};
  std::array<float, 3> finite_max{};
  bool reaches_infinity = false;

  // With a VolumeView: every point of the volume (its points at infinity included) has NDC
  // depth z / w in [depth_min, depth_max] when depth_bounded, i.e. when every vertex a triangle
  // uses has clip w > 0 (each point is then a positive combination of its triangle's vertices,
  // and z / w a weighted mean of theirs). Otherwise (the volume reaches the eye plane or behind
  // it, or no view) depth_bounded is false and a host must take the whole depth range. Computed
  // in double from the float vertices and the given matrix: GL's float transform may differ in
  // the last bits, so a host using them with glDepthBoundsEXT widens them by its depth
  // buffer's precision.
  bool depth_bounded = false;
  double depth_min = 0.0;
  double depth_max = 0.0;
};

}  // namespace shadowcert
