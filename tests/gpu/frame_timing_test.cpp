// gpu/frame_timing.h: medians, minima and maxima of timed frames, and the stages' JSON keys
// (gpu/gpu_stage_timer.h's render_stage_name). No GL context needed.
#include "gpu/frame_timing.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string_view>
#include <vector>

namespace shadowcert::gpu {
namespace {

TEST(Summarize, OddCount_MedianIsTheMiddleSampleInAnyOrder) {
  const std::vector<double> samples{9.0, 1.0, 5.0, 7.0, 3.0};
  const TimingSummary s = summarize(samples);
  EXPECT_EQ(s.median_ms, 5.0);
  EXPECT_EQ(s.min_ms, 1.0);
  EXPECT_EQ(s.max_ms, 9.0);
}

TEST(Summarize, EvenCount_MedianIsTheMeanOfTheTwoMiddleSamples) {
  const std::vector<double> samples{4.0, 100.0, 1.0, 2.0};
  EXPECT_EQ(summarize(samples).median_ms, 3.0);
  EXPECT_EQ(summarize(std::vector<double>{2.5}).median_ms, 2.5);
}

TEST(Summarize, NoSample_Throws) { EXPECT_THROW((void)summarize(std::vector<double>{}), std::invalid_argument); }

TEST(SummarizeFrames, PerStageAndFrame_OnlyTheMethodsStagesFilled) {
  std::vector<FrameStageTimes> gpu(3);
  for (int f = 0; f < 3; ++f) {
    gpu[f].gpu_ms[static_cast<std::size_t>(RenderStage::depth)] = 1.0 + f;
    gpu[f].wall_ms[static_cast<std::size_t>(RenderStage::depth)] = 10.0 + f;
    gpu[f].gpu_ms[static_cast<std::size_t>(RenderStage::lit)] = 4.0 - f;
    gpu[f].frame_ms = 20.0 * (f + 1);
  }
  const std::vector<double> cpu{30.0, 10.0, 20.0};
  const std::vector<RenderStage> stages{RenderStage::depth, RenderStage::lit};
  const FrameTiming t = summarize_frames(stages, StageSync::finish, gpu, cpu);
  EXPECT_EQ(t.frames, 3u);
  EXPECT_EQ(t.stages, stages);
  EXPECT_EQ(t.gpu(RenderStage::depth).median_ms, 2.0);
  EXPECT_EQ(t.wall(RenderStage::depth).max_ms, 12.0);
  EXPECT_EQ(t.gpu(RenderStage::lit).min_ms, 2.0);
  EXPECT_EQ(t.gpu(RenderStage::stencil).max_ms, 0.0);  // not a stage of this method
  EXPECT_EQ(t.frame_gpu.median_ms, 40.0);
  EXPECT_EQ(t.frame_cpu.median_ms, 20.0);
  EXPECT_EQ(t.mean_cpu_ms, 20.0);
  // Without stage sync the wall times are not summarised (they are all zero).
  EXPECT_EQ(summarize_frames(stages, StageSync::none, gpu, cpu).wall(RenderStage::depth).max_ms, 0.0);
}

TEST(SummarizeFrames, NoFrameOrCountsDiffer_Throws) {
  const std::vector<RenderStage> stages{RenderStage::depth};
  EXPECT_THROW((void)summarize_frames(stages, StageSync::none, {}, {}), std::invalid_argument);
  const std::vector<FrameStageTimes> gpu(2);
  const std::vector<double> cpu{1.0};
  EXPECT_THROW((void)summarize_frames(stages, StageSync::none, gpu, cpu), std::invalid_argument);
}

TEST(RenderStageName, EveryStage_HasItsJsonKey) {
  const std::vector<std::string_view> expected{"volume", "depth", "stencil", "lit", "shadow_map", "smoothie_map",
                                             "g_buffer", "edge_filter", "composite"};
  ASSERT_EQ(kRenderStages.size(), expected.size());
  for (std::size_t i = 0; i < kRenderStages.size(); ++i) EXPECT_EQ(render_stage_name(kRenderStages[i]), expected[i]);
}

}  // namespace
}  // namespace shadowcert::gpu
