#pragma once
// GPU stage times of timed frames (gpu/frame_timing.h) as `render --timing` and `edges --timing` print them and
// writes them under "timing" in --json, in render --timing's layout (docs/cli.md): per stage and
// per frame the median, min and max of GPU ms (queries) and, with stages bounded by glFinish
// (software renderers), of CPU wall ms.
#include <cstddef>
#include <nlohmann/json.hpp>

#include "gpu/frame_timing.h"

namespace shadowcert::cli {

// Frames drawn (without readback, each ended by glFinish) for the ms-per-frame figure that
// render, diff and edges print without --timing: one frame alone would mostly time llvmpipe's
// first-use shader compilation.
inline constexpr std::size_t kPlainTimedFrames = 5;
// --timing: untimed frames first (llvmpipe compiles shader variants on first use), then
// --frames timed ones (default kDefaultTimingFrames) whose medians are reported.
inline constexpr std::size_t kTimingWarmUpFrames = 2;
inline constexpr std::size_t kDefaultTimingFrames = 20;

// {"median", "min", "max"} of one stage's or frame's times, ms.
[[nodiscard]] nlohmann::json timing_summary_json(const gpu::TimingSummary& summary);

// {"warm_up_frames", "frames", "stage_sync": "finish"|"none", "gpu_ms": {stage: {median, min,
// max}, ..., "frame": ...}, "cpu_ms": {...}} (cpu_ms holds the stages only with finish).
[[nodiscard]] nlohmann::json frame_timing_json(const gpu::FrameTiming& timing, std::size_t warm_up_frames);

// The table: one row per stage, then the frame, GPU median/min/max and (with finish) CPU ones.
void print_frame_timing(const gpu::FrameTiming& timing, std::size_t warm_up_frames);

}  // namespace shadowcert::cli
