#pragma once
// Which volume VolumeWorkspace builds (volume/volume_workspace.h). One method so far: the robust
// one, the volume `render --method cpu` draws (exact/cpu_volume.h): the exact chain of the
// float-rounded input, side quads repeated |m| times by their exact multiplicity, front and
// back caps; closed by construction (docs/definitions.md#closure). The enum leaves room for the
// float methods, which are not robust and are not offered here.
#include <cstdint>
#include <string_view>

namespace shadowcert {

enum class VolumeMethod : std::uint8_t {
  cpu,  // render --method cpu: the exact chain of the input as the GPU receives it (float)
};

// "cpu": the CLI's --method name of the same volume.
[[nodiscard]] constexpr std::string_view volume_method_name(VolumeMethod method) {
  switch (method) {
    case VolumeMethod::cpu:
      return "cpu";
  }
  return "unknown";
}

}  // namespace shadowcert
