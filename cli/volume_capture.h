#pragma once
// `render --capture`: a light's volume as drawn, converted from gpu/'s forms to exact/'s
// CapturedVolume (gpu/ does not include exact/, so cli/ converts) and written as .vol.
#include <string>
#include <vector>

#include "exact/captured_volume.h"
#include "gpu/compute_volume.h"
#include "gpu/shadow_volume_geometry.h"

namespace shadowcert::cli {

[[nodiscard]] CapturedVolume captured_volume(const gpu::ShadowVolumeGeometry& geometry);
// Triangle soup as read back from the GPU: three vertices per triangle, welded on writing.
[[nodiscard]] CapturedVolume captured_volume(const std::vector<gpu::VolumeTriangle>& triangles);

// Creates parent folders and writes `volume` (welded) to `file` with `comment` on top.
void write_capture(const std::string& file, const CapturedVolume& volume, const std::string& comment);

}  // namespace shadowcert::cli
