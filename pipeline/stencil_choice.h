#pragma once
// Which stencil method counts each light (docs/gpu.md#proven-z-pass): z-fail, z-pass, or
// `auto`: z-pass for every light for which exact/zpass_proof.h proves it at the scene's camera,
// z-fail for the others. `render --stencil` and `diff --stencil` choose here.
//
//   const std::vector<LightStencil> s = choose_stencil(StencilChoice::automatic, inputs, scene.lights, scene.camera);
//   options.light_stencil = stencil_methods(s);   // gpu::ShadowMethodOptions
//
// The proof runs on the scene as GL receives it: the canonical casters and each light rounded
// to float (exact/cpu_volume.h), whose chain cpu draws and whose every consistent float chain
// cs, gs, ts and pertri draw (exact/zpass_proof.h: n = 0 on the tip makes the winding number of
// each of them 0 there). The tip is gpu/camera_transform.h's near plane, enlarged by the two
// tolerances below: exact/ decides exactly on what it is given and owns no tolerance.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "exact/zpass_proof.h"
#include "gpu/stencil_shadow_renderer.h"
#include "pipeline/method_inputs.h"

namespace shadowcert {

enum class StencilChoice { zfail, zpass, automatic };

// "zfail", "zpass", "auto" (the CLI's --stencil values).
[[nodiscard]] std::string_view stencil_choice_name(StencilChoice choice);
// The choice of that name; nullopt for any other string.
[[nodiscard]] std::optional<StencilChoice> parse_stencil_choice(std::string_view name);

// Relative enlargement of the near rectangle's half extents and of the near distance. It
// absorbs GL's float rounding of the near plane (the projection's -2 near entry) and of the
// projection (1 / half_width, 1 / half_height, each relative 2^-24), and the double rounding of
// the corners computed here: 2^-8 is far beyond all of them.
inline constexpr double kNearTipRelativeMargin = 0x1p-8;
// Absolute margin, relative to the scene's largest coordinate magnitude M (casters, eye, point
// lights): GL transforms float vertices by a float matrix, which moves a point by a few float
// ulps of M (the view translation cancels coordinates of size M), so a face within that
// distance of the tip may be drawn through it. The tip is grown to hold every point within
// kNearTipFloatMargin * M of it (per axis of the camera frame): 2^-14 is 2^10 float epsilons,
// generous for the few roundings of one matrix-vector product; rasterisation near the eye
// (clip w close to 0) has no proven bound, which is why it is generous.
inline constexpr double kNearTipFloatMargin = 0x1p-14;

// The region z-pass counts from, as exact/zpass_proof.h takes it.
struct NearTip {
  Vec3 apex{};                     // behind the eye by the margins
  std::array<Vec3, 4> corners{};   // the enlarged near rectangle, in cyclic order
};

// GL's near-plane tip of `camera` (gpu/camera_transform.h: near plane camera.near_plane, the
// frame of core/pixel_ray.h), enlarged: the apex moved back along the view direction by
// s = d (1 + 1 / min(half_width, half_height)) with d = kNearTipFloatMargin * magnitude, the
// near distance grown by s + d, then everything by kNearTipRelativeMargin. Every point within d
// of the GL tip (per frame axis) lies in the result. Throws std::invalid_argument for a
// degenerate camera (core/pixel_ray.h) or a magnitude that is negative or not finite.
[[nodiscard]] NearTip gl_near_tip(const Camera& camera, double magnitude);

// The magnitude gl_near_tip takes: the largest absolute coordinate of `casters`' vertices, of
// the eye and of the point lights among `lights`.
[[nodiscard]] double scene_magnitude(const Soup& casters, std::span<const Light> lights, const Camera& camera);

// One light's stencil method and, for `auto`, why.
struct LightStencil {
  gpu::StencilMethod method = gpu::StencilMethod::zfail;
  std::optional<ZPassProof> proof;  // auto only
  double seconds = 0.0;             // the proof's time
};

// "requested" without a proof, else zpass_verdict_name of it.
[[nodiscard]] std::string_view stencil_reason(const LightStencil& stencil);
// One line for the text output: "zpass (proven: no face of the exact chain meets the near tip,
// n = 0 there)", "zfail (camera in volume: n(eye) = 2)", "zfail (face meets the near tip: side of
// edge 12-40, m = -1)", "zfail (requested)".
[[nodiscard]] std::string describe_stencil(const LightStencil& stencil);

// Per light of `lights` (those `inputs` was prepared with; a volume method among them, so that
// inputs.canonical and inputs.table are there): `zfail` and `zpass` as requested; `automatic`
// proves z-pass for each light at `camera` (float-rounded casters and light, gl_near_tip) and
// takes z-pass where proven, z-fail elsewhere. Throws std::invalid_argument from prove_zpass and
// gl_near_tip.
[[nodiscard]] std::vector<LightStencil> choose_stencil(StencilChoice choice, const MethodInputs& inputs,
                                                       std::span<const Light> lights, const Camera& camera);

// The methods alone, for gpu::ShadowMethodOptions::light_stencil.
[[nodiscard]] std::vector<gpu::StencilMethod> stencil_methods(std::span<const LightStencil> stencils);

}  // namespace shadowcert
