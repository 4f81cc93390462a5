#pragma once
// What `render --timing` and bench/render_bench.cpp report of N timed frames: for each stage
// of the method (gpu/gpu_stage_timer.h) and for the whole frame, the median, min and max GPU
// time over the frames, and the same of each frame's CPU wall time. Medians, because a shared
// machine or a driver's first-use work spoils single frames, not the middle one.
#include <array>
#include <span>
#include <vector>

#include "gpu/gpu_stage_timer.h"

namespace shadowcert::gpu {

struct TimingSummary {
  double median_ms = 0.0;  // the middle sample; the mean of the two middle ones for an even count
  double min_ms = 0.0;
  double max_ms = 0.0;
};

// Throws std::invalid_argument("summarize: ...") when `samples_ms` is empty.
[[nodiscard]] TimingSummary summarize(std::span<const double> samples_ms);

struct FrameTiming {
  std::size_t frames = 0;
  StageSync sync = StageSync::none;
  std::vector<RenderStage> stages;                           // the method's, in frame order
  // By RenderStage (zeros for stages not in `stages`): GPU time from the queries; CPU wall
  // time with StageSync::finish (zeros with none).
  std::array<TimingSummary, kRenderStageCount> stage_gpu{};
  std::array<TimingSummary, kRenderStageCount> stage_wall{};
  TimingSummary frame_gpu;  // timestamp at the frame's start to timestamp at its end
  TimingSummary frame_cpu;  // wall time of each frame, its closing glFinish included
  double mean_cpu_ms = 0.0;  // mean wall time per frame (render's `frame_ms`)

  [[nodiscard]] const TimingSummary& gpu(RenderStage s) const { return stage_gpu[static_cast<std::size_t>(s)]; }
  [[nodiscard]] const TimingSummary& wall(RenderStage s) const { return stage_wall[static_cast<std::size_t>(s)]; }
};

// Summaries of frame i's times gpu[i] (taken with `sync`) and wall time cpu_ms[i]. Throws
// std::invalid_argument("summarize_frames: ...") when there is no frame or the two counts differ.
[[nodiscard]] FrameTiming summarize_frames(std::span<const RenderStage> stages, StageSync sync,
                                           std::span<const FrameStageTimes> gpu, std::span<const double> cpu_ms);

}  // namespace shadowcert::gpu
