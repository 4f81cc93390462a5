#include "gpu/egl_context.h"

// epoxy first: it defines the khronos types itself and guards KHR/khrplatform.h out, which
// EGL's headers would otherwise declare a second time.
#include <epoxy/gl.h>
// No X11 headers through eglplatform.h: their macros (None, Bool, Status) break C++ code.
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <map>
#include <mutex>
#include <sstream>
#include <string_view>
#include <utility>

#include "gpu/detail/gl_debug_output.h"
#include "gpu/gl_environment_error.h"

namespace shadowcert::gpu {
namespace {

// What the methods need: DSA (4.5), KHR_debug (4.3), compute and tessellation shaders.
constexpr int kRequiredGlMajor = 4;
constexpr int kRequiredGlMinor = 5;

std::string egl_error_name(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    case EGL_BAD_DEVICE_EXT: return "EGL_BAD_DEVICE_EXT";
    default: {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "EGL error 0x%04X", static_cast<unsigned>(code));
      return buffer;
    }
  }
}

// The pending EGL error's name, "" when EGL reports none (the message then says enough).
std::string last_egl_error() {
  const EGLint code = eglGetError();
  return code == EGL_SUCCESS ? std::string() : egl_error_name(code);
}

bool has_extension(std::string_view list, std::string_view name) {
  // Whole tokens only: "EGL_EXT_device_base" must not match "EGL_EXT_device_base_foo".
  std::size_t at = 0;
  while ((at = list.find(name, at)) != std::string_view::npos) {
    const bool starts = at == 0 || list[at - 1] == ' ';
    const std::size_t end = at + name.size();
    if (starts && (end == list.size() || list[end] == ' ')) return true;
    at = end;
  }
  return false;
}

std::string client_extensions() {
  const char* s = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (s == nullptr) {
    eglGetError();  // EGL 1.4 without EGL_EXT_client_extensions: clear EGL_BAD_DISPLAY
    return {};
  }
  return s;
}

struct EglEntryPoints {
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;
};

EglEntryPoints entry_points() {
  EglEntryPoints e;
  e.query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  e.query_device_string =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  e.get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  return e;
}

std::vector<EGLDeviceEXT> query_devices(const std::string& client, const EglEntryPoints& e) {
  if (!has_extension(client, "EGL_EXT_device_enumeration") && !has_extension(client, "EGL_EXT_device_base")) {
    return {};
  }
  if (e.query_devices == nullptr) return {};
  EGLint count = 0;
  if (!e.query_devices(0, nullptr, &count) || count <= 0) return {};
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (!e.query_devices(count, devices.data(), &count)) {
    throw GlEnvironmentError("eglQueryDevicesEXT failed", last_egl_error());
  }
  devices.resize(static_cast<std::size_t>(count));
  return devices;
}

// EGL displays are per device and not reference counted: eglTerminate would pull the
// display from under every other EglContext on it. Count the users ourselves.
std::mutex display_mutex;
std::map<EGLDisplay, int> display_users;

void acquire_display(EGLDisplay display, const std::string& description) {
  std::lock_guard lock(display_mutex);
  int& users = display_users[display];
  if (users == 0) {
    EGLint major = 0;
    EGLint minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
      display_users.erase(display);
      throw NoGlDeviceError(description + ": eglInitialize failed", last_egl_error());
    }
  }
  ++users;
}

void release_display(EGLDisplay display) noexcept {
  std::lock_guard lock(display_mutex);
  auto it = display_users.find(display);
  if (it == display_users.end()) return;
  if (--it->second == 0) {
    eglTerminate(display);
    display_users.erase(it);
  }
}

bool software_renderer(std::string_view renderer) {
  return renderer.find("llvmpipe") != std::string_view::npos || renderer.find("softpipe") != std::string_view::npos ||
         renderer.find("SWR") != std::string_view::npos;
}

}  // namespace

std::string EglDeviceInfo::describe() const {
  std::ostringstream s;
  s << "EGL device " << index;
  if (nvidia) s << " [NVIDIA]";
  if (software) s << " [software]";
  if (!vendor.empty() || !renderer.empty()) s << " " << vendor << (vendor.empty() ? "" : " ") << renderer;
  if (!drm_device_file.empty()) s << " " << drm_device_file;
  s << " (" << extensions << ")";
  return s.str();
}

