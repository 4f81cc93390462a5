#pragma once
// The method registry: every shadow method `render`, `diff`, `fuzz --gl` and `bench` know, one
// entry each, in one place. An entry says what the method is (its row of gpu/shadow_method.h:
// name, family, filter), whether it is held to the robust rule, which of the image commands'
// options it reads, its help text and docs section, and the parameter bench sweeps. The CLI
// composes its --help, its method lists (`--methods all`), its option checks ("--pcf is read
// by pcf only") and each method's parameter report from here; bench makes its runs from here.
// Adding a method is one entry here and its own files (docs/development.md#adding-a-method).
//
//   for (const MethodEntry& m : method_registry()) ...                  // display order
//   const MethodEntry& e = method_entry(gpu::ShadowMethod::pcf);       // e.reads(MethodOption::pcf_kernel)
//   std::vector<gpu::ShadowMethod> ms = parse_method_list("cpu,pcf");  // "all": the in_all methods
//
// Two kinds of method: the GL methods (gpu/shadow_method.h's table, drawn by a GL renderer, one
// MethodEntry each) and the ray-traced ones (traced on the CPU by Embree, raytrace/: no GL
// context, no volume, no option of the GL methods; one RayTracedEntry each). Both are named by
// --method/--methods; a command or a comparison takes a MethodSelection of both kinds:
//
//   MethodSelection s = parse_method_selection("cpu,rt-robust");  // s.gl {cpu}, s.ray_traced {rt_robust}
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gpu/shadow_method.h"
#include "raytrace/embree_scene.h"

namespace shadowcert {

// The options of the image commands a method reads, as bits of MethodEntry::options.
enum class MethodOption : std::uint32_t {
  stencil = 1u << 0,       // --stencil auto|zpass|zfail, --zpass, --zfail: how the volume is counted
  sign = 1u << 1,          // --sign exact|float: how the GPU takes each triangle's light side
  shadow_map = 1u << 2,    // --shadowmap-size, --shadowmap-bias, --shadowmap-slope
  pcf_kernel = 1u << 3,    // --pcf K
  light_radius = 1u << 4,  // --light-radius R, --light-angle DEG (the area light's size: point, directional)
  smoothie = 1u << 5,      // --smoothie-width D, --smoothie-space world|light
  silhouette = 1u << 6,    // --epsilon, --crease-angle
  capture = 1u << 7,       // --capture: the first light's volume as drawn
};
[[nodiscard]] constexpr std::uint32_t operator|(MethodOption a, MethodOption b) {
  return static_cast<std::uint32_t>(a) | static_cast<std::uint32_t>(b);
}
[[nodiscard]] constexpr std::uint32_t operator|(std::uint32_t a, MethodOption b) { return a | static_cast<std::uint32_t>(b); }

// The CLI options a MethodOption stands for, for messages and the docs test ("--shadowmap-size").
[[nodiscard]] std::span<const std::string_view> method_option_flags(MethodOption option);

// The parameter bench sweeps for a method, each value one run with id "name/label".
enum class SweptParameter { none, sign, shadow_map_size, pcf_kernel, smoothie_width_in_r, epsilon };
struct BenchSweep {
  SweptParameter parameter = SweptParameter::none;
  // The values and their id labels ("exact"/"float" for sign as 0/1; "R/4" for a smoothie width
  // of a quarter of the light radius); `count` of the four are used.
  std::array<double, 4> values{};
  std::array<std::string_view, 4> labels{};
  std::size_t count = 0;
};

struct MethodEntry {
  gpu::ShadowMethod method = gpu::ShadowMethod::cpu;
  // Held to the robust rule: zero hard errors against the exact image and closed volumes
  // (docs/definitions.md#pixel-protocol). Shadow maps are baselines (their error is their
  // speed-against-error figure); accurate, smooth and smooth-gpu shadow another surface
  // (docs/smooth-silhouettes.md): reported, never a failure. Every volume must be closed all the same.
  bool robust = false;
  std::uint32_t options = 0;   // MethodOption bits
  std::string_view help;       // render --method's clause for it
  std::string_view docs;       // the docs/ page (and section) that defines it
  BenchSweep sweep;            // bench's runs of it

