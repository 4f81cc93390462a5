#include "gpu/light_side_probe.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/detail/compute_pass.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

constexpr GLint kLightLocation = 0;
constexpr GLint kTripleCountLocation = 1;
constexpr GLuint kPointsBinding = 0;
constexpr GLuint kResultsBinding = 1;

}  // namespace

LightSideProbe::LightSideProbe(SignMode sign) {
  const Shader shader = compile_shader(GL_COMPUTE_SHADER, shaders::light_side_probe_comp, "light_side_probe.comp.glsl",
                                       sign_mode_defines(sign));
  program_ = link_program({&shader}, "light_side_probe");
}

std::vector<LightSideSample> LightSideProbe::evaluate(std::span<const Vec3f> points, const Vec4f& light) const {
  if (points.size() % 3 != 0)
    throw std::invalid_argument("LightSideProbe::evaluate: " + std::to_string(points.size()) +
                                " points are not whole triples");
  const std::size_t triples = points.size() / 3;
  if (triples > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("LightSideProbe::evaluate: more than 2^32 - 1 triples");
  if (!std::isfinite(light[0]) || !std::isfinite(light[1]) || !std::isfinite(light[2]) ||
      (light[3] != 0.0f && light[3] != 1.0f))
    throw std::invalid_argument("LightSideProbe::evaluate: the light must be finite with w = 0 or 1");
  std::vector<LightSideSample> samples(triples);
  if (triples == 0) return samples;

  std::vector<Vec4f> padded;
  padded.reserve(points.size());
  for (const Vec3f& p : points) padded.push_back({p[0], p[1], p[2], 1.0f});
  const Buffer input = Buffer::create();
  compute_pass::upload(input, padded);
  const Buffer output = Buffer::create();
  glNamedBufferStorage(output.name(), static_cast<GLsizeiptr>(triples * 2 * sizeof(std::int32_t)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);

  const GLuint program = program_.name();
  glProgramUniform4f(program, kLightLocation, light[0], light[1], light[2], light[3]);
  glProgramUniform1ui(program, kTripleCountLocation, static_cast<GLuint>(triples));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPointsBinding, input.name());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kResultsBinding, output.name());
  glUseProgram(program);
  compute_pass::dispatch(static_cast<std::uint32_t>(triples));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glUseProgram(0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPointsBinding, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kResultsBinding, 0);
  const std::vector<std::int32_t> raw =
      compute_pass::read_buffer<std::int32_t>(output.name(), 0, 2 * triples, "LightSideProbe::evaluate");
  for (std::size_t i = 0; i < triples; ++i) samples[i] = {raw[2 * i], raw[2 * i + 1] != 0};
  return samples;
}

}  // namespace shadowcert::gpu
