#include "pipeline/method_registry.h"

#include <algorithm>
#include <stdexcept>

namespace shadowcert {
namespace {

using gpu::ShadowMethod;

constexpr std::uint32_t kVolume = MethodOption::stencil | MethodOption::capture;
constexpr std::uint32_t kGpuVolume = kVolume | MethodOption::sign;
constexpr std::uint32_t kMap = static_cast<std::uint32_t>(MethodOption::shadow_map);
constexpr std::uint32_t kSilhouette = kVolume | MethodOption::silhouette;

constexpr BenchSweep kSigns{SweptParameter::sign, {0.0, 1.0}, {"exact", "float"}, 2};
constexpr BenchSweep kMapSizes{SweptParameter::shadow_map_size, {512, 1024, 2048, 4096}, {"512", "1024", "2048", "4096"}, 4};
constexpr BenchSweep kKernels{SweptParameter::pcf_kernel, {3, 5, 9}, {"3", "5", "9"}, 3};
constexpr BenchSweep kSmoothieWidths{SweptParameter::smoothie_width_in_r, {0.25, 0.5, 1.0}, {"R/4", "R/2", "R"}, 3};
constexpr BenchSweep kEpsilons{SweptParameter::epsilon, {0.1, 0.03, 0.01, 0.003}, {"0.1", "0.03", "0.01", "0.003"}, 4};
constexpr BenchSweep kOneEpsilon{SweptParameter::epsilon, {0.01}, {"0.01"}, 1};

// Display order: the chain methods, the shadow maps, the smooth-silhouette methods.
const std::array<MethodEntry, gpu::kShadowMethodTable.size()> kRegistry{{
    {ShadowMethod::cpu, true, kVolume,
     "cpu (the exact chain of the float-rounded input from exact/, drawn as is; exact/cpu_volume.h)",
     "docs/gpu.md", {}},
    {ShadowMethod::cs, true, kGpuVolume,
     "cs (compute shader, float reference-edge multiplicities, rebuilt every frame; gpu/compute_volume.h)",
     "docs/gpu.md", kSigns},
    {ShadowMethod::gs, true, kGpuVolume,
     "gs (geometry shader over edge records, the same multiplicities, captured by transform feedback, rebuilt "
     "every frame; gpu/geometry_shader_volume.h)",
     "docs/gpu.md", kSigns},
    {ShadowMethod::ts, true, kGpuVolume,
     "ts (tessellation over edge-record patches, the same multiplicities and capture; gpu/tessellation_volume.h)",
     "docs/gpu.md", kSigns},
    {ShadowMethod::pertri, true, kGpuVolume,
     "pertri (compute shader, every triangle's own closed volume, no silhouette, rebuilt every frame; "
     "gpu/per_triangle_volume.h)",
     "docs/gpu.md", kSigns},
    {ShadowMethod::shadowmap, false, kMap,
     "shadowmap (no volume: a depth map from each light, --shadowmap-size/-bias/-slope; gpu/shadow_map_renderer.h)",
     "docs/gpu.md#shadow-map-baseline", kMapSizes},
    {ShadowMethod::pcf, false, kMap | MethodOption::pcf_kernel,
     "pcf (the map filtered by K x K percentage-closer taps, --pcf K)", "docs/smoothies.md", kKernels},
    {ShadowMethod::pcss, false, kMap | MethodOption::light_radius,
     "pcss (percentage-closer soft shadows of a disk light: --light-radius for a point light, --light-angle for a "
     "directional one)", "docs/smoothies.md", {}},
    {ShadowMethod::smoothie, false, kMap | MethodOption::smoothie,
     "smoothie (the map, then smoothies along the silhouette edges: --smoothie-width, --smoothie-space)",
     "docs/smoothies.md", kSmoothieWidths},
    {ShadowMethod::discrete, true, kSilhouette,
     "discrete (the silhouette loops of every mesh that is an oriented 2-manifold, the others by the robust chain, "
     "named in the output)",
     "docs/smooth-silhouettes.md", {}},
    {ShadowMethod::accurate, false, kSilhouette, "accurate (loops through the interpolated-normal contour)",
     "docs/smooth-silhouettes.md", {}},
    {ShadowMethod::smooth, false, kSilhouette, "smooth (the smooth contour within --epsilon)",
     "docs/smooth-silhouettes.md", kEpsilons},
    {ShadowMethod::smooth_gpu, false, kSilhouette,
     "smooth-gpu (smooth's volume built on the GPU every frame; gpu/smooth_silhouette_volume.h)",
     "docs/smooth-silhouettes.md", kOneEpsilon},
}};

// The ray-traced methods, after the GL ones (docs/ray-tracing.md).
constexpr std::array<RayTracedEntry, 2> kRayTraced{{
    {RayTracedMethod::rt, "rt", raytrace::BuildMode::fast, false,
     "rt (no GL: Embree ray-traces the centre rays on the CPU, one shadow ray per hit and light, in float; "
     "Embree's default fast build; raytrace/ray_traced_image.h)",
     "docs/ray-tracing.md"},
    {RayTracedMethod::rt_robust, "rt-robust", raytrace::BuildMode::robust, false,
     "rt-robust (rt with Embree's robust mode: RTC_SCENE_FLAG_ROBUST and a high-quality BVH)", "docs/ray-tracing.md"},
}};

}  // namespace

std::span<const RayTracedEntry> ray_traced_registry() { return kRayTraced; }

const RayTracedEntry& ray_traced_entry(RayTracedMethod method) {
  for (const RayTracedEntry& e : kRayTraced)
    if (e.method == method) return e;
  throw std::invalid_argument("ray_traced_entry: no entry for method " + std::to_string(static_cast<int>(method)));
}

const RayTracedEntry* find_ray_traced_method(std::string_view name) {
  for (const RayTracedEntry& e : kRayTraced)
    if (e.name == name) return &e;
  return nullptr;
}

std::span<const std::string_view> method_option_flags(MethodOption option) {
  static constexpr std::array<std::string_view, 3> kStencil{"--stencil", "--zpass", "--zfail"};
  static constexpr std::array<std::string_view, 1> kSign{"--sign"};
  static constexpr std::array<std::string_view, 3> kMapFlags{"--shadowmap-size", "--shadowmap-bias", "--shadowmap-slope"};
  static constexpr std::array<std::string_view, 1> kPcf{"--pcf"};
  static constexpr std::array<std::string_view, 2> kRadius{"--light-radius", "--light-angle"};
  static constexpr std::array<std::string_view, 2> kSmoothie{"--smoothie-width", "--smoothie-space"};
  static constexpr std::array<std::string_view, 2> kSilhouetteFlags{"--epsilon", "--crease-angle"};
  static constexpr std::array<std::string_view, 1> kCapture{"--capture"};
  switch (option) {
    case MethodOption::stencil: return kStencil;
    case MethodOption::sign: return kSign;
    case MethodOption::shadow_map: return kMapFlags;
    case MethodOption::pcf_kernel: return kPcf;
    case MethodOption::light_radius: return kRadius;
    case MethodOption::smoothie: return kSmoothie;
    case MethodOption::silhouette: return kSilhouetteFlags;
    case MethodOption::capture: return kCapture;
  }
  throw std::invalid_argument("method_option_flags: unknown option");
}

std::span<const MethodEntry> method_registry() { return kRegistry; }

const MethodEntry& method_entry(gpu::ShadowMethod method) {
  for (const MethodEntry& e : kRegistry)
    if (e.method == method) return e;
  throw std::invalid_argument("method_entry: no entry for method " + std::to_string(static_cast<int>(method)));
}

const MethodEntry* find_method(std::string_view name) {
  for (const MethodEntry& e : kRegistry)
    if (e.name() == name) return &e;
  return nullptr;
}

bool robust(gpu::ShadowMethod method) { return method_entry(method).robust; }

std::string method_names(std::string_view separator) {
  std::string names;
  for (const MethodEntry& e : kRegistry) names += (names.empty() ? "" : std::string(separator)) + std::string(e.name());
  for (const RayTracedEntry& e : kRayTraced) names += std::string(separator) + std::string(e.name);
  return names;
}

MethodSelection parse_method_selection(std::string_view list) {
  MethodSelection selection;
  std::vector<gpu::ShadowMethod>& methods = selection.gl;
  const auto add = [&](gpu::ShadowMethod m) {
    if (std::find(methods.begin(), methods.end(), m) == methods.end()) methods.push_back(m);
  };
  const auto add_all = [&] {
    for (const MethodEntry& e : kRegistry)
      if (e.traits().in_all) add(e.method);
  };
  if (list.empty()) {
    add_all();
    return selection;
  }
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string_view name = list.substr(start, comma - start);
    start = comma + 1;
    if (name == "all") {
      add_all();
      continue;
    }
    if (const RayTracedEntry* r = find_ray_traced_method(name)) {
      if (std::find(selection.ray_traced.begin(), selection.ray_traced.end(), r->method) == selection.ray_traced.end())
        selection.ray_traced.push_back(r->method);
      continue;
    }
    const MethodEntry* e = find_method(name);
    if (e == nullptr) throw std::invalid_argument("unknown method '" + std::string(name) + "': use " + method_names() + " or all");
    add(e->method);
  }
  return selection;
}

