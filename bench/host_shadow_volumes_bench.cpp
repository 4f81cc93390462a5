// What each call of the GL layer for a host's context (gpu/host_shadow_volumes.h) costs, on
// the bundled scenes at 1024x768 (docs/engine-integration.md#per-frame-cost-on-llvmpipe): the
// host's framebuffer bound and its depth drawn once, then per iteration one call followed by
// glFinish, so that the time is the call's work on the device (llvmpipe: the CPU), not only its
// queuing. `build` is the GPU build of the volume (nothing for cpu), `draw_stencil` the
// stencil-only entry, `draw_lit` the full entry (the counts and the lit receivers).
//
//   build/bench/host_shadow_volumes_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <filesystem>
#include <memory>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "gl_bench_main.h"
#include "gpu/camera_transform.h"
#include "gpu/host_shadow_volumes.h"
#include "gpu/offscreen_target.h"
#include "gpu/shader_compiler.h"
#include "gpu/shadow_method_renderer.h"
#include "io/soup_file.h"
#include "pipeline/drawn_method_scene.h"
#include "scene/scene_file.h"

namespace shadowcert {
namespace {

constexpr std::uint32_t kWidth = 1024;
constexpr std::uint32_t kHeight = 768;

// The host's depth pass: the state contract's position expression.
constexpr const char* kVertex = R"(#version 450 core
layout(location = 0) in vec4 position;
layout(location = 0) uniform mat4 world_to_clip;
invariant gl_Position;
void main() { precise vec4 clip = world_to_clip * position; gl_Position = clip; }
)";
constexpr const char* kFragment = R"(#version 450 core
layout(location = 0) out vec4 fragment;
void main() { fragment = vec4(0.1, 0.1, 0.1, 1.0); }
)";

enum class Call { build, draw_stencil, draw_lit };

void run(benchmark::State& state, const std::string& scene_name, gpu::ShadowMethod method, Call call) {
  Scene scene = load_scene(std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "scenes" / scene_name,
                           [](const std::filesystem::path& f) { return read_soup(f); });
  scene.camera.width = kWidth;
  scene.camera.height = kHeight;
  const auto d = prepare_drawn_method_scene(scene, method, StencilChoice::zfail);
  const gpu::ShadedSoupMesh receivers(d->parts);
  const gpu::OffscreenTarget target(kWidth, kHeight);
  const gpu::Shader vs = gpu::compile_shader(GL_VERTEX_SHADER, kVertex, "host.vert");
  const gpu::Shader fs = gpu::compile_shader(GL_FRAGMENT_SHADER, kFragment, "host.frag");
  const gpu::Program program = gpu::link_program({&vs, &fs}, "host");
  const glm::mat4 clip(gpu::projection_matrix(d->scene.camera) * gpu::view_matrix(d->scene.camera));
  target.bind();
  target.clear();
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(program.name());
  glProgramUniformMatrix4fv(program.name(), 0, 1, GL_FALSE, glm::value_ptr(clip));
  glBindVertexArray(receivers.vertex_array());
  glDrawArrays(GL_TRIANGLES, 0, receivers.vertex_count());
  glBindVertexArray(0);
  glUseProgram(0);
  gpu::HostShadowVolumes shadows(method, d->method_scene(), d->host_options());
  const gpu::HostReceivers r = gpu::host_receivers(receivers);
  shadows.build();
  for (int warm = 0; warm < 2; ++warm) {  // llvmpipe compiles shader variants on first use
    shadows.build();
    shadows.draw_lit(clip, 0, r, {0.85f, 0.85f, 0.85f});
  }
  glFinish();
  for (auto _ : state) {
    if (call == Call::build) shadows.build();
    if (call == Call::draw_stencil) shadows.draw_stencil(clip, 0);
    if (call == Call::draw_lit) shadows.draw_lit(clip, 0, r, {0.85f, 0.85f, 0.85f});
    glFinish();
  }
  state.counters["caster_triangles"] = static_cast<double>(d->casters.triangles.size());
}

}  // namespace
}  // namespace shadowcert

int main(int argc, char** argv) {
  using namespace shadowcert;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  const std::optional<gpu::EglContext> context = bench::open_bench_context("host_shadow_volumes_bench");
  if (!context) return 2;
  benchmark::AddCustomContext("renderer", context->renderer());
  for (const char* scene : {"default.json", "lamp_in_room.json", "sphere_over_floor.json"})
    for (const gpu::ShadowMethod method : {gpu::ShadowMethod::cpu, gpu::ShadowMethod::cs, gpu::ShadowMethod::gs,
                                           gpu::ShadowMethod::ts, gpu::ShadowMethod::pertri})
      for (const auto& [call, name] : {std::pair{Call::build, "build"}, std::pair{Call::draw_stencil, "draw_stencil"},
                                       std::pair{Call::draw_lit, "draw_lit"}}) {
        if (call == Call::build && method == gpu::ShadowMethod::cpu) continue;  // nothing to build
        const std::string s = scene;
        benchmark::RegisterBenchmark(fmt::format("{}/{}/{}", scene, gpu::shadow_method_name(method), name).c_str(),
                                     [s, method, call = call](benchmark::State& st) { run(st, s, method, call); })
            ->Unit(benchmark::kMillisecond)
            ->MinTime(0.2);
      }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
