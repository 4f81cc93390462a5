#include "cli/stencil_output.h"

#include <fmt/core.h>

#include <algorithm>
#include <string>

namespace shadowcert::cli {

nlohmann::json stencil_json(std::span<const LightStencil> stencils) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k < stencils.size(); ++k) {
    const LightStencil& s = stencils[k];
    nlohmann::json j{{"light", k},
                     {"stencil", gpu::stencil_method_name(s.method)},
                     {"reason", stencil_reason(s)}};
    if (s.proof) {
      const ZPassProof& p = *s.proof;
      j["eye_count"] = p.apex_count ? nlohmann::json(*p.apex_count) : nlohmann::json(nullptr);
      j["proof_seconds"] = s.seconds;
      if (p.face_kind == ChainFace::front_cap) j["face"] = {{"kind", "front_cap"}, {"triangle", p.face}};
      if (p.face_kind == ChainFace::side)
        j["face"] = {{"kind", "side"}, {"edge", {p.edge[0], p.edge[1]}}, {"multiplicity", p.multiplicity}};
    }
    out.push_back(j);
  }
  return out;
}

void print_stencil(std::span<const LightStencil> stencils) {
  if (std::none_of(stencils.begin(), stencils.end(), [](const LightStencil& s) { return s.proof.has_value(); }))
    return;
  for (std::size_t k = 0; k < stencils.size(); ++k)
    fmt::print("  light {}: {}\n", k, describe_stencil(stencils[k]));
}

}  // namespace shadowcert::cli
