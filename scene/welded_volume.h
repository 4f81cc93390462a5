#pragma once
// Exact welding of a homogeneous float mesh (core/homogeneous_mesh.h), the volume-file twin
// of scene/welded_soup.h: the GPU may emit one point several times, with -0 or +0.
#include "core/homogeneous_mesh.h"

namespace shadowcert {

// Merges vertices whose four floats are bitwise equal after mapping -0 to +0, keeping
// first-seen order and bits, and renumbers the triangles (none is dropped).
// Throws std::invalid_argument("weld_volume: ...") on an index out of range.
[[nodiscard]] HomogeneousMesh weld_volume(const HomogeneousMesh& volume);

}  // namespace shadowcert
