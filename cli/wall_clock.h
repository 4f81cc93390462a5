#pragma once
// The wall clock of the commands' "seconds" figures (build, upload, first frame, the whole
// command): a steady clock, so a change of the system time cannot make a figure negative.
#include <chrono>

namespace shadowcert::cli {

using Clock = std::chrono::steady_clock;

// Seconds from `start` to now.
[[nodiscard]] inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace shadowcert::cli