std::vector<gpu::ShadowMethod> parse_method_list(std::string_view list) {
  MethodSelection selection = parse_method_selection(list);
  if (!selection.ray_traced.empty()) {
    std::string gl_names;
    for (const MethodEntry& e : kRegistry) gl_names += (gl_names.empty() ? "" : ", ") + std::string(e.name());
    throw std::invalid_argument("'" + std::string(ray_traced_method_name(selection.ray_traced.front())) +
                                "' is traced on the CPU, not a GL method: use " + gl_names + " or all");
  }
  return std::move(selection.gl);
}

std::string method_help() {
  std::vector<std::string_view> clauses;
  for (const MethodEntry& e : kRegistry) clauses.push_back(e.help);
  for (const RayTracedEntry& e : kRayTraced) clauses.push_back(e.help);
  std::string help = "The shadow method: ";
  for (std::size_t i = 0; i < clauses.size(); ++i)
    help += std::string(i == 0 ? "" : i + 1 == clauses.size() ? " or " : ", ") + std::string(clauses[i]);
  // Where each is defined, grouped by page in the order the pages first appear.
  std::vector<std::pair<std::string_view, std::string>> pages;
  const auto add_page = [&](std::string_view docs, std::string_view name) {
    const std::string_view page = docs.substr(0, docs.find('#'));
    auto at = std::find_if(pages.begin(), pages.end(), [&](const auto& p) { return p.first == page; });
    if (at == pages.end()) at = pages.insert(pages.end(), {page, std::string()});
    at->second += (at->second.empty() ? "" : ", ") + std::string(name);
  };
  for (const MethodEntry& e : kRegistry) add_page(e.docs, e.name());
  for (const RayTracedEntry& e : kRayTraced) add_page(e.docs, e.name);
  help += ". Defined in ";
  for (std::size_t i = 0; i < pages.size(); ++i)
    help += std::string(i == 0 ? "" : "; ") + std::string(pages[i].first) + " (" + pages[i].second + ")";
  return help;
}

std::string methods_reading(MethodOption option) {
  std::string names;
  for (const MethodEntry& e : kRegistry)
    if (e.reads(option)) names += (names.empty() ? "" : ", ") + std::string(e.name());
  return names;
}

}  // namespace shadowcert
