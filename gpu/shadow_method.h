#pragma once
// The GL shadow methods and what each one is, in one table: its name (the CLI's --method value),
// its family (how it draws), the shadow-map filter it applies, and the two facts the comparison
// rests on (whether it shadows the polyhedral surface and whether `--methods all` includes it).
// Every predicate below reads the table, so a method's traits are stated once
// (docs/development.md#adding-a-method; pipeline/method_registry.h adds the options, the help
// and the bench runs of each method on top of this).
#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/gpu_stage_timer.h"

namespace shadowcert::gpu {

enum class ShadowMethod { cpu, cs, gs, ts, pertri, shadowmap, discrete, accurate, smooth, smooth_gpu, pcf, pcss, smoothie };

// How a method shadows.
enum class MethodFamily {
  given_volume,  // cpu: one volume per light, built by the caller (exact/chain_mesh.h), drawn as is
  gpu_volume,    // cs, gs, ts, pertri: built on the GPU from the canonical soup, every frame
  silhouette,    // discrete, accurate, smooth, smooth-gpu: smooth-silhouette volumes (contour/, pipeline/)
  shadow_map,    // shadowmap, pcf, pcss, smoothie: a depth map per light, no volume
};

// gpu/shadow_map_renderer.h's filters of the depth map (hard for the volume methods).
enum class ShadowFilter { hard, pcf, pcss, smoothie };

struct ShadowMethodTraits {
  ShadowMethod method;
  std::string_view name;
  MethodFamily family;
  ShadowFilter filter;
  // Shadows the smooth surface the corner normals describe (accurate, smooth, smooth-gpu), not
  // the polyhedral one: its disagreement with the exact image is its error, and its stencil
  // counts are not n(P) (docs/smooth-silhouettes.md).
  bool smooth_surface;
  // In `--methods all` (diff's default): the exact chain, the four GPU-built volumes and the
  // hard shadow map. The others are asked for by name: the smooth-silhouette methods need
  // casters that qualify, the soft ones are baselines of another question (docs/smoothies.md).
  bool in_all;
};

// Indexed by ShadowMethod (the enum's order); the tests check that every row sits at its index.
inline constexpr std::array<ShadowMethodTraits, 13> kShadowMethodTable{{
    {ShadowMethod::cpu, "cpu", MethodFamily::given_volume, ShadowFilter::hard, false, true},
    {ShadowMethod::cs, "cs", MethodFamily::gpu_volume, ShadowFilter::hard, false, true},
    {ShadowMethod::gs, "gs", MethodFamily::gpu_volume, ShadowFilter::hard, false, true},
    {ShadowMethod::ts, "ts", MethodFamily::gpu_volume, ShadowFilter::hard, false, true},
    {ShadowMethod::pertri, "pertri", MethodFamily::gpu_volume, ShadowFilter::hard, false, true},
    {ShadowMethod::shadowmap, "shadowmap", MethodFamily::shadow_map, ShadowFilter::hard, false, true},
    {ShadowMethod::discrete, "discrete", MethodFamily::silhouette, ShadowFilter::hard, false, false},
    {ShadowMethod::accurate, "accurate", MethodFamily::silhouette, ShadowFilter::hard, true, false},
    {ShadowMethod::smooth, "smooth", MethodFamily::silhouette, ShadowFilter::hard, true, false},
    {ShadowMethod::smooth_gpu, "smooth-gpu", MethodFamily::silhouette, ShadowFilter::hard, true, false},
    {ShadowMethod::pcf, "pcf", MethodFamily::shadow_map, ShadowFilter::pcf, false, false},
    {ShadowMethod::pcss, "pcss", MethodFamily::shadow_map, ShadowFilter::pcss, false, false},
    {ShadowMethod::smoothie, "smoothie", MethodFamily::shadow_map, ShadowFilter::smoothie, false, false},
}};

[[nodiscard]] constexpr const ShadowMethodTraits& shadow_method_traits(ShadowMethod m) {
  const auto index = static_cast<std::size_t>(m);
  if (index >= kShadowMethodTable.size()) throw std::invalid_argument("shadow_method_traits: unknown method");
  return kShadowMethodTable[index];
}

// Every method of a family, in the table's order.
template <std::size_t N>
[[nodiscard]] constexpr std::array<ShadowMethod, N> methods_where(bool (*keep)(const ShadowMethodTraits&)) {
  std::array<ShadowMethod, N> out{};
  std::size_t n = 0;
  for (const ShadowMethodTraits& t : kShadowMethodTable)
    if (keep(t)) out[n++] = t.method;  // a wrong N fails to compile (out of bounds) or leaves cpu rows
  return out;
}

// What `--methods all` means: the chain methods and the shadow map.
inline constexpr std::array<ShadowMethod, 6> kShadowMethods =
    methods_where<6>([](const ShadowMethodTraits& t) { return t.in_all; });
// The smooth-silhouette methods (docs/smooth-silhouettes.md): discrete, accurate, smooth, smooth-gpu.
inline constexpr std::array<ShadowMethod, 4> kSilhouetteMethods =
    methods_where<4>([](const ShadowMethodTraits& t) { return t.family == MethodFamily::silhouette; });
// The soft shadow-map methods (docs/smoothies.md): the filtered maps and the smoothies.
inline constexpr std::array<ShadowMethod, 3> kSoftShadowMethods = methods_where<3>(
    [](const ShadowMethodTraits& t) { return t.family == MethodFamily::shadow_map && t.filter != ShadowFilter::hard; });

// "cpu", "cs", "gs", "ts", "pertri", "shadowmap", "discrete", "accurate", "smooth", "smooth-gpu",
// "pcf", "pcss", "smoothie" (the CLI's --method values).
[[nodiscard]] constexpr std::string_view shadow_method_name(ShadowMethod method) {
  return shadow_method_traits(method).name;
}
// The method of that name; nullopt for any other string.
[[nodiscard]] constexpr std::optional<ShadowMethod> parse_shadow_method(std::string_view name) {
  for (const ShadowMethodTraits& t : kShadowMethodTable)
    if (t.name == name) return t.method;
  return std::nullopt;
}
// The shadow map or one of its filters (shadowmap, pcf, pcss, smoothie): no volume, one depth
// map per light (gpu/shadow_map_renderer.h).
[[nodiscard]] constexpr bool uses_shadow_map(ShadowMethod m) {
  return shadow_method_traits(m).family == MethodFamily::shadow_map;
}
// The shadow-map filter of such a method (hard for shadowmap and every volume method).
[[nodiscard]] constexpr ShadowFilter shadow_filter(ShadowMethod m) { return shadow_method_traits(m).filter; }
// Whether the method counts a shadow volume in the stencil (all but the shadow-map methods).
[[nodiscard]] constexpr bool draws_volume(ShadowMethod m) { return !uses_shadow_map(m); }
// Whether the GPU builds the volume from the canonical soup (cs, gs, ts, pertri).
[[nodiscard]] constexpr bool builds_volume_on_gpu(ShadowMethod m) {
  return shadow_method_traits(m).family == MethodFamily::gpu_volume;
}
// The smooth-silhouette methods: discrete, accurate, smooth, smooth-gpu.
[[nodiscard]] constexpr bool is_silhouette_method(ShadowMethod m) {
  return shadow_method_traits(m).family == MethodFamily::silhouette;
}
// accurate, smooth, smooth-gpu (ShadowMethodTraits::smooth_surface).
[[nodiscard]] constexpr bool shadows_smooth_surface(ShadowMethod m) { return shadow_method_traits(m).smooth_surface; }
// Whether the caller hands the method one volume per light (ShadowMethodScene::cpu_volumes):
// cpu and the smooth-silhouette methods (for smooth-gpu, the volume of the meshes it does not
// build; it may be empty).
[[nodiscard]] constexpr bool draws_given_volume(ShadowMethod m) {
  const MethodFamily f = shadow_method_traits(m).family;
  return f == MethodFamily::given_volume || f == MethodFamily::silhouette;
}
// The stages a frame of the method runs, in order: volume, depth, stencil, lit for the volume
// methods (cpu's volume stage is empty: 0); depth, shadow_map, lit for shadowmap, pcf and pcss;
// depth, shadow_map, smoothie_map, lit for smoothie.
[[nodiscard]] std::vector<RenderStage> method_stages(ShadowMethod method);

}  // namespace shadowcert::gpu
