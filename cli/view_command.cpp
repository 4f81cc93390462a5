#include "cli/view_command.h"

#define GLFW_INCLUDE_NONE  // GL itself is gpu/'s (gpu/viewer_frame.h): cli/ sees GLFW only
#include <GLFW/glfw3.h>
#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cli/exit_code.h"
#include "cli/option_values.h"
#include "core/input_error.h"
#include "core/vector3.h"
#include "gpu/gl_environment_error.h"
#include "gpu/host_shadow_volumes.h"
#include "gpu/offscreen_target.h"
#include "gpu/png_image.h"
#include "gpu/shadow_method_renderer.h"
#include "gpu/viewer_frame.h"
#include "io/output_file.h"
#include "io/scene_input.h"
#include "pipeline/drawn_method_scene.h"
#include "pipeline/method_registry.h"
#include "pipeline/scene_comparison.h"

namespace shadowcert::cli {
namespace {

struct ViewOptions {
  std::string input;
  std::string method = "cs";
  std::string stencil = "zfail";
  std::string size;
  std::string screenshot;
  std::size_t frames = 0;  // 0: until the window is closed
  bool overlay = false;
};

// Orbit and drag speeds: radians per pixel dragged, zoom factor per scroll step, and the
// light's move per pixel as a share of its distance to the camera target.
constexpr double kOrbitRadiansPerPixel = 0.005;
constexpr double kZoomPerStep = 0.9;
constexpr double kLightSharePerPixel = 0.003;
// Overlay colours (RGBA): hard errors red, ambiguous pixels grey, half transparent.
constexpr std::array<std::uint8_t, 4> kHardErrorColour{255, 0, 0, 200};
constexpr std::array<std::uint8_t, 4> kAmbiguousColour{128, 128, 128, 160};

// The volume methods, in the table's order: what `view` can draw (and M cycles through).
std::vector<gpu::ShadowMethod> view_methods() {
  std::vector<gpu::ShadowMethod> out;
  for (const gpu::ShadowMethodTraits& t : gpu::kShadowMethodTable)
    if (gpu::draws_volume(t.method)) out.push_back(t.method);
  return out;
}

Vec3 rotate(const Vec3& v, const Vec3& axis, double angle) {  // Rodrigues, `axis` of unit length
  const double c = std::cos(angle), s = std::sin(angle), d = dot(axis, v);
  const Vec3 x = cross(axis, v);
  return {v[0] * c + x[0] * s + axis[0] * d * (1 - c), v[1] * c + x[1] * s + axis[1] * d * (1 - c),
          v[2] * c + x[2] * s + axis[2] * d * (1 - c)};
}

Vec3 unit(const Vec3& v) {
  const double n = std::sqrt(dot(v, v));
  return {v[0] / n, v[1] / n, v[2] / n};
}

// The exact image's verdicts for light 0 of the frame `d` draws, as an overlay (needs the GL
// context: the frame is rendered offscreen, which equals the window's by construction).
gpu::RgbaImage verdict_overlay(const DrawnMethodScene& d, const ExactImage& exact, PixelComparison* counts) {
  gpu::ShadowMethodOptions o;
  o.stencil = d.light_stencil.front();
  gpu::ShadowMethodRenderer renderer(d.method, light_scene(d.inputs, d.parts, d.scene.lights, 0), o);
  const gpu::OffscreenTarget target(d.scene.camera.width, d.scene.camera.height);
  const LightRun run = compare_light(renderer, exact, 0, target, d.scene.camera);
  *counts = run.comparison;
  gpu::RgbaImage overlay(d.scene.camera.width, d.scene.camera.height);
  for (std::size_t p = 0; p < run.comparison.verdicts.size(); ++p) {
    const PixelVerdict v = run.comparison.verdicts[p];
    if (v == PixelVerdict::agree) continue;
    const auto& c = v == PixelVerdict::hard_error ? kHardErrorColour : kAmbiguousColour;
    std::copy(c.begin(), c.end(), overlay.pixels.begin() + static_cast<std::ptrdiff_t>(4 * p));
  }
  return overlay;
}

StencilChoice parse_stencil(const std::string& name) {
  return name == "auto" ? StencilChoice::automatic : name == "zpass" ? StencilChoice::zpass : StencilChoice::zfail;
}

// The viewer's state: the world scene (camera and lights move), what is drawn, the overlay.
class Viewer {
 public:
  Viewer(Scene scene, gpu::ShadowMethod method, StencilChoice stencil, bool overlay)
      : scene_(std::move(scene)), method_(method), stencil_(stencil), overlay_on_(overlay) {}

