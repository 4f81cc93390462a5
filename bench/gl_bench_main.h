#pragma once
// What the main() of every benchmark that draws with gpu/ shares: its command line (the
// program's own --x= flags, then Google Benchmark's; a message and exit 2 when either is refused),
// the headless EGL context it draws with (a message and exit 2 without one), the StageSync of its
// --stage-sync=auto|finish|none setting, and the context it adds to Google Benchmark's output (the
// renderer, the stage sync). Bench code only (header-only: each bench is an executable of its
// own, bench/CMakeLists.txt).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <exception>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

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

// The programs' own flags, `--name=VALUE`: VALUE when `arg` is that flag, else nullopt.
inline std::optional<std::string> flag_value(std::string_view arg, std::string_view flag) {
  if (arg.substr(0, flag.size()) != flag) return std::nullopt;
  return std::string(arg.substr(flag.size()));
}

// A comma-separated list of counts ("32000,128000"); std::stoull's exceptions on a bad one.
inline std::vector<std::uint64_t> count_list(const std::string& list) {
  std::vector<std::uint64_t> out;
  for (std::size_t begin = 0; begin <= list.size();) {
    const std::size_t end = std::min(list.find(',', begin), list.size());
    out.push_back(std::stoull(list.substr(begin, end - begin)));
    begin = end + 1;
  }
  return out;
}

// "WxH" as {W, H}; throws std::invalid_argument("FLAG expects WxH, e.g. EXAMPLE") without the x.
inline std::array<std::uint32_t, 2> image_size(const std::string& text, std::string_view flag,
                                               std::string_view example = "1024x768") {
  const std::size_t x = text.find('x');
  if (x == std::string::npos)
    throw std::invalid_argument(std::string(flag) + " expects WxH, e.g. " + std::string(example));
  return {static_cast<std::uint32_t>(std::stoul(text.substr(0, x))),
          static_cast<std::uint32_t>(std::stoul(text.substr(x + 1)))};
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
