#pragma once
// One scene, every chosen GL shadow method against the exact image (DESIGN.md §5, docs/diff.md):
// the part `shadowcert diff` and `shadowcert fuzz --gl` share, so that a fuzz reproducer's
// `shadowcert diff` command computes exactly what the campaign computed.
//
//   gpu::EglContext context = open_gl_context("diff", device);   // current on this thread
//   SceneComparison c = compare_scene(scene, methods, {});         // exact image, then GL
//   bool ok = c.passed();                                          // no robust method failed
//
// Per method and light (each light rendered alone, so that every light is compared): the
// frame and its readback, the pixel comparison (exact/pixel_comparison.h) against the exact
// image of the scene and of its float rounding (exact/input_rounding.h), and for the volume
// methods the exact closure of the captured volume (exact/captured_volume.h).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene.h"
#include "exact/closure_certificate.h"
#include "exact/exact_image.h"
#include "exact/pixel_comparison.h"
#include "gpu/egl_context.h"
#include "gpu/shadow_method_renderer.h"

namespace shadowcert::cli {

// Robust methods must show zero hard errors and closed volumes (DESIGN.md §5); the shadow map
// is the baseline whose errors are its speed-against-error figures (§7).
[[nodiscard]] constexpr bool robust(gpu::ShadowMethod method) { return method != gpu::ShadowMethod::shadowmap; }

// A comma-separated list of method names (cpu, cs, gs, ts, pertri, shadowmap), duplicates
// dropped, in the list's order; empty: every method. Throws CLI::ValidationError naming
// `option` and the unknown name.
[[nodiscard]] std::vector<gpu::ShadowMethod> parse_shadow_methods(const std::string& list, const std::string& option);

// An OpenGL 4.5 core context through headless EGL, current on the calling thread. Throws
// gpu::GlEnvironmentError whose message says that `command` needs it, which packages give it,
// and the driver's own message (main maps it to exit 2).
[[nodiscard]] gpu::EglContext open_gl_context(std::string_view command, std::optional<int> device);

// One method against one light.
struct LightRun {
  PixelComparison comparison;
  gpu::StencilShadowFrame frame;
  std::optional<ClosureCertificate> closure;  // volume methods
  std::uint64_t volume_triangles = 0;
  double gl_ms = 0.0;          // mean wall ms of the timed frames; 0 when none were timed
  std::string capacity_error;  // a GPU-built volume overflowed its buffers (then drawn open)
};

struct MethodRun {
  gpu::ShadowMethod method = gpu::ShadowMethod::cpu;
  std::vector<LightRun> lights;

  [[nodiscard]] std::uint64_t sum(std::uint64_t PixelComparison::*figure) const;
  // nullopt for shadowmap (no volume); otherwise whether every light's volume is closed.
  [[nodiscard]] std::optional<bool> closed() const;
  [[nodiscard]] double gl_ms() const;
  // A robust method with a hard error or an open volume.
  [[nodiscard]] bool failed() const;
};

struct SceneComparisonOptions {
  gpu::ShadowMethodOptions method_options;  // z-fail or z-pass, shadow map size
  // Frames drawn without readback after the compared one, for LightRun::gl_ms (one frame
  // alone would mostly time llvmpipe's first-use compilation); 0: none.
  std::size_t timed_frames = 0;
  bool progress = false;  // the exact image's progress bar on stderr
};

struct SceneComparison {
  ExactImage exact;  // the reference, marked by the float-rounded scene's image
  double rounded_seconds = 0.0;  // the float-rounded scene's exact image
  std::vector<MethodRun> runs;   // one per method, in the given order

  [[nodiscard]] bool passed() const;  // no run failed
};

// The reference and every method on `scene` (every mesh receives and casts, as in the GL
// methods). Preconditions: a GL context is current on this thread; the scene has at least one
// light and one triangle, and `methods` is not empty (std::invalid_argument("compare_scene:
// ...") otherwise). Throws what the renderers and the exact image throw.
[[nodiscard]] SceneComparison compare_scene(const Scene& scene, const std::vector<gpu::ShadowMethod>& methods,
                                            const SceneComparisonOptions& options);

}  // namespace shadowcert::cli
