#pragma once
// How the GL volume methods (cs, gs, ts, pertri) take each triangle's light side s(t)
// (docs/definitions.md#orientation, docs/gpu.md "Exact signs"):
//   exact   : the exact sign of the float inputs (a float filter with a proven bound, integer
//             arithmetic where it cannot decide; gpu/shaders/light_side_sign.glsl), equal to
//             exact/'s glsign multiplicities of the float-rounded scene. The default.
//   float32 : the float value's sign (Milet 2014's refedge as written), equal to exact/'s
//             float32 refedge; kept so that speed against error stays measurable (`--sign float`).
#include <optional>
#include <string_view>

namespace shadowcert::gpu {

enum class SignMode { exact, float32 };

// "exact" or "float" (the CLI's spelling).
[[nodiscard]] constexpr std::string_view sign_mode_name(SignMode mode) {
  return mode == SignMode::exact ? "exact" : "float";
}

[[nodiscard]] constexpr std::optional<SignMode> parse_sign_mode(std::string_view name) {
  if (name == "exact") return SignMode::exact;
  if (name == "float") return SignMode::float32;
  return std::nullopt;
}

// The GLSL preamble a shader that takes a sign is compiled with (after its #version line).
[[nodiscard]] constexpr std::string_view sign_mode_defines(SignMode mode) {
  return mode == SignMode::exact ? std::string_view{} : std::string_view{"#define SHADOWCERT_FLOAT_SIGNS 1\n"};
}

}  // namespace shadowcert::gpu
