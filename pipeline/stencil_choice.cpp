#include "pipeline/stencil_choice.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/float_rounding.h"
#include "core/pixel_ray.h"
#include "gpu/camera_transform.h"

namespace shadowcert {

std::string_view stencil_choice_name(StencilChoice choice) {
  switch (choice) {
    case StencilChoice::zfail: return "zfail";
    case StencilChoice::zpass: return "zpass";
    case StencilChoice::automatic: return "auto";
  }
  throw std::invalid_argument("stencil_choice_name: unknown choice " + std::to_string(static_cast<int>(choice)));
}

std::optional<StencilChoice> parse_stencil_choice(std::string_view name) {
  for (StencilChoice c : {StencilChoice::zfail, StencilChoice::zpass, StencilChoice::automatic})
    if (stencil_choice_name(c) == name) return c;
  return std::nullopt;
}

NearTip gl_near_tip(const Camera& camera, double magnitude) {
  if (!(magnitude >= 0.0) || !std::isfinite(magnitude))
    throw std::invalid_argument("gl_near_tip: the magnitude must be finite and >= 0");
  const CameraFrame f = camera_frame(camera, "gl_near_tip");
  const double d = kNearTipFloatMargin * magnitude;
  const double back = d * (1.0 + 1.0 / std::min(f.half_width, f.half_height));
  const double grow = 1.0 + kNearTipRelativeMargin;
  // The GL tip is {eye + t (forward + a right + b up) : t in [0, near], |a| <= hw, |b| <= hh};
  // from the apex eye - back * forward, parameter t' = t + back + dt, a point within d of it
  // (per axis) has t' in [back - d, near + back + d] and |a'| <= hw (since back - d >= d / hw).
  const double near = (camera.near_plane + back + d) * grow;
  const double hw = f.half_width * grow;
  const double hh = f.half_height * grow;
  NearTip tip;
  for (std::size_t k = 0; k < 3; ++k) tip.apex[k] = f.eye[k] - back * f.forward[k];
  constexpr std::array<std::array<double, 2>, 4> kCorners{{{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}};
  for (std::size_t c = 0; c < 4; ++c)
    for (std::size_t k = 0; k < 3; ++k)
      tip.corners[c][k] = tip.apex[k] + near * (f.forward[k] + kCorners[c][0] * hw * f.right[k] +
                                                kCorners[c][1] * hh * f.up[k]);
  return tip;
}

double scene_magnitude(const Soup& casters, std::span<const Light> lights, const Camera& camera) {
  double m = 0.0;
  const auto add = [&m](const Vec3& p) {
    for (double x : p) m = std::max(m, std::abs(x));
  };
  for (const Vec3& v : casters.vertices) add(v);
  add(camera.eye);
  for (const Light& l : lights)
    if (!l.directional()) add({l.position[0], l.position[1], l.position[2]});
  return m;
}

std::string_view stencil_reason(const LightStencil& stencil) {
  return stencil.proof ? zpass_verdict_name(stencil.proof->verdict) : std::string_view("requested");
}

std::string describe_stencil(const LightStencil& stencil) {
  const std::string_view method = gpu::stencil_method_name(stencil.method);
  if (!stencil.proof) return fmt::format("{} (requested)", method);
  const ZPassProof& p = *stencil.proof;
  switch (p.verdict) {
    case ZPassVerdict::proven:
      return fmt::format("{} (proven: no face of the exact chain meets the near tip, n = 0 there)", method);
    case ZPassVerdict::camera_in_volume:
      return p.apex_count ? fmt::format("{} (camera in volume: n(eye) = {})", method, *p.apex_count)
                          : fmt::format("{} (camera in volume: n > 0 in the near tip)", method);
    case ZPassVerdict::face_meets_tip:
      if (p.face_kind == ChainFace::side)
        return fmt::format("{} (face meets the near tip: side of edge {}-{}, m = {})", method, p.edge[0], p.edge[1],
                           p.multiplicity);
      return fmt::format("{} (face meets the near tip: front cap of triangle {})", method, p.face);
    case ZPassVerdict::count_undefined:
      return fmt::format("{} (camera on a volume boundary: n undefined in the near tip)", method);
  }
  return std::string(method);
}

std::vector<LightStencil> choose_stencil(StencilChoice choice, const MethodInputs& inputs,
                                         std::span<const Light> lights, const Camera& camera) {
  std::vector<LightStencil> out(lights.size());
  if (choice != StencilChoice::automatic) {
    for (LightStencil& s : out)
      s.method = choice == StencilChoice::zpass ? gpu::StencilMethod::zpass : gpu::StencilMethod::zfail;
    return out;
  }
  // What GL receives (exact/cpu_volume.h): ids and topology of the canonical soup, so the
  // table serves the rounded soup as well.
  const Soup rounded = float_rounded(inputs.canonical.soup);
  const NearTip tip = gl_near_tip(camera, scene_magnitude(rounded, lights, camera));
  for (std::size_t k = 0; k < lights.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    out[k].proof = prove_zpass(rounded, inputs.table, float_rounded(lights[k]), tip.apex, tip.corners);
    out[k].method = out[k].proof->proven() ? gpu::StencilMethod::zpass : gpu::StencilMethod::zfail;
    out[k].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return out;
}

std::vector<gpu::StencilMethod> stencil_methods(std::span<const LightStencil> stencils) {
  std::vector<gpu::StencilMethod> methods;
  methods.reserve(stencils.size());
  for (const LightStencil& s : stencils) methods.push_back(s.method);
  return methods;
}

}  // namespace shadowcert
