#include "gpu/gl_error.h"

#include <epoxy/gl.h>

#include <cstdio>

#include "gpu/detail/gl_debug_output.h"

namespace shadowcert::gpu {

std::string gl_error_name(unsigned int code) {
  switch (code) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    default: {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "GL error 0x%04X", code);
      return buffer;
    }
  }
}

void check_gl_errors(const char* where) {
  // glGetError returns one flag per call; a bounded loop, since a lost context may report
  // GL_CONTEXT_LOST forever.
  constexpr int kMaxErrorFlags = 16;
  std::string codes;
  for (int i = 0; i < kMaxErrorFlags; ++i) {
    const GLenum code = glGetError();
    if (code == GL_NO_ERROR) break;
    if (!codes.empty()) codes += ", ";
    codes += gl_error_name(code);
    if (code == GL_CONTEXT_LOST) break;
  }
  std::string driver;
  if (GlDebugLog* log = current_debug_log()) {
    for (const std::string& m : log->take()) {
      if (!driver.empty()) driver += " | ";
      driver += m;
    }
  }
  if (codes.empty() && driver.empty()) return;
  std::string message = std::string(where) + ": " + (codes.empty() ? "GL error" : codes);
  if (!driver.empty()) message += "; driver: " + driver;
  throw GlError(message);
}

}  // namespace shadowcert::gpu