  [[nodiscard]] std::string_view name() const { return gpu::shadow_method_name(method); }
  [[nodiscard]] const gpu::ShadowMethodTraits& traits() const { return gpu::shadow_method_traits(method); }
  [[nodiscard]] bool reads(MethodOption option) const { return (options & static_cast<std::uint32_t>(option)) != 0; }
};

// The ray-traced methods (docs/ray-tracing.md): float hard shadows of the exact image's own
// centre rays, one shadow ray per hit and light, by Embree in one of its build modes.
enum class RayTracedMethod { rt, rt_robust };

struct RayTracedEntry {
  RayTracedMethod method = RayTracedMethod::rt;
  std::string_view name;       // the --method value: "rt", "rt-robust"
  raytrace::BuildMode mode = raytrace::BuildMode::fast;
  // Never held to the robust rule: a float peer, like the shadow maps, whose hard errors are its
  // figure (reported by diff and bench, never a failure). Kept as a field so that the rule reads
  // the same for both kinds.
  bool robust = false;
  std::string_view help;       // render --method's clause for it
  std::string_view docs;       // the docs/ page that defines it
};

// Every method, in display order (the chain methods, the shadow maps, the silhouette methods):
// the order of --help, of `--methods all` and of bench's matrix. The GL methods only; the
// ray-traced ones follow them (ray_traced_registry()).
[[nodiscard]] std::span<const MethodEntry> method_registry();
// The ray-traced methods, in display order (after the GL ones): rt, rt-robust.
[[nodiscard]] std::span<const RayTracedEntry> ray_traced_registry();
[[nodiscard]] const RayTracedEntry& ray_traced_entry(RayTracedMethod method);
// The ray-traced entry of that name; nullptr for any other string.
[[nodiscard]] const RayTracedEntry* find_ray_traced_method(std::string_view name);
[[nodiscard]] inline std::string_view ray_traced_method_name(RayTracedMethod method) {
  return ray_traced_entry(method).name;
}
// The entry of `method` (every gpu::ShadowMethod has one).
[[nodiscard]] const MethodEntry& method_entry(gpu::ShadowMethod method);
// The entry of that name; nullptr for any other string.
[[nodiscard]] const MethodEntry* find_method(std::string_view name);
// Whether the method is held to the robust rule (MethodEntry::robust).
[[nodiscard]] bool robust(gpu::ShadowMethod method);

// Every method name in display order, the GL methods then the ray-traced ones, separated by
// `separator` ("cpu, cs, ..., rt, rt-robust" or "cpu|cs|...").
[[nodiscard]] std::string method_names(std::string_view separator = ", ");

// Methods of both kinds, each in the order its list named it.
struct MethodSelection {
  std::vector<gpu::ShadowMethod> gl;
  std::vector<RayTracedMethod> ray_traced;
  [[nodiscard]] bool empty() const { return gl.empty() && ray_traced.empty(); }
};
// The methods `list` names, comma-separated, duplicates dropped, in the list's order; "all" (alone
// or as an entry) stands for the in_all GL methods (a ray-traced method is asked for by name);
// an empty list is "all". Throws std::invalid_argument("unknown method 'x': use cpu, cs, ...")
// for any other name.
[[nodiscard]] MethodSelection parse_method_selection(std::string_view list);
// The same for a command that draws with GL only (fuzz --gl-methods): a ray-traced name throws
// std::invalid_argument("'rt' is traced on the CPU, not a GL method: use ...").
[[nodiscard]] std::vector<gpu::ShadowMethod> parse_method_list(std::string_view list);

// render --method's help: every entry's clause, GL and ray-traced.
[[nodiscard]] std::string method_help();

// The methods that read `option`, by name ("pcf" or "shadowmap, pcf, pcss, smoothie").
[[nodiscard]] std::string methods_reading(MethodOption option);

}  // namespace shadowcert
