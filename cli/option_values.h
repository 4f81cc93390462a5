#pragma once
// Values of the options several subcommands share, read in one place with one message each:
// `--size WxH` (the camera's image size, each side in [1, kMaxImageSide], core/camera.h:
// GL_MAX_RENDERBUFFER_SIZE of every driver we target) and method names (render --method,
// diff --methods, fuzz --gl-methods), read from pipeline/method_registry.h, and the stencil choice
// (--stencil and its aliases --zpass and --zfail).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "core/camera.h"
#include "gpu/shadow_method_renderer.h"
#include "pipeline/method_registry.h"
#include "pipeline/stencil_choice.h"

namespace shadowcert::cli {

// The input of the commands that make images (render, diff, soft, edges): io/scene_input.h's
// load_image_scene.
inline constexpr const char* kImageInputHelp =
    "Scene (.json), or a mesh file (.obj .off .ply .stl) framed over a floor with a light and a camera "
    "(docs/cli.md#inputs)";

// `--light-angle DEG` (render, diff, soft, bench): a directional light's angular radius in
// degrees, the size of a sun whatever the scene's scale (docs/smoothies.md#light-sizes); the
// point lights' size is `--light-radius R` in world units.
inline constexpr const char* kLightAngleHelp =
    "A directional light's angular radius in degrees, in (0, 90) (default 0.573 = atan 0.01, whatever the scene's "
    "scale; the sun's is 0.27); point lights take --light-radius";
// Throws CLI::ValidationError naming `option` unless `degrees` is finite and in (0, 90), or
// [0, 90) with `zero_allowed` (soft: 0 is the hard shadow).
void check_light_angle(double degrees, bool zero_allowed = false, const std::string& option = "--light-angle");

// Sets camera.width and camera.height from "WxH" (e.g. "1024x768"); an empty string leaves
// the scene camera's size. Throws CLI::ValidationError naming `option` otherwise.
void apply_image_size(const std::string& size, Camera& camera, const std::string& option = "--size");

// The method named `name`. Throws CLI::ValidationError naming `option` and the unknown name,
// with the list of names.
[[nodiscard]] gpu::ShadowMethod shadow_method_option(const std::string& name, const std::string& option);

// `--stencil auto|zpass|zfail` (empty: not given) with its aliases `--zpass` and `--zfail`
// (render, diff): the choice, zfail when none is given. Throws CLI::ValidationError for --zpass
// with --zfail, and for an alias that contradicts --stencil (an agreeing one is accepted).
[[nodiscard]] StencilChoice stencil_option(const std::string& stencil, bool zpass, bool zfail);

// `--shard K/N` (fuzz; bench reads the same syntax): shard K of N, 1 <= K <= N, decimal
// digits only; an empty string is 1/1, the whole run. Throws CLI::ValidationError naming
// `option` and the text for anything else (a malformed K/N, K = 0, K > N, N = 0).
struct ShardOption {
  std::uint64_t k = 1;
  std::uint64_t n = 1;
};
[[nodiscard]] ShardOption shard_option(const std::string& text, const std::string& option = "--shard");

// A comma-separated list of method names, duplicates dropped, in the list's order; "all" (or an
// empty list): the registry's in_all methods (pipeline/method_registry.h's parse_method_list).
// Throws CLI::ValidationError naming `option`, the unknown name and the names.
[[nodiscard]] std::vector<gpu::ShadowMethod> shadow_methods_option(const std::string& list, const std::string& option);
// The same list with the ray-traced methods too (rt, rt-robust: pipeline/method_registry.h's
// parse_method_selection); "all" stays the in_all GL methods.
[[nodiscard]] MethodSelection method_selection_option(const std::string& list, const std::string& option);

// `--threads N` (diff, render, bench; fuzz has its own): the worker threads of everything the
// command runs on the CPU through TBB (the exact image, the soft reference, Embree's builds and
// rays), so that the exact image and the ray tracer are timed on the same threads. 0: every core.
inline constexpr const char* kThreadsHelp =
    "Worker threads of the exact image, the soft reference and the ray tracer (TBB; 0: every core)";
// The limit for `threads` (held for the command's run), or none for 0. Throws
// CLI::ValidationError naming `option` for more than 4096 (a typo, not a machine).
[[nodiscard]] std::unique_ptr<tbb::global_control> thread_limit(unsigned threads, const std::string& option = "--threads");

}  // namespace shadowcert::cli
