#pragma once
// What the main() of every benchmark that draws with gpu/ shares: its command line (the
// program's own --x= flags, then Google Benchmark's; a message and exit 2 when either is refused),
// the headless EGL context it draws with (a message and exit 2 without one), the StageSync of its
// --stage-sync=auto|finish|none setting, and the context it adds to Google Benchmark's output (the
// renderer, the stage sync). Bench code only (header-only: each bench is an executable of its
// own, bench/CMakeLists.txt).
#include <benchmark/benchmark.h>

#include <exception>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "gpu/egl_context.h"
#include "gpu/gl_environment_error.h"
#include "gpu/gpu_stage_timer.h"

namespace shadowcert::bench {

// The command line: `take(argc, argv)` parses and removes the program's own flags (Google
// Benchmark rejects flags it does not know) and throws on a bad value; Google Benchmark takes the
// rest. False, after a message on stderr naming `program`, when either refuses it (main then
// returns 2).
template <class Take>
bool take_command_line(std::string_view program, int& argc, char** argv, Take&& take) {
  try {
    take(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << '\n';
    return false;
  }
  benchmark::Initialize(&argc, argv);
  return !benchmark::ReportUnrecognizedArguments(argc, argv);
}

// The same, for a program whose `take_settings` returns its settings: into `settings`.
template <class Settings>
bool take_command_line(std::string_view program, int& argc, char** argv, Settings& settings,
                       Settings (*take_settings)(int&, char**)) {
  return take_command_line(program, argc, argv, [&](int& n, char** args) { settings = take_settings(n, args); });
}

// The context `program` draws with, current on this thread; nullopt, after a message on stderr
// naming `program`, when the machine gives no OpenGL 4.5 core through headless EGL (main then
// returns 2).
inline std::optional<gpu::EglContext> open_bench_context(std::string_view program) {
  std::optional<gpu::EglContext> context;
  try {
    context.emplace(gpu::EglContextOptions{});
  } catch (const gpu::GlEnvironmentError& e) {
    std::cerr << program << ": needs OpenGL 4.5 core through headless EGL: " << e.what() << '\n';
  }
  return context;
}

// The value of --stage-sync=VALUE; throws std::invalid_argument unless auto, finish or none.
inline std::string stage_sync_setting(std::string_view value) {
  if (value != "auto" && value != "finish" && value != "none")
    throw std::invalid_argument("--stage-sync expects auto, finish or none");
  return std::string(value);
}

// finish or none as asked; auto: finish on a software renderer (llvmpipe, whose timer queries
// do not time its stages: gpu/gpu_stage_timer.h), none (GPU timer queries only) on a GPU.
inline gpu::StageSync chosen_stage_sync(std::string_view setting, const gpu::EglContext& context) {
  return setting == "finish" ? gpu::StageSync::finish
         : setting == "none" ? gpu::StageSync::none
         : context.software() ? gpu::StageSync::finish
                              : gpu::StageSync::none;
}

// The renderer and the stage sync in the output's context; `timed` names what the program times
// in stages ("passes", "stages"): "finish (passes: wall ms)" or "none (passes: GPU query ms)".
inline void add_gl_context(const gpu::EglContext& context, gpu::StageSync sync, std::string_view timed) {
  benchmark::AddCustomContext("renderer", context.renderer());
  benchmark::AddCustomContext("stage_sync", sync == gpu::StageSync::finish
                                                ? "finish (" + std::string(timed) + ": wall ms)"
                                                : "none (" + std::string(timed) + ": GPU query ms)");
}

}  // namespace shadowcert::bench
