#include "cli/frame_timing_output.h"

#include <fmt/core.h>

#include <string>
#include <string_view>

namespace shadowcert::cli {
nlohmann::json timing_summary_json(const gpu::TimingSummary& s) {
  return {{"median", s.median_ms}, {"min", s.min_ms}, {"max", s.max_ms}};
}

nlohmann::json frame_timing_json(const gpu::FrameTiming& timing, std::size_t warm_up_frames) {
  const bool synchronised = timing.sync == gpu::StageSync::finish;
  nlohmann::json gpu_ms = nlohmann::json::object();
  nlohmann::json cpu_ms = nlohmann::json::object();
  for (gpu::RenderStage stage : timing.stages) {
    const std::string name(gpu::render_stage_name(stage));
    gpu_ms[name] = timing_summary_json(timing.gpu(stage));
    if (synchronised) cpu_ms[name] = timing_summary_json(timing.wall(stage));
  }
  gpu_ms["frame"] = timing_summary_json(timing.frame_gpu);
  cpu_ms["frame"] = timing_summary_json(timing.frame_cpu);
  return {{"warm_up_frames", warm_up_frames},
          {"frames", timing.frames},
          {"stage_sync", synchronised ? "finish" : "none"},
          {"gpu_ms", gpu_ms},
          {"cpu_ms", cpu_ms}};
}

void print_frame_timing(const gpu::FrameTiming& timing, std::size_t warm_up_frames) {
  const bool synchronised = timing.sync == gpu::StageSync::finish;
  fmt::print("  timing, ms over {} frames after {} warm-up{}:\n", timing.frames, warm_up_frames,
             synchronised ? " (stages bounded by glFinish: software renderer)" : "");
  fmt::print("    {:<12} {:>10} {:>8} {:>8}   {:>10} {:>8} {:>8}\n", "stage", "gpu median", "min", "max",
             "cpu median", "min", "max");
  const auto row = [](std::string_view name, const gpu::TimingSummary& gpu, const gpu::TimingSummary* cpu) {
    fmt::print("    {:<12} {:10.3f} {:8.3f} {:8.3f}", name, gpu.median_ms, gpu.min_ms, gpu.max_ms);
    if (cpu != nullptr) fmt::print("   {:10.3f} {:8.3f} {:8.3f}", cpu->median_ms, cpu->min_ms, cpu->max_ms);
    fmt::print("\n");
  };
  for (gpu::RenderStage stage : timing.stages)
    row(gpu::render_stage_name(stage), timing.gpu(stage), synchronised ? &timing.wall(stage) : nullptr);
  row("frame", timing.frame_gpu, &timing.frame_cpu);
}

}  // namespace shadowcert::cli
