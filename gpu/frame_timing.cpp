#include "gpu/frame_timing.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace shadowcert::gpu {

TimingSummary summarize(std::span<const double> samples_ms) {
  if (samples_ms.empty()) throw std::invalid_argument("summarize: no sample");
  std::vector<double> sorted(samples_ms.begin(), samples_ms.end());
  std::sort(sorted.begin(), sorted.end());
  const std::size_t middle = sorted.size() / 2;
  const double median = sorted.size() % 2 == 1 ? sorted[middle] : 0.5 * (sorted[middle - 1] + sorted[middle]);
  return {median, sorted.front(), sorted.back()};
}

FrameTiming summarize_frames(std::span<const RenderStage> stages, StageSync sync,
                             std::span<const FrameStageTimes> gpu, std::span<const double> cpu_ms) {
  if (gpu.empty()) throw std::invalid_argument("summarize_frames: no frame");
  if (gpu.size() != cpu_ms.size())
    throw std::invalid_argument("summarize_frames: " + std::to_string(gpu.size()) + " GPU frames but " +
                                std::to_string(cpu_ms.size()) + " wall times");
  FrameTiming timing;
  timing.frames = gpu.size();
  timing.sync = sync;
  timing.stages.assign(stages.begin(), stages.end());
  std::vector<double> samples(gpu.size());
  const auto summary_of = [&](auto&& sample) {
    std::transform(gpu.begin(), gpu.end(), samples.begin(), sample);
    return summarize(samples);
  };
  for (RenderStage stage : stages) {
    const auto s = static_cast<std::size_t>(stage);
    timing.stage_gpu[s] = summary_of([stage](const FrameStageTimes& t) { return t.gpu(stage); });
    if (sync == StageSync::finish)
      timing.stage_wall[s] = summary_of([stage](const FrameStageTimes& t) { return t.wall(stage); });
  }
  timing.frame_gpu = summary_of([](const FrameStageTimes& t) { return t.frame_ms; });
  timing.frame_cpu = summarize(cpu_ms);
  timing.mean_cpu_ms = std::accumulate(cpu_ms.begin(), cpu_ms.end(), 0.0) / static_cast<double>(cpu_ms.size());
  return timing;
}

}  // namespace shadowcert::gpu
