#pragma once
// The per-light stencil methods of `render` and `diff` (pipeline/stencil_choice.h) as they
// report them: one text line per light in auto mode, and the JSON's "stencil_per_light" array
// (docs/cli.md).
#include <nlohmann/json.hpp>

#include <span>

#include "pipeline/stencil_choice.h"

namespace shadowcert::cli {

// [{"light": k, "stencil": "zpass"|"zfail", "reason": "requested"|"proven"|"camera_in_volume"|
//   "face_meets_tip"|"count_undefined", and with a proof "eye_count" (n at the near tip's apex, null
//   when undefined there), "proof_seconds", and for face_meets_tip "face": {"kind": "front_cap",
//   "triangle": t} or {"kind": "side", "edge": [u, v], "multiplicity": m}}, ...]; triangle and vertex
// ids are the canonical soup's.
[[nodiscard]] nlohmann::json stencil_json(std::span<const LightStencil> stencils);

// "  light K: zpass (proven: ...)" per light, on stdout; nothing when no light has a proof
// (a requested method is stated once in the header line).
void print_stencil(std::span<const LightStencil> stencils);

}  // namespace shadowcert::cli
