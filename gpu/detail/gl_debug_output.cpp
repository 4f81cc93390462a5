#include "gpu/detail/gl_debug_output.h"

#include <epoxy/gl.h>

#include <string_view>
#include <utility>

namespace shadowcert::gpu {

void GlDebugLog::record(std::string message) {
  std::lock_guard lock(mutex_);
  if (messages_.size() < kMaxKeptMessages) {
    messages_.push_back(std::move(message));
  } else {
    ++dropped_;
  }
}

std::vector<std::string> GlDebugLog::take() {
  std::lock_guard lock(mutex_);
  std::vector<std::string> out = std::move(messages_);
  messages_.clear();
  if (dropped_ > 0) out.push_back("(+" + std::to_string(dropped_) + " more)");
  dropped_ = 0;
  return out;
}

namespace {

// C callback: must not throw (the driver's frames are below us), so it only records.
void GLAPIENTRY on_debug_message(GLenum /*source*/, GLenum type, GLuint /*id*/, GLenum /*severity*/,
                                 GLsizei length, const GLchar* message, const void* user) {
  if (type != GL_DEBUG_TYPE_ERROR || user == nullptr || message == nullptr) return;
  auto* log = static_cast<GlDebugLog*>(const_cast<void*>(user));
  try {
    log->record(length >= 0 ? std::string(message, static_cast<std::size_t>(length)) : std::string(message));
  } catch (...) {
    // Out of memory while recording: the glGetError code still reaches check_gl_errors.
  }
}

}  // namespace

void install_debug_output(GlDebugLog& log) {
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(on_debug_message, &log);
  // Only errors interest us; leaving the rest on would make drivers format every
  // performance note for nothing.
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_FALSE);
  glDebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

GlDebugLog* current_debug_log() {
  // Asking GL for the installed callback (rather than a global) keeps several contexts
  // apart: each reports to the log its own EglContext owns.
  void* function = nullptr;
  glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &function);
  if (function != reinterpret_cast<void*>(&on_debug_message)) return nullptr;
  void* user = nullptr;
  glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &user);
  return static_cast<GlDebugLog*>(user);
}

}  // namespace shadowcert::gpu
