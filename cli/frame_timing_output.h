#pragma once
// GPU stage times of timed frames (gpu/frame_timing.h) as `edges --timing` prints them and
// writes them under "timing" in --json, in render --timing's layout (docs/cli.md): per stage and
// per frame the median, min and max of GPU ms (queries) and, with stages bounded by glFinish
// (software renderers), of CPU wall ms.
#include <cstddef>
#include <nlohmann/json.hpp>

#include "gpu/frame_timing.h"

namespace shadowcert::cli {

// {"warm_up_frames", "frames", "stage_sync": "finish"|"none", "gpu_ms": {stage: {median, min,
// max}, ..., "frame": ...}, "cpu_ms": {...}} (cpu_ms holds the stages only with finish).
[[nodiscard]] nlohmann::json frame_timing_json(const gpu::FrameTiming& timing, std::size_t warm_up_frames);

// The table: one row per stage, then the frame, GPU median/min/max and (with finish) CPU ones.
void print_frame_timing(const gpu::FrameTiming& timing, std::size_t warm_up_frames);

}  // namespace shadowcert::cli
