#pragma once
// GL_KHR_debug output for debug contexts: the driver reports errors with a sentence
// ("glBindBuffer(non-gen name)") instead of a bare code; we keep the ERROR-type ones
// until check_gl_errors() turns them into a GlError.
#include <cstddef>
#include <mutex>
#include <string>
#include <vector>

namespace shadowcert::gpu {

class GlDebugLog {
 public:
  // Keeps the first kMaxKeptMessages messages: a draw loop with one bad call would
  // otherwise grow without bound before the next check point; the rest are only counted.
  static constexpr std::size_t kMaxKeptMessages = 16;

  void record(std::string message);
  // Returns and clears everything recorded; "(+N more)" closes a truncated list.
  [[nodiscard]] std::vector<std::string> take();

 private:
  std::mutex mutex_;  // drivers may call back from their own threads without SYNCHRONOUS
  std::vector<std::string> messages_;
  std::size_t dropped_ = 0;
};

// Installs the callback on the current (debug) context with GL_DEBUG_OUTPUT_SYNCHRONOUS, so
// a message arrives during the call that caused it. `log` must outlive the context.
void install_debug_output(GlDebugLog& log);

// The log the current context reports to, or nullptr when it has no debug output of ours.
[[nodiscard]] GlDebugLog* current_debug_log();

}  // namespace shadowcert::gpu
