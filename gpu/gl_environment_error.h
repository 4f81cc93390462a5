#pragma once
// The machine cannot give us OpenGL 4.5 core headlessly: no EGL, no usable device, no
// context of the right version. cli/ maps it to the environment-error exit code (2);
// tests turn it into GTEST_SKIP only when no EGL device exists at all.
#include <stdexcept>
#include <string>
#include <utility>

namespace shadowcert::gpu {

class GlEnvironmentError : public std::runtime_error {
 public:
  // `egl_error` is the EGL error code's name ("EGL_BAD_MATCH"), empty when the failure is
  // not an EGL call (e.g. GL_VERSION too low); what() = "message (EGL_BAD_MATCH)".
  GlEnvironmentError(const std::string& message, std::string egl_error = {})
      : std::runtime_error(egl_error.empty() ? message : message + " (" + egl_error + ")"),
        egl_error_(std::move(egl_error)) {}

  [[nodiscard]] const std::string& egl_error() const { return egl_error_; }

 private:
  std::string egl_error_;
};

// The subclass thrown when EGL works but enumerates nothing to render with: the one case
// where the GL tests skip rather than fail.
class NoGlDeviceError : public GlEnvironmentError {
 public:
  using GlEnvironmentError::GlEnvironmentError;
};

}  // namespace shadowcert::gpu
