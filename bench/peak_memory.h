#pragma once
// The resident set's high-water mark of one stage of a benchmark (Linux): reset_peak_rss()
// before it, peak_rss_mib() after it, minus the resident set before it, is what the stage itself
// added at its peak, not what ran earlier in the process (getrusage's ru_maxrss never resets).
#include <malloc.h>

#include <fstream>
#include <string>

namespace shadowcert::bench {

// Resets the peak (VmHWM) to the current resident set (/proc/self/clear_refs "5", Linux >= 4.0),
// after handing the allocator's free pages back (malloc_trim), so that a stage's peak counts the
// pages it touches, not only those beyond what an earlier stage left cached in the heap.
inline void reset_peak_rss() {
  malloc_trim(0);
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
}

// A line of /proc/self/status in MiB ("VmHWM:" the peak since the last reset, "VmRSS:" now).
inline double rss_line_mib(const std::string& key) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(key, 0) == 0) return std::stod(line.substr(key.size())) / 1024.0;  // kB
  return 0.0;
}

}  // namespace shadowcert::bench
