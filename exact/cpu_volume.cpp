#include "exact/cpu_volume.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "core/float_rounding.h"
#include "exact/chain_mesh.h"

namespace shadowcert {

HomogeneousMesh cpu_volume_mesh(const Soup& canonical, const EdgeTable& table, const Light& light) {
  // Rounded values are exact doubles: rounding them again (chain_mesh's upload) changes nothing,
  // and the far vertices x - l are formed from the rounded x and l, as the GPU forms them.
  require_defined(light, "cpu_volume_mesh");
  CpuVolumeBuffers buffers;
  rounded_cpu_volume(float_rounded(canonical), table, light, buffers);
  return std::move(buffers.mesh);
}

void rounded_cpu_volume(const Soup& rounded, const EdgeTable& table, const Light& light, CpuVolumeBuffers& buffers) {
  // A soup that is not float-rounded would give a volume of geometry the GPU never receives.
  for (std::size_t v = 0; v < rounded.vertices.size(); ++v)
    for (const double x : rounded.vertices[v])
      if (float_rounded(x) != x)
        throw std::invalid_argument("rounded_cpu_volume: vertex " + std::to_string(v) +
                                    " has a coordinate that is not a float value");
  require_defined(light, "rounded_cpu_volume");
  const Light rounded_light = float_rounded(light);
  exact_multiplicities(rounded, table, rounded_light, buffers.multiplicities);
  assemble_chain(rounded, table, buffers.multiplicities, rounded_light, buffers.chain);
  chain_mesh(buffers.chain, rounded, rounded_light, buffers.mesh);
}

}  // namespace shadowcert
