// gpu/gpu_stage_timer.h: one result per frame, in frame order, through a ring smaller than the
// number of frames; stages summed over their intervals and 0 where not run; wall times of
// StageSync::finish that cover what the interval did; misuse rejected.
#include "gpu/gpu_stage_timer.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <vector>

#include "gl_test_support.h"
#include "gpu/offscreen_target.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;

// A frame of frame i sleeps (i + 1) x kSleepMs inside its lit interval: long against timer
// and scheduler granularity, short enough for a test.
constexpr double kSleepMs = 4.0;
// What steady_clock and the driver's nanosecond timestamps may disagree by over one sleep:
// they are different clocks read at slightly different moments around the same interval.
constexpr double kClockSlackMs = 1.0;

void sleep_ms(double ms) { std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(ms)); }

// Some GPU work: clears of a target (every device executes them).
void clear_work(const OffscreenTarget& target, int clears) {
  target.bind();
  for (int i = 0; i < clears; ++i) target.clear({0.1f * static_cast<float>(i % 10), 0.0f, 0.0f, 1.0f});
}

using GpuStageTimerTest = GlTest;

TEST_F(GpuStageTimerTest, FinishSync_MoreFramesThanSlots_EveryFrameInOrderWithItsWallTimes) {
  constexpr int kFrames = 7;
  GpuStageTimer timer(StageSync::finish, 3);
  const OffscreenTarget target(256, 256);
  for (int f = 0; f < kFrames; ++f) {
    timer.begin_frame();
    {
      const ScopedStage stage(&timer, RenderStage::depth);
      clear_work(target, 4);
    }
    for (int light = 0; light < 2; ++light) {  // a stage recurring in a frame adds up
      const ScopedStage stage(&timer, RenderStage::lit);
      sleep_ms((f + 1) * kSleepMs / 2.0);
    }
    timer.end_frame();
    glFinish();  // as ShadowMethodRenderer::render_frames ends each frame
  }
  const std::vector<FrameStageTimes> times = timer.collect();
  ASSERT_EQ(times.size(), static_cast<std::size_t>(kFrames));
  for (int f = 0; f < kFrames; ++f) {
    const FrameStageTimes& t = times[f];
    const double slept = (f + 1) * kSleepMs;
    EXPECT_GE(t.wall(RenderStage::lit), slept) << "frame " << f;
    // In order: frame f slept kSleepMs more than frame f - 1, far more than any overhead here.
    if (f > 0) {
      EXPECT_GT(t.wall(RenderStage::lit), times[f - 1].wall(RenderStage::lit)) << "frame " << f;
    }
    EXPECT_GE(t.frame_ms, slept - kClockSlackMs) << "frame " << f << ": the GPU frame spans the sleep";
    for (RenderStage s : {RenderStage::volume, RenderStage::stencil, RenderStage::shadow_map}) {
      EXPECT_EQ(t.gpu(s), 0.0) << render_stage_name(s) << " never ran";
      EXPECT_EQ(t.wall(s), 0.0) << render_stage_name(s) << " never ran";
    }
    for (RenderStage s : kRenderStages) EXPECT_TRUE(std::isfinite(t.gpu(s)) && t.gpu(s) >= 0.0);
  }
  EXPECT_TRUE(timer.collect().empty()) << "frames are returned once";
}

TEST_F(GpuStageTimerTest, NoSync_QueriesOnly_WallTimesStayZero) {
  GpuStageTimer timer(StageSync::none);
  const OffscreenTarget target(256, 256);
  for (int f = 0; f < 5; ++f) {
    timer.begin_frame();
    {
      const ScopedStage stage(&timer, RenderStage::stencil);
      clear_work(target, 8);
    }
    timer.end_frame();
  }
  glFinish();
  const std::vector<FrameStageTimes> times = timer.collect();
  ASSERT_EQ(times.size(), 5u);
  for (const FrameStageTimes& t : times) {
    EXPECT_GE(t.gpu(RenderStage::stencil), 0.0);
    EXPECT_GE(t.frame_ms, 0.0);
    for (RenderStage s : kRenderStages) EXPECT_EQ(t.wall(s), 0.0);
    EXPECT_EQ(t.gpu(RenderStage::lit), 0.0);
  }
}

TEST_F(GpuStageTimerTest, NullTimer_ScopedStageDoesNothing) {
  const OffscreenTarget target(16, 16);
  const ScopedStage stage(nullptr, RenderStage::depth);
  clear_work(target, 1);
  SUCCEED();
}

TEST_F(GpuStageTimerTest, Misuse_Throws) {
  EXPECT_THROW(GpuStageTimer(StageSync::none, 0), std::invalid_argument);
  GpuStageTimer timer(StageSync::none);
  EXPECT_THROW(timer.begin(RenderStage::depth), std::logic_error);  // no frame
  EXPECT_THROW(timer.end(), std::logic_error);
  EXPECT_THROW(timer.end_frame(), std::logic_error);
  timer.begin_frame();
  EXPECT_THROW(timer.begin_frame(), std::logic_error);
  EXPECT_THROW((void)timer.collect(), std::logic_error);  // a frame is open
  timer.begin(RenderStage::depth);
  EXPECT_THROW(timer.begin(RenderStage::lit), std::logic_error);  // intervals cannot nest
  EXPECT_THROW(timer.end_frame(), std::logic_error);             // an interval is open
  timer.end();
  timer.end_frame();
  EXPECT_EQ(timer.collect().size(), 1u);
}

TEST(RenderStageName, EveryStage_HasItsJsonKey) {
  const std::vector<std::string_view> expected{"volume", "depth", "stencil", "lit", "shadow_map"};
  ASSERT_EQ(kRenderStages.size(), expected.size());
  for (std::size_t i = 0; i < kRenderStages.size(); ++i) EXPECT_EQ(render_stage_name(kRenderStages[i]), expected[i]);
}

}  // namespace
}  // namespace shadowcert::gpu