  void rebuild() {
    // Order: the GL objects of the old scene go before its data.
    shadows_.reset();
    frame_.reset();
    drawn_ = prepare_drawn_method_scene(scene_, method_, stencil_);
    shadows_.emplace(method_, drawn_->method_scene(), drawn_->host_options());
    frame_.emplace(drawn_->parts, drawn_->scene.camera.width, drawn_->scene.camera.height);
    overlay_.reset();
    dirty_ = false;
    if (overlay_on_) start_exact();
  }

  void draw() {
    if (dirty_) rebuild();
    // The overlay first: it renders the comparison offscreen, which binds other framebuffers.
    if (overlay_on_ && exact_future_.valid() &&
        exact_future_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      exact_ = exact_future_.get();
      overlay_ = verdict_overlay(*drawn_, *exact_, &comparison_);
    }
    shadows_->build();
    frame_->draw(drawn_->scene.camera, *shadows_);
    if (overlay_on_ && overlay_) frame_->draw_overlay(*overlay_);
    frame_->present();
  }

  // Whether what the frame shows is complete: no overlay asked for, or its verdicts drawn.
  [[nodiscard]] bool settled() const { return !overlay_on_ || overlay_.has_value(); }
  // The overlay's verdict counts, when it is drawn.
  [[nodiscard]] std::optional<PixelComparison> verdicts() const {
    return overlay_on_ && overlay_ ? std::optional(comparison_) : std::nullopt;
  }

  // The window's back buffer (the frame just drawn), row 0 at the top.
  [[nodiscard]] gpu::RgbaImage read_colour() const { return frame_->read_colour(); }

  [[nodiscard]] std::string title(double frame_ms) const {
    std::string t = fmt::format("shadowcert view: {} {} | {:.2f} ms/frame", gpu::shadow_method_name(method_),
                                stencil_choice_name(stencil_), frame_ms);
    if (overlay_on_) {
      if (overlay_)
        t += fmt::format(" | exact: {} hard errors (red), {} ambiguous (grey)", comparison_.hard_errors,
                         comparison_.ambiguous);
      else
        t += fmt::format(" | exact image: computing ({:.1f} s)",
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - exact_started_).count());
    }
    return t;
  }

  void next_method() {
    const std::vector<gpu::ShadowMethod> all = view_methods();
    auto it = std::find(all.begin(), all.end(), method_);
    method_ = ++it == all.end() ? all.front() : *it;
    dirty_ = true;
  }
  void next_stencil() {
    stencil_ = stencil_ == StencilChoice::zfail   ? StencilChoice::zpass
               : stencil_ == StencilChoice::zpass ? StencilChoice::automatic
                                                  : StencilChoice::zfail;
    dirty_ = true;
  }
  void toggle_overlay() {
    overlay_on_ = !overlay_on_;
    if (overlay_on_ && !overlay_ && !exact_future_.valid()) start_exact();
  }
  void orbit(double dx, double dy) {
    Camera& c = scene_.camera;
    const Vec3 up = unit(c.up);
    Vec3 arm = difference(c.eye, c.target);
    arm = rotate(arm, up, -dx * kOrbitRadiansPerPixel);
    const Vec3 right = unit(cross(arm, up));
    const Vec3 pitched = rotate(arm, right, -dy * kOrbitRadiansPerPixel);
    if (std::abs(dot(unit(pitched), up)) < 0.99) arm = pitched;  // never over the pole
    c.eye = {c.target[0] + arm[0], c.target[1] + arm[1], c.target[2] + arm[2]};
    dirty_ = true;
  }
  void zoom(double steps) {
    Camera& c = scene_.camera;
    const double f = std::pow(kZoomPerStep, steps);
    const Vec3 arm = difference(c.eye, c.target);
    c.eye = {c.target[0] + arm[0] * f, c.target[1] + arm[1] * f, c.target[2] + arm[2] * f};
    dirty_ = true;
  }
  // The first light moved in the view plane (a directional light's direction turned alike).
  void drag_light(double dx, double dy) {
    Camera& c = scene_.camera;
    std::array<double, 4>& l = scene_.lights.front().position;
    const Vec3 forward = unit(difference(c.target, c.eye));
    const Vec3 right = unit(cross(forward, c.up));
    const Vec3 up = cross(right, forward);
    const Vec3 from_target = l[3] == 0.0 ? Vec3{l[0], l[1], l[2]} : difference(Vec3{l[0], l[1], l[2]}, c.target);
    const double step = kLightSharePerPixel * std::sqrt(dot(from_target, from_target));
    for (int k = 0; k < 3; ++k) l[k] += step * (dx * right[k] - dy * up[k]);
    dirty_ = true;
  }

