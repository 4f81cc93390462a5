#include "exact/volume_closure.h"

#include "exact/shadow_volume_chain.h"
#include "scene/welded_volume.h"

namespace shadowcert {

VolumeClosure certify_volume_closure(const HomogeneousMesh& volume) {
  VolumeClosure result{weld_volume(volume), {}};
  // certify_closure on a triangles-only chain: with `directional` its id range is n + 1,
  // which covers the n welded vertices; the far-vertex convention plays no part here.
  ShadowVolumeChain chain;
  chain.finite_vertices = static_cast<std::uint32_t>(result.welded.vertices.size());
  chain.directional = true;
  chain.triangles = result.welded.triangles;
  result.certificate = certify_closure(chain);
  return result;
}

}  // namespace shadowcert
