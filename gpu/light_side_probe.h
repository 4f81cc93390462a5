#pragma once
// The GL methods' light-side sign (gpu/shaders/light_side_sign.glsl, the code cs, gs, ts and
// pertri include) evaluated on given vertex triples: for tests that hold the GPU's signs to
// exact/'s bit for bit, and for the exact filter's fallback rate (docs/gpu.md "Exact signs").
//
//   LightSideProbe probe;                                  // compiles the shader
//   auto samples = probe.evaluate(triples, light);         // one GPU dispatch
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/gl_object.h"
#include "gpu/sign_mode.h"

namespace shadowcert::gpu {

using Vec3f = std::array<float, 3>;
using Vec4f = std::array<float, 4>;

struct LightSideSample {
  std::int32_t sign = 0;  // sign D(a, b, c, L): -1, 0 or 1
  bool fallback = false;  // the filter could not decide; the exact integer stage answered
};

class LightSideProbe {
 public:
  // Needs a current context; throws GlError with the driver's log.
  explicit LightSideProbe(SignMode sign = SignMode::exact);

  // `points`: 3 per triple (a, b, c); `light`: (l, w), w = 0 or 1. Throws std::invalid_argument
  // ("LightSideProbe::evaluate: ...") on a point count not a multiple of 3 or above 2^32 - 1
  // triples, or a light that is not finite with w in {0, 1}.
  [[nodiscard]] std::vector<LightSideSample> evaluate(std::span<const Vec3f> points, const Vec4f& light) const;

 private:
  Program program_;
};

}  // namespace shadowcert::gpu
