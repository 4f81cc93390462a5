#include "cli/volume_capture.h"

#include "cli/output_file.h"

namespace shadowcert::cli {

CapturedVolume captured_volume(const gpu::ShadowVolumeGeometry& geometry) {
  return {geometry.vertices, geometry.triangles};
}

CapturedVolume captured_volume(const std::vector<gpu::VolumeTriangle>& triangles) {
  CapturedVolume volume;
  volume.vertices.reserve(3 * triangles.size());
  volume.triangles.reserve(triangles.size());
  for (const gpu::VolumeTriangle& t : triangles) {
    const auto first = static_cast<std::uint32_t>(volume.vertices.size());
    volume.vertices.insert(volume.vertices.end(), t.begin(), t.end());
    volume.triangles.push_back({first, first + 1, first + 2});
  }
  return volume;
}

void write_capture(const std::string& file, const CapturedVolume& volume, const std::string& comment) {
  create_parent_directories(file);
  write_captured_volume(file, volume, comment);
}

}  // namespace shadowcert::cli
