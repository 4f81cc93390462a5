#pragma once
// A smooth caster (contour/smooth_caster.h) as the plain arrays the GPU build of its smooth
// volume reads (gpu/smooth_silhouette_volume.h: `smooth-gpu`): contour/ and gpu/ know nothing of
// each other, pipeline/ puts them together.
#include "contour/smooth_caster.h"
#include "gpu/smooth_silhouette_volume.h"

namespace shadowcert {

// Appends `caster` to `arrays` (indices moved past what `arrays` holds), every triangle with
// the mesh's `epsilon` (world units, > 0) and `cap_offset` (>= 0; SmoothVolumeOptions). Throws
// std::invalid_argument("append_smooth_caster: ...") on a bad epsilon or cap offset, or when the
// concatenation outgrows 32-bit indices.
void append_smooth_caster(gpu::SmoothCasterArrays& arrays, const SmoothCaster& caster, double epsilon,
                          double cap_offset);

}  // namespace shadowcert
