#include "gpu/gpu_stage_timer.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "gpu/gl_environment_error.h"
#include "gpu/gl_error.h"

namespace shadowcert::gpu {
namespace {

constexpr double kMillisecondsPerNanosecond = 1.0e-6;  // query results are in nanoseconds

GLint counter_bits(GLenum target) {
  GLint bits = 0;
  glGetQueryiv(target, GL_QUERY_COUNTER_BITS, &bits);
  return bits;
}

GLuint64 result(const Query& query) {
  GLuint64 value = 0;
  glGetQueryObjectui64v(query.name(), GL_QUERY_RESULT, &value);  // waits if not yet available
  return value;
}

}  // namespace

std::string_view render_stage_name(RenderStage stage) {
  switch (stage) {
    case RenderStage::volume: return "volume";
    case RenderStage::depth: return "depth";
    case RenderStage::stencil: return "stencil";
    case RenderStage::lit: return "lit";
    case RenderStage::shadow_map: return "shadow_map";
    case RenderStage::smoothie_map: return "smoothie_map";
    case RenderStage::g_buffer: return "g_buffer";
    case RenderStage::edge_filter: return "edge_filter";
    case RenderStage::composite: return "composite";
  }
  throw std::invalid_argument("render_stage_name: unknown stage " + std::to_string(static_cast<int>(stage)));
}

GpuStageTimer::GpuStageTimer(StageSync sync, std::size_t frames_in_flight) : sync_(sync) {
  if (frames_in_flight == 0) throw std::invalid_argument("GpuStageTimer: frames_in_flight must be at least 1");
  for (GLenum target : {GLenum{GL_TIME_ELAPSED}, GLenum{GL_TIMESTAMP}}) {
    if (counter_bits(target) == 0)
      throw GlEnvironmentError(std::string("GpuStageTimer: the driver's ") +
                               (target == GL_TIME_ELAPSED ? "GL_TIME_ELAPSED" : "GL_TIMESTAMP") +
                               " counter has 0 bits (no timer queries)");
  }
  slots_.resize(frames_in_flight);
  for (Slot& slot : slots_) {
    slot.frame_begin = Query::create(GL_TIMESTAMP);
    slot.frame_end = Query::create(GL_TIMESTAMP);
  }
  check_gl_errors("GpuStageTimer");
}

void GpuStageTimer::begin_frame() {
  if (frame_open_) throw std::logic_error("GpuStageTimer::begin_frame: a frame is already open");
  Slot& slot = slots_[current_];
  if (slot.pending) read_results(slot);
  slot.used = 0;
  glQueryCounter(slot.frame_begin.name(), GL_TIMESTAMP);
  frame_open_ = true;
}

void GpuStageTimer::begin(RenderStage stage) {
  if (!frame_open_) throw std::logic_error("GpuStageTimer::begin: no frame is open");
  if (stage_open_) throw std::logic_error("GpuStageTimer::begin: an interval is already open (they cannot nest)");
  Slot& slot = slots_[current_];
  if (slot.used == slot.intervals.size()) slot.intervals.push_back({stage, Query::create(GL_TIME_ELAPSED)});
  Interval& interval = slot.intervals[slot.used++];
  interval.stage = stage;
  interval.wall_ms = 0.0;
  if (sync_ == StageSync::finish) {
    glFinish();  // what was queued before (a clear, the previous stage) is not this stage's
    stage_start_ = std::chrono::steady_clock::now();
  }
  glBeginQuery(GL_TIME_ELAPSED, interval.query.name());
  stage_open_ = true;
}

void GpuStageTimer::end() {
  if (!stage_open_) throw std::logic_error("GpuStageTimer::end: no interval is open");
  glEndQuery(GL_TIME_ELAPSED);
  if (sync_ == StageSync::finish) {
    glFinish();
    slots_[current_].intervals[slots_[current_].used - 1].wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - stage_start_).count();
  }
  stage_open_ = false;
}

void GpuStageTimer::end_frame() {
  if (!frame_open_) throw std::logic_error("GpuStageTimer::end_frame: no frame is open");
  if (stage_open_) throw std::logic_error("GpuStageTimer::end_frame: an interval is still open");
  Slot& slot = slots_[current_];
  glQueryCounter(slot.frame_end.name(), GL_TIMESTAMP);
  slot.pending = true;
  current_ = (current_ + 1) % slots_.size();
  frame_open_ = false;
  check_gl_errors("GpuStageTimer::end_frame");
}

std::vector<FrameStageTimes> GpuStageTimer::collect() {
  if (frame_open_) throw std::logic_error("GpuStageTimer::collect: a frame is still open");
  // current_ is the slot the next frame takes, i.e. the oldest frame in flight.
  for (std::size_t k = 0; k < slots_.size(); ++k) {
    Slot& slot = slots_[(current_ + k) % slots_.size()];
    if (slot.pending) read_results(slot);
  }
  return std::exchange(finished_, {});
}

void GpuStageTimer::read_results(Slot& slot) {
  FrameStageTimes times;
  for (std::size_t i = 0; i < slot.used; ++i) {
    const auto stage = static_cast<std::size_t>(slot.intervals[i].stage);
    times.gpu_ms[stage] += static_cast<double>(result(slot.intervals[i].query)) * kMillisecondsPerNanosecond;
    times.wall_ms[stage] += slot.intervals[i].wall_ms;
  }
  const GLuint64 first = result(slot.frame_begin);
  const GLuint64 last = result(slot.frame_end);
  // Timestamps are monotonic on a conforming driver; a reversed pair reads as 0, not as ~2^64.
  times.frame_ms = last > first ? static_cast<double>(last - first) * kMillisecondsPerNanosecond : 0.0;
  check_gl_errors("GpuStageTimer: reading query results");
  slot.pending = false;
  finished_.push_back(times);
}

}  // namespace shadowcert::gpu
