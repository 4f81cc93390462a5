#include "exact/cpu_volume.h"

#include "exact/chain_mesh.h"
#include "exact/edge_multiplicity.h"
#include "core/float_rounding.h"
#include "exact/shadow_volume_chain.h"

namespace shadowcert {

HomogeneousMesh cpu_volume_mesh(const Soup& canonical, const EdgeTable& table, const Light& light) {
  // Rounded values are exact doubles: rounding them again (chain_mesh's upload) changes nothing,
  // and the far vertices x - l are formed from the rounded x and l, as the GPU forms them.
  const Soup rounded = float_rounded(canonical);
  const Light rounded_light = float_rounded(light);
  const EdgeMultiplicities m = exact_multiplicities(rounded, table, rounded_light);
  return chain_mesh(assemble_chain(rounded, table, m, rounded_light), rounded, rounded_light);
}

}  // namespace shadowcert