 private:
  void start_exact() {
    exact_started_ = std::chrono::steady_clock::now();
    const Scene snapshot = scene_;
    exact_future_ = std::async(std::launch::async, [snapshot] { return reference_image(snapshot); });
  }

  Scene scene_;
  gpu::ShadowMethod method_;
  StencilChoice stencil_;
  bool overlay_on_;
  bool dirty_ = true;
  std::unique_ptr<DrawnMethodScene> drawn_;
  std::optional<gpu::HostShadowVolumes> shadows_;
  std::optional<gpu::ViewerFrame> frame_;
  std::future<ExactImage> exact_future_;
  std::optional<ExactImage> exact_;
  std::optional<gpu::RgbaImage> overlay_;
  PixelComparison comparison_;
  std::chrono::steady_clock::time_point exact_started_{};
};

// GLFW's last error as text, for the environment errors.
std::string glfw_error() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description != nullptr ? description : "no description";
}

struct GlfwSession {  // glfwInit / glfwTerminate
  GlfwSession() {
    if (glfwInit() != GLFW_TRUE)
      throw gpu::GlEnvironmentError("view needs a display (set DISPLAY, or run under xvfb-run -a): GLFW: " +
                                    glfw_error());
  }
  ~GlfwSession() { glfwTerminate(); }
  GlfwSession(const GlfwSession&) = delete;
  GlfwSession& operator=(const GlfwSession&) = delete;
};

// The window; destroyed after the viewer's GL objects (declared before it), while GLFW lives.
struct GlfwWindow {
  GLFWwindow* window = nullptr;
  ~GlfwWindow() {
    if (window != nullptr) glfwDestroyWindow(window);
  }
};

struct Input {  // what the callbacks hand the loop
  Viewer* viewer = nullptr;
  double x = 0.0, y = 0.0;
};

