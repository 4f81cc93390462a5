#pragma once
// What VolumeWorkspace (volume/volume_workspace.h) may be told of the camera, to add the flags
// that depend on it: the depth bounds of the volume under a view-projection matrix, and the
// exact proof that z-pass counts right (exact/zpass_proof.h).
#include <array>
#include <optional>

#include "core/soup.h"

namespace shadowcert {

// The region z-pass counts from, world space, as exact/zpass_proof.h takes it: the eye (apex)
// and the four corners of the near rectangle in cyclic order, spanning two proper tetrahedra
// (apex, c0, c1, c2) and (apex, c0, c2, c3) of one orientation. The proof is exact on these
// doubles: a host whose GL transforms in float must pass a tip grown by that rounding, as
// pipeline/stencil_choice.h's gl_near_tip grows shadowcert's own (relative 2^-8 and 2^-14 of
// the scene's largest coordinate, behind the eye too).
struct ZPassTip {
  Vec3 apex{};
  std::array<Vec3, 4> corners{};
};

struct VolumeView {
  // clip = M (x, y, z, w), column-major as GL and GLM store it: entry (row r, column c) is
  // view_projection[4 * c + r]. Used for the depth bounds (VolumeInfo::depth_*).
  std::array<double, 16> view_projection{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  // When given, z-pass is proven or refuted exactly (VolumeInfo::stencil). The proof builds an
  // occluder-count tree of the soup: it allocates, and costs about as much as the volume.
  std::optional<ZPassTip> tip;
};

}  // namespace shadowcert