std::vector<EglDeviceInfo> list_egl_devices() {
  const std::string client = client_extensions();
  const EglEntryPoints e = entry_points();
  const std::vector<EGLDeviceEXT> devices = query_devices(client, e);
  std::vector<EglDeviceInfo> out;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    EglDeviceInfo info;
    info.index = static_cast<int>(i);
    auto query = [&](EGLint name) -> std::string {
      const char* s = e.query_device_string != nullptr ? e.query_device_string(devices[i], name) : nullptr;
      if (s == nullptr) {
        eglGetError();  // an unsupported name is not a failure of the listing
        return {};
      }
      return s;
    };
    info.extensions = query(EGL_EXTENSIONS);
    if (has_extension(info.extensions, "EGL_EXT_device_drm")) info.drm_device_file = query(EGL_DRM_DEVICE_FILE_EXT);
    if (has_extension(info.extensions, "EGL_EXT_device_query_name")) {
      info.renderer = query(EGL_RENDERER_EXT);
      info.vendor = query(EGL_VENDOR);
    }
    info.software = has_extension(info.extensions, "EGL_MESA_device_software");
    info.nvidia = has_extension(info.extensions, "EGL_NV_device_cuda");
    out.push_back(std::move(info));
  }
  return out;
}

namespace {

struct CreatedContext {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

// Initialises `display`, creates a 4.5 core context without surface and makes it current.
// On failure nothing is left behind (the display user is released).
CreatedContext create_on(EGLDisplay display, const std::string& description, bool debug) {
  if (display == EGL_NO_DISPLAY) throw NoGlDeviceError(description + ": no EGL display", last_egl_error());
  acquire_display(display, description);
  CreatedContext created{display, EGL_NO_CONTEXT};
  try {
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    const std::string extensions = ext != nullptr ? ext : "";
    if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
      throw GlEnvironmentError(description + ": EGL_KHR_surfaceless_context is missing");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) throw GlEnvironmentError(description + ": eglBindAPI(OpenGL) failed", last_egl_error());

    // A config is only needed by implementations without EGL_KHR_no_config_context; any
    // OpenGL-renderable one does, since we never create a surface.
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
      const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
      EGLint count = 0;
      if (!eglChooseConfig(display, config_attributes, &config, 1, &count) || count < 1) {
        throw GlEnvironmentError(description + ": no EGL config renders OpenGL", last_egl_error());
      }
    }
    // EGL_KHR_create_context's flag works on EGL 1.4 and 1.5 alike.
    const EGLint context_attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION_KHR, kRequiredGlMajor,
        EGL_CONTEXT_MINOR_VERSION_KHR, kRequiredGlMinor,
        EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR,
        EGL_CONTEXT_FLAGS_KHR, debug ? EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR : 0,
        EGL_NONE};
    created.context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
    if (created.context == EGL_NO_CONTEXT) {
      throw GlEnvironmentError(description + ": no OpenGL 4.5 core context", last_egl_error());
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, created.context)) {
      throw GlEnvironmentError(description + ": eglMakeCurrent without surface failed", last_egl_error());
    }
  } catch (...) {
    if (created.context != EGL_NO_CONTEXT) eglDestroyContext(display, created.context);
    release_display(display);
    throw;
  }
  return created;
}

}  // namespace

