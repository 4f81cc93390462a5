// gpu/gpu_stage_timer.h: one result per frame, in frame order, through a ring smaller than the
// number of frames; stages summed over their intervals and 0 where not run; wall times of
// StageSync::finish that cover what the interval did; misuse rejected. Timing checks are lower
// bounds only (sleeps), so a loaded machine cannot fail them.
#include "gpu/gpu_stage_timer.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/gl_test_support.h"
#include "gpu/offscreen_target.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;

// Every timed interval of the first test sleeps at least this long: its wall time is then
// surely above 0, whatever the machine's load (which can only lengthen it).
constexpr double kSleepMs = 2.0;
// What steady_clock and the driver's nanosecond timestamps may disagree by over one frame:
// they are different clocks read at slightly different moments around the same interval.
constexpr double kClockSlackMs = 1.0;

void sleep_ms(double ms) { std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(ms)); }

// Some GPU work: clears of a target (every device executes them).
void clear_work(const OffscreenTarget& target, int clears) {
  target.bind();
  for (int i = 0; i < clears; ++i) target.clear({0.1f * static_cast<float>(i % 10), 0.0f, 0.0f, 1.0f});
}

// Frame f runs depth if bit 0 of f is set, stencil if bit 1, shadow_map if bit 2, and lit
// always (as two intervals, as with two lights): 7 frames have 7 different stage sets, so
// which frame a result belongs to shows in which of its stages are 0.
bool runs(int frame, RenderStage stage) {
  switch (stage) {
    case RenderStage::depth: return (frame & 1) != 0;
    case RenderStage::stencil: return (frame & 2) != 0;
    case RenderStage::shadow_map: return (frame & 4) != 0;
    case RenderStage::lit: return true;
    case RenderStage::volume: return false;
    case RenderStage::smoothie_map: return false;
    case RenderStage::g_buffer: return false;
    case RenderStage::edge_filter: return false;
    case RenderStage::composite: return false;
  }
  return false;
}

using GpuStageTimerTest = GlTest;

TEST_F(GpuStageTimerTest, FinishSync_MoreFramesThanSlots_EveryFrameInOrderWithItsWallTimes) {
  constexpr int kFrames = 7;
  GpuStageTimer timer(StageSync::finish, 3);
  const OffscreenTarget target(256, 256);
  std::vector<double> slept(kFrames, 0.0);
  for (int f = 0; f < kFrames; ++f) {
    timer.begin_frame();
    for (RenderStage s : {RenderStage::depth, RenderStage::stencil, RenderStage::shadow_map}) {
      if (!runs(f, s)) continue;
      const ScopedStage stage(&timer, s);
      clear_work(target, 4);
      sleep_ms(kSleepMs);
      slept[f] += kSleepMs;
    }
    for (int light = 0; light < 2; ++light) {  // a stage recurring in a frame adds up
      const ScopedStage stage(&timer, RenderStage::lit);
      sleep_ms(kSleepMs);
      slept[f] += kSleepMs;
    }
    timer.end_frame();
    glFinish();  // as ShadowMethodRenderer::render_frames ends each frame
  }
  const std::vector<FrameStageTimes> times = timer.collect();
  ASSERT_EQ(times.size(), static_cast<std::size_t>(kFrames));
  for (int f = 0; f < kFrames; ++f) {
    const FrameStageTimes& t = times[f];
    for (RenderStage s : kRenderStages) {
      SCOPED_TRACE("frame " + std::to_string(f) + ", " + std::string(render_stage_name(s)));
      EXPECT_TRUE(std::isfinite(t.gpu(s)) && t.gpu(s) >= 0.0);
      if (!runs(f, s)) {
        EXPECT_EQ(t.gpu(s), 0.0) << "never ran in this frame";
        EXPECT_EQ(t.wall(s), 0.0) << "never ran in this frame";
      } else {
        EXPECT_GE(t.wall(s), s == RenderStage::lit ? 2 * kSleepMs : kSleepMs);
      }
    }
    EXPECT_GE(t.frame_ms, slept[f] - kClockSlackMs) << "frame " << f << ": the GPU frame spans its sleeps";
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

}  // namespace
}  // namespace shadowcert::gpu
