#pragma once
// A headless OpenGL 4.5 core context through EGL: no window, no X, no surface.
//
// Device choice (docs/gpu.md): with EGL_EXT_device_enumeration + EGL_EXT_platform_device,
// a hardware device is preferred (NVIDIA's, recognised by EGL_NV_device_cuda, first);
// otherwise Mesa's surfaceless platform, which gives llvmpipe. An explicit device index
// (`--device N` of render, diff and fuzz --gl; list_egl_devices()) bypasses the choice.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shadowcert::gpu {

class GlDebugLog;

struct EglDeviceInfo {
  int index = 0;               // the position in eglQueryDevicesEXT's list: --device N
  std::string extensions;      // the device's EGL extension string
  std::string drm_device_file; // "/dev/dri/card0" where EGL_EXT_device_drm says so, else ""
  std::string renderer;        // EGL_EXT_device_query_name's renderer/vendor, else ""
  std::string vendor;
  bool software = false;       // EGL_MESA_device_software: llvmpipe/softpipe
  bool nvidia = false;         // EGL_NV_device_cuda

  [[nodiscard]] std::string describe() const;  // one line for logs (egl_context_test prints one per device)
};

// Every EGL device, in EGL's order; empty when the client extensions are missing.
// Throws GlEnvironmentError only when libEGL itself is unusable.
[[nodiscard]] std::vector<EglDeviceInfo> list_egl_devices();

// Debug output is on by default in Debug builds (every GL error becomes an exception at
// the next check_gl_errors) and opt-in in Release, where it costs a little per call.
#ifdef NDEBUG
inline constexpr bool kGlDebugByDefault = false;
#else
inline constexpr bool kGlDebugByDefault = true;
#endif

struct EglContextOptions {
  std::optional<int> device;      // an index of list_egl_devices(); nullopt = automatic choice
  bool debug = kGlDebugByDefault; // EGL_CONTEXT_OPENGL_DEBUG + our GL_KHR_debug callback
};

// Move-only RAII: the constructor creates the context and makes it current on the calling
// thread; the destructor releases it (and terminates the EGL display when no other
// EglContext uses it). GL objects (gpu/gl_object.h) must die while their context is current.
class EglContext {
 public:
  // Throws GlEnvironmentError (NoGlDeviceError when there is nothing to render with)
  // carrying the EGL error's name and the driver's strings.
  explicit EglContext(const EglContextOptions& options = {});
  ~EglContext();
  EglContext(EglContext&& other) noexcept;
  EglContext& operator=(EglContext&& other) noexcept;
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  void make_current() const;  // after another context was made current on this thread

  [[nodiscard]] const std::string& device() const { return device_; }   // how EGL was reached
  [[nodiscard]] const std::string& renderer() const { return renderer_; } // GL_RENDERER
  [[nodiscard]] const std::string& version() const { return version_; }   // GL_VERSION
  [[nodiscard]] bool software() const { return software_; }  // llvmpipe/softpipe renderer
  [[nodiscard]] bool debug() const { return debug_log_ != nullptr; }
  // Why the automatic choice skipped hardware devices (empty when it did not).
  [[nodiscard]] const std::string& fallback_reason() const { return fallback_reason_; }

 private:
  void release() noexcept;

  void* display_ = nullptr;  // EGLDisplay, EGLContext: kept void* so EGL headers stay in the .cpp
  void* context_ = nullptr;
  std::unique_ptr<GlDebugLog> debug_log_;  // heap: its address is the callback's user pointer
  std::string device_;
  std::string renderer_;
  std::string version_;
  std::string fallback_reason_;
  bool software_ = false;
};

// The context a command draws with (device: as EglContextOptions::device), current on the
// calling thread. Throws GlEnvironmentError whose message says that `command` needs OpenGL 4.5
// core through headless EGL, which packages give it, and the driver's own message.
[[nodiscard]] EglContext open_gl_context(std::string_view command, std::optional<int> device);

}  // namespace shadowcert::gpu
