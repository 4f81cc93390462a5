#pragma once
// The size of one light's volume (volume/volume_workspace.h), in the units of the caller's two
// output buffers: `vertices` homogeneous vertices, i.e. 4 * vertices floats (x, y, z, w), and
// `triangles` triangles, i.e. 3 * triangles uint32 indices.
#include <cstddef>

namespace shadowcert {

struct VolumeSizes {
  std::size_t vertices = 0;
  std::size_t triangles = 0;

  // The spans' lengths VolumeWorkspace::write needs at least.
  [[nodiscard]] std::size_t position_floats() const { return 4 * vertices; }
  [[nodiscard]] std::size_t index_count() const { return 3 * triangles; }

  friend bool operator==(const VolumeSizes&, const VolumeSizes&) = default;
};

}  // namespace shadowcert
