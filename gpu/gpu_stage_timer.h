#pragma once
// GPU time per render stage (`render --timing` and bench/render_bench.cpp), from
// GL_TIME_ELAPSED queries (ARB_timer_query, core since GL 3.3), and GPU time per frame from
// two GL_TIMESTAMP counters.
//
//   GpuStageTimer timer(StageSync::none);
//   for (each frame) {
//     timer.begin_frame();
//     { ScopedStage s(&timer, RenderStage::depth); draw... }   // any number of intervals,
//     { ScopedStage s(&timer, RenderStage::lit); draw... }     // one stage may recur (per light)
//     timer.end_frame();
//   }
//   std::vector<FrameStageTimes> times = timer.collect();   // one entry per frame, in order
//
// Results are read without stalling the pipeline: each frame's queries live in one slot of a
// ring of `frames_in_flight` slots and are read only when the slot comes round again (that
// frame is then frames_in_flight - 1 frames old, normally long finished) or by collect().
// GL_TIME_ELAPSED queries cannot nest, so stages are disjoint intervals; what lies between
// them (clears, state changes, readbacks) belongs to the frame only.
//
// Software renderers: Mesa's llvmpipe bins a frame's passes into screen tiles and records a
// query's start and end per tile, overwriting them tile after tile, so its GL_TIME_ELAPSED is
// about one tile's time, not the stage's; and its compute and vertex stages (the volume
// builds) run outside the timed rasteriser threads. StageSync::finish is for such devices:
// every interval is bounded by glFinish and its CPU wall time is recorded too, which there is
// the stage's cost (the GPU is the CPU). On a GPU it would add a stall per stage: use none.
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "gpu/gl_object.h"

namespace shadowcert::gpu {

// The stages a frame is split into. volume: building the shadow volumes on the GPU (compute,
// transform-feedback or tessellation passes); depth: the receivers' depth pre-pass; stencil:
// the volume pass; lit: the lighting pass; shadow_map: the shadow map method's depth pass from
// the light; smoothie_map: the smoothie method's pass of the smoothies from the light
// (gpu/smoothie_map.h). Edge maps (gpu/edge_map.h, gpu/edge_style.h): g_buffer: the G-buffer
// pass; edge_filter: the filter pass(es) writing the edge map; composite: a style's passes (the
// shaded scene, then the edges over it).
enum class RenderStage : std::uint8_t {
  volume, depth, stencil, lit, shadow_map, smoothie_map, g_buffer, edge_filter, composite };
inline constexpr std::size_t kRenderStageCount = 9;
inline constexpr std::array<RenderStage, kRenderStageCount> kRenderStages{
    RenderStage::volume,       RenderStage::depth,    RenderStage::stencil,
    RenderStage::lit,          RenderStage::shadow_map, RenderStage::smoothie_map,
    RenderStage::g_buffer,     RenderStage::edge_filter, RenderStage::composite};

// "volume", "depth", "stencil", "lit", "shadow_map", "smoothie_map", "g_buffer", "edge_filter",
// "composite": the JSON keys and table columns.
[[nodiscard]] std::string_view render_stage_name(RenderStage stage);

// One frame's times in milliseconds, per stage the sum of that stage's intervals (0 for a
// stage the frame did not run): GPU time from the queries and, with StageSync::finish only,
// CPU wall time (0 otherwise); the frame's GPU time from the timestamp at begin_frame to the
// one at end_frame.
struct FrameStageTimes {
  std::array<double, kRenderStageCount> gpu_ms{};
  std::array<double, kRenderStageCount> wall_ms{};
  double frame_ms = 0.0;

  [[nodiscard]] double gpu(RenderStage s) const { return gpu_ms[static_cast<std::size_t>(s)]; }
  [[nodiscard]] double wall(RenderStage s) const { return wall_ms[static_cast<std::size_t>(s)]; }
};

// How stage intervals are bounded (see the top of this file).
enum class StageSync {
  none,    // queries only: the pipeline runs as without a timer
  finish,  // glFinish before and after each interval, whose CPU wall time is recorded too
};

// Enough for a GPU to run two frames behind the CPU without the timer waiting on either.
inline constexpr std::size_t kDefaultFramesInFlight = 3;

class GpuStageTimer {
 public:
  // Needs a current context. Throws std::invalid_argument for frames_in_flight 0 and
  // GlEnvironmentError when the driver's GL_TIME_ELAPSED or GL_TIMESTAMP counter has 0 bits
  // (no timer queries).
  explicit GpuStageTimer(StageSync sync, std::size_t frames_in_flight = kDefaultFramesInFlight);

  // Opens a frame (records its first timestamp). Reusing the ring slot of the oldest frame
  // in flight reads that frame's results first (waiting only if it has not finished).
  // Throws std::logic_error when a frame is already open.
  void begin_frame();
  // Opens / closes one interval of `stage` in the open frame. Throws std::logic_error outside
  // a frame, when an interval is already open (begin) or none is (end).
  void begin(RenderStage stage);
  void end();
  // Closes the frame (records its last timestamp). Throws std::logic_error when no frame is
  // open or an interval still is.
  void end_frame();

  // Waits for the frames still in flight and returns every frame not yet returned, in the
  // order they were drawn. Throws std::logic_error while a frame is open.
  [[nodiscard]] std::vector<FrameStageTimes> collect();

  [[nodiscard]] bool frame_open() const { return frame_open_; }
  [[nodiscard]] StageSync sync() const { return sync_; }

 private:
  struct Interval {
    RenderStage stage = RenderStage::volume;
    Query query;
    double wall_ms = 0.0;  // StageSync::finish only
  };
  struct Slot {
    std::vector<Interval> intervals;  // a pool: the first `used` belong to the slot's frame
    std::size_t used = 0;
    Query frame_begin, frame_end;
    bool pending = false;  // holds a frame whose results were not read yet
  };
  void read_results(Slot& slot);

  StageSync sync_;
  std::vector<Slot> slots_;
  std::size_t current_ = 0;  // the slot of the open (or next) frame
  bool frame_open_ = false;
  bool stage_open_ = false;
  std::chrono::steady_clock::time_point stage_start_;  // StageSync::finish only
  std::vector<FrameStageTimes> finished_;
};

// Begins `stage` on construction and ends it on destruction; does nothing for a null timer,
// so that drawing code times itself only when asked.
class ScopedStage {
 public:
  ScopedStage(GpuStageTimer* timer, RenderStage stage) : timer_(timer) {
    if (timer_ != nullptr) timer_->begin(stage);
  }
  ~ScopedStage() {
    if (timer_ != nullptr) timer_->end();
  }
  ScopedStage(const ScopedStage&) = delete;
  ScopedStage& operator=(const ScopedStage&) = delete;

 private:
  GpuStageTimer* timer_;
};

}  // namespace shadowcert::gpu