EglContext::EglContext(const EglContextOptions& options) {
  const std::string client = client_extensions();
  if (client.empty()) throw NoGlDeviceError("EGL has no client extensions (no EGL implementation or vendor library?)");
  const EglEntryPoints e = entry_points();
  const bool platform_device = has_extension(client, "EGL_EXT_platform_device") && e.get_platform_display != nullptr;
  const std::vector<EGLDeviceEXT> devices = platform_device ? query_devices(client, e) : std::vector<EGLDeviceEXT>{};
  const std::vector<EglDeviceInfo> infos = platform_device ? list_egl_devices() : std::vector<EglDeviceInfo>{};

  auto on_device = [&](std::size_t i) {
    return create_on(e.get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), infos[i].describe(),
                     options.debug);
  };

  CreatedContext created;
  if (options.device) {
    const int n = *options.device;
    if (!platform_device) throw GlEnvironmentError("--device needs EGL_EXT_platform_device, which EGL lacks");
    if (n < 0 || static_cast<std::size_t>(n) >= devices.size()) {
      throw GlEnvironmentError("EGL device " + std::to_string(n) + " does not exist (" +
                               std::to_string(devices.size()) + " devices)");
    }
    created = on_device(static_cast<std::size_t>(n));
    device_ = infos[static_cast<std::size_t>(n)].describe();
  } else {
    // Hardware first, NVIDIA's before others: the shadow-volume timings are about GPUs.
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < infos.size(); ++i) if (infos[i].nvidia) order.push_back(i);
    for (std::size_t i = 0; i < infos.size(); ++i) if (!infos[i].nvidia && !infos[i].software) order.push_back(i);
    for (std::size_t i : order) {
      try {
        created = on_device(i);
        device_ = infos[i].describe();
        break;
      } catch (const GlEnvironmentError& error) {
        fallback_reason_ += (fallback_reason_.empty() ? "" : "; ") + std::string(error.what());
      }
    }
    if (created.context == EGL_NO_CONTEXT) {
      if (has_extension(client, "EGL_MESA_platform_surfaceless") && e.get_platform_display != nullptr) {
        const std::string description = "Mesa surfaceless platform";
        created = create_on(e.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                            description, options.debug);
        device_ = description;
      } else {
        for (std::size_t i = 0; i < infos.size() && created.context == EGL_NO_CONTEXT; ++i) {
          if (infos[i].software) {
            created = on_device(i);
            device_ = infos[i].describe();
          }
        }
      }
    }
    if (created.context == EGL_NO_CONTEXT) {
      throw NoGlDeviceError("no EGL device and no Mesa surfaceless platform" +
                            (fallback_reason_.empty() ? std::string() : ": " + fallback_reason_));
    }
  }
  display_ = created.display;
  context_ = created.context;

  // From here the context is ours: the destructor cleans up if a check below throws.
  try {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    renderer_ = renderer != nullptr ? renderer : "";
    version_ = version != nullptr ? version : "";
    software_ = software_renderer(renderer_);
    GLint major = 0;
    GLint minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < kRequiredGlMajor || (major == kRequiredGlMajor && minor < kRequiredGlMinor)) {
      throw GlEnvironmentError(device_ + ": OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                               " (" + renderer_ + ", " + version_ + "), 4.5 core needed");
    }
    if (options.debug) {
      debug_log_ = std::make_unique<GlDebugLog>();
      install_debug_output(*debug_log_);
    }
  } catch (...) {
    release();
    throw;
  }
}

EglContext::~EglContext() { release(); }

EglContext::EglContext(EglContext&& other) noexcept
    : display_(std::exchange(other.display_, nullptr)),
      context_(std::exchange(other.context_, nullptr)),
      debug_log_(std::move(other.debug_log_)),
      device_(std::move(other.device_)),
      renderer_(std::move(other.renderer_)),
      version_(std::move(other.version_)),
      fallback_reason_(std::move(other.fallback_reason_)),
      software_(other.software_) {}

EglContext& EglContext::operator=(EglContext&& other) noexcept {
  if (this != &other) {
    release();
    display_ = std::exchange(other.display_, nullptr);
    context_ = std::exchange(other.context_, nullptr);
    debug_log_ = std::move(other.debug_log_);
    device_ = std::move(other.device_);
    renderer_ = std::move(other.renderer_);
    version_ = std::move(other.version_);
    fallback_reason_ = std::move(other.fallback_reason_);
    software_ = other.software_;
  }
  return *this;
}

void EglContext::make_current() const {
  if (context_ == nullptr) throw std::logic_error("EglContext::make_current: moved-from context");
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, static_cast<EGLContext>(context_))) {
    throw GlEnvironmentError(device_ + ": eglMakeCurrent failed", last_egl_error());
  }
}

void EglContext::release() noexcept {
  if (context_ == nullptr) return;
  auto display = static_cast<EGLDisplay>(display_);
  auto context = static_cast<EGLContext>(context_);
  if (eglGetCurrentContext() == context) eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, context);
  release_display(display);
  debug_log_.reset();  // after the context: no callback can reach it any more
  display_ = nullptr;
  context_ = nullptr;
}

EglContext open_gl_context(std::string_view command, std::optional<int> device) {
  try {
    return EglContext(EglContextOptions{device, kGlDebugByDefault});
  } catch (const GlEnvironmentError& e) {
    throw GlEnvironmentError(std::string(command) +
                             " needs OpenGL 4.5 core through headless EGL (a GPU driver or Mesa's llvmpipe: "
                             "packages libegl-mesa0 libgl1-mesa-dri); " + std::string(e.what()));
  }
}

}  // namespace shadowcert::gpu
