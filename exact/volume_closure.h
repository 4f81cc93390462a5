#pragma once
// Closure of a volume as drawn (docs/definitions.md#closure): the homogeneous float triangles a
// GL method emitted (captured by transform feedback, or read from a .vol file), welded and
// balanced edge by edge exactly as certify_closure does for a chain.
#include "core/homogeneous_mesh.h"
#include "exact/closure_certificate.h"

namespace shadowcert {

// `welded`: the input after scene/welded_volume.h's weld_volume; UnbalancedEdge ids index it.
struct VolumeClosure {
  HomogeneousMesh welded;
  ClosureCertificate certificate;
};
// Throws std::invalid_argument on a triangle index out of range (from weld_volume).
[[nodiscard]] VolumeClosure certify_volume_closure(const HomogeneousMesh& volume);

}  // namespace shadowcert