int run_view(const ViewOptions& options) {
  const auto method = gpu::parse_shadow_method(options.method);
  if (!method) throw CLI::ValidationError("--method", fmt::format("unknown method '{}'", options.method));
  if (!gpu::draws_volume(*method))
    throw CLI::ValidationError("--method", fmt::format("view draws the volume methods (the host layer's); {} draws "
                                                       "none", options.method));
  if (!options.screenshot.empty() && options.frames == 0)
    throw CLI::ValidationError("--screenshot", "needs --frames N (N >= 1): the frame to write");
  Scene scene = load_image_scene(options.input);
  if (scene.lights.empty()) throw InputError(options.input, "the scene has no light");
  apply_image_size(options.size, scene.camera);
  const std::uint32_t width = scene.camera.width, height = scene.camera.height;

  const GlfwSession glfw;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  // The framebuffer of `render`'s offscreen target: RGBA8 (alpha marks coverage), depth 24,
  // stencil 8, one sample; the window's size is the image's.
  glfwWindowHint(GLFW_RED_BITS, 8);
  glfwWindowHint(GLFW_GREEN_BITS, 8);
  glfwWindowHint(GLFW_BLUE_BITS, 8);
  glfwWindowHint(GLFW_ALPHA_BITS, 8);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  glfwWindowHint(GLFW_STENCIL_BITS, 8);
  glfwWindowHint(GLFW_SAMPLES, 0);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  const GlfwWindow owner{glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), "shadowcert view",
                                         nullptr, nullptr)};
  GLFWwindow* window = owner.window;
  if (window == nullptr)
    throw gpu::GlEnvironmentError("view: no OpenGL 4.5 core window: GLFW: " + glfw_error());
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);  // frame time is drawing time, not the display's refresh
  int fb_width = 0, fb_height = 0;
  glfwGetFramebufferSize(window, &fb_width, &fb_height);
  if (fb_width != static_cast<int>(width) || fb_height != static_cast<int>(height))
    throw gpu::GlEnvironmentError(fmt::format("view: the window's framebuffer is {}x{}, not the scene's {}x{}",
                                              fb_width, fb_height, width, height));

  Viewer viewer(std::move(scene), *method, parse_stencil(options.stencil), options.overlay);
  Input input{&viewer};
  glfwSetWindowUserPointer(window, &input);
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    Viewer& v = *static_cast<Input*>(glfwGetWindowUserPointer(w))->viewer;
    if (key == GLFW_KEY_M) v.next_method();
    if (key == GLFW_KEY_S) v.next_stencil();
    if (key == GLFW_KEY_O) v.toggle_overlay();
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, GLFW_TRUE);
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    Input& in = *static_cast<Input*>(glfwGetWindowUserPointer(w));
    const double dx = x - in.x, dy = y - in.y;
    in.x = x;
    in.y = y;
    if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) in.viewer->orbit(dx, dy);
    if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) in.viewer->drag_light(dx, dy);
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
    static_cast<Input*>(glfwGetWindowUserPointer(w))->viewer->zoom(dy);
  });

  std::size_t frame = 0;
  double frame_ms = 0.0;
  double timed_ms = 0.0;  // frames 2.. (the first compiles llvmpipe's shader variants)
  std::size_t timed = 0;
  auto last = std::chrono::steady_clock::now();
  while (glfwWindowShouldClose(window) == GLFW_FALSE) {
    viewer.draw();
    ++frame;
    // With the overlay, the frame to write is the first from frame N on that shows it.
    if (!options.screenshot.empty() && frame >= options.frames && viewer.settled()) {
      const gpu::RgbaImage shot = viewer.read_colour();
      create_parent_directories(options.screenshot);
      gpu::write_png(options.screenshot, shot);
      std::printf("view: wrote %s (%ux%u, frame %zu)\n", options.screenshot.c_str(), width, height, frame);
      break;
    }
    glfwSwapBuffers(window);
    glfwPollEvents();
    const auto now = std::chrono::steady_clock::now();
    frame_ms = std::chrono::duration<double, std::milli>(now - last).count();
    last = now;
    if (frame >= 2) {
      timed_ms += frame_ms;
      ++timed;
    }
    glfwSetWindowTitle(window, viewer.title(frame_ms).c_str());
    if (options.screenshot.empty() && options.frames != 0 && frame >= options.frames && viewer.settled()) break;
  }
  // A frame's wall time, draw to swap (llvmpipe renders on the CPU, and its swap waits for
  // the frame): docs/engine-integration.md's per-frame cost.
  if (timed != 0) std::printf("view: %.2f ms/frame (mean of frames 2 to %zu)\n", timed_ms / double(timed), timed + 1);
  if (const auto v = viewer.verdicts())
    std::printf("view: exact overlay, first light: %llu hard errors, %llu ambiguous pixels\n",
                static_cast<unsigned long long>(v->hard_errors), static_cast<unsigned long long>(v->ambiguous));
  return kExitOk;
}

}  // namespace

void add_view_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ViewOptions>();
  CLI::App* cmd = app.add_subcommand(
      "view", "A window drawing the scene's shadows live (GLFW): left drag orbits, scroll zooms, right drag moves the "
              "first light; M: next method, S: next stencil mode, O: the exact image's overlay (hard errors red, "
              "ambiguous grey), Esc: quit; the frame time in the title");
  cmd->add_option("scene", options->input, "Scene file (.json) or mesh")->required();
  std::string names;
  for (const gpu::ShadowMethod m : view_methods()) names += (names.empty() ? "" : ", ") + std::string(gpu::shadow_method_name(m));
  cmd->add_option("--method", options->method, "The volume method to draw first: " + names)
      ->capture_default_str();
  cmd->add_option("--stencil", options->stencil, "zfail (default), zpass or auto (z-pass where proven, per light)")
      ->check(CLI::IsMember({"auto", "zpass", "zfail"}));
  cmd->add_option("--size", options->size, "Window and image size WxH (default: the scene camera's)");
  cmd->add_option("--screenshot", options->screenshot,
                  "Write frame N (--frames) of the window as PNG, then exit; with --overlay, the first frame from N on "
                  "that shows the exact image's overlay");
  cmd->add_option("--frames", options->frames, "Draw N frames, then exit (0: until the window closes)");
  cmd->add_flag("--overlay", options->overlay, "Start with the exact image's overlay on");
  cmd->callback([options, &exit_code] { exit_code = run_view(*options); });
}

}  // namespace shadowcert::cli
