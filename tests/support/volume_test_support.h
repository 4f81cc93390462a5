#pragma once
// What the GL volume tests share: the canonical soup and edge table of a test soup, the
// default scene and the half fan, the reference volume, any method of
// gpu/shadow_method_renderer.h lit by one light (as `render --method` draws it) and its stencil
// difference from cpu, the per-soup, per-light build loop of the volume classes' own tests, and
// the closure check of captured triangles. The reference every method is compared with is the
// exact cpu chain as GPU geometry, exact/cpu_volume.h's cpu_volume_mesh (what render --method
// cpu draws): tests that include this header link shadowcert_pipeline (CPU reference only: gpu/
// never links exact/; tests/CMakeLists.txt). Scenes are merged into one soup as the CLI merges them
// (scene/merged_soup.h). Test code only.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <iterator>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/homogeneous_mesh.h"
#include "core/scene.h"
#include "core/sign.h"
#include "exact/cpu_volume.h"
#include "exact/edge_multiplicity.h"
#include "gpu/compute_volume.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method_renderer.h"
#include "gpu/shadow_volume_geometry.h"
#include "gpu/stencil_shadow_renderer.h"
#include "pipeline/method_inputs.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/merged_soup.h"
#include "scene/scene_file.h"

namespace shadowcert::gpu::test {

inline const Light kPointLight{{1.5, 4.0, 2.5, 1.0}};
inline const Light kDirectionalLight{{0.3, 1.0, 0.2, 0.0}};

// The canonical soup and edge table of a test soup (pipeline/method_inputs.h, no cpu volumes).
using Prepared = MethodInputs;

inline Prepared prepare(const Soup& soup) {
  const std::array gpu_built{ShadowMethod::cs};
  return prepare_method_inputs(soup, {}, gpu_built);
}

inline Scene default_scene() {
  return load_scene(std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/default.json",
                    [](const std::filesystem::path& file) -> Soup {
                      throw std::runtime_error("default.json should need no mesh file: " + file.string());
                    });
}

// kShadowMethods that draw a shadow volume (all but shadowmap) and those of them that build it
// on the GPU (cs, gs, ts, pertri), in kShadowMethods' order.
inline std::vector<ShadowMethod> shadow_methods_where(bool (*keep)(ShadowMethod)) {
  std::vector<ShadowMethod> out;
  std::copy_if(kShadowMethods.begin(), kShadowMethods.end(), std::back_inserter(out), keep);
  return out;
}
inline const std::vector<ShadowMethod> kVolumeMethods = shadow_methods_where(draws_volume);
inline const std::vector<ShadowMethod> kGpuBuiltMethods = shadow_methods_where(builds_volume_on_gpu);

// The exact chain of `light` over p's canonical soup, both rounded to float as the GPU receives
// them, as the float triangles `render --method cpu` uploads (exact/cpu_volume.h): the
// reference volume.
inline HomogeneousMesh cpu_volume(const Prepared& p, const Light& light) {
  return cpu_volume_mesh(p.canonical.soup, p.table, light);
}

// What ShadowMethodRenderer needs to draw `light` alone over `receivers`, the casters being
// `p` (prepare() of the receivers' merged soup); cpu draws `*cpu` (cpu_volume(p, light); null
// for the other methods). The spans point into the arguments: construct the renderer while
// they live, and keep `*cpu` alive as long as the renderer (it reads the rest while constructed).
inline ShadowMethodScene one_light_scene(std::span<const ShadedSoupPart> receivers, const Prepared& p,
                                         const Light& light, const HomogeneousMesh* cpu) {
  ShadowMethodScene scene = method_scene(p, receivers, std::span(&light, 1));
  scene.cpu_volumes = cpu != nullptr ? std::span(cpu, 1) : std::span<const HomogeneousMesh>{};
  return scene;
}

// `method` (any of gpu/shadow_method_renderer.h's) rendering `soup` lit by `light` alone, every
// triangle a receiver (one part, default albedo) and a caster; `prepared` = prepare(soup). cpu
// draws `*cpu` (cpu_volume(prepared, light)), which must outlive the renderer; the other
// methods ignore it (null allowed). The renderer uploads and compiles everything it draws
// with, so its lifetime is that of every GL object the method needs. Throws as the
// ShadowMethodRenderer constructor (std::invalid_argument for cpu without a volume).
inline ShadowMethodRenderer one_light_renderer(ShadowMethod method, const Soup& soup, const Prepared& prepared,
                                               const Light& light, const HomogeneousMesh* cpu,
                                               StencilMethod stencil = StencilMethod::zfail) {
  const std::array parts{ShadedSoupPart{&soup}};
  ShadowMethodOptions options;
  options.stencil = stencil;
  return ShadowMethodRenderer(method, one_light_scene(parts, prepared, light, cpu), options);
}

// A scene ready for every method, as `shadowcert render` prepares it (pipeline/method_inputs.h):
// its casting meshes merged (merged_casters) as the casters; each mesh a receiver part, casting
// as it says; cpu's volume of each light. Set the camera's size before or after; change the
// lights only before (cpu_volumes follow them). Not copyable: `parts` point into `scene`.
struct PreparedScene {
  explicit PreparedScene(Scene s)
      : scene(std::move(s)), soup(merged_soup(scene)), casters(merged_casters(scene)),
        prepared(prepare_method_inputs(casters, scene.lights, kShadowMethods)) {
    for (const SceneMesh& mesh : scene.meshes) parts.push_back({&mesh.soup, ShadedSoupPart{}.albedo, mesh.casts});
  }
  PreparedScene(const PreparedScene&) = delete;
  PreparedScene& operator=(const PreparedScene&) = delete;

  // Every light (the renderer's cpu draws cpu_volumes).
  [[nodiscard]] ShadowMethodScene method_scene() const { return shadowcert::method_scene(prepared, parts, scene.lights); }
  // Light k alone; cpu draws `cpu` when given (it must outlive the renderer), else cpu_volumes[k].
  [[nodiscard]] ShadowMethodScene light_scene(std::size_t k, const HomogeneousMesh* cpu = nullptr) const {
    return shadowcert::light_scene(prepared, parts, scene.lights, k, cpu);
  }

  Scene scene;
  Soup soup;     // every mesh (merged_soup)
  Soup casters;  // the casting meshes (merged_casters)
  MethodInputs prepared;
  std::vector<ShadedSoupPart> parts;
  const std::vector<HomogeneousMesh>& cpu_volumes = prepared.cpu_volumes;
};

// A method's first-light stencil counts (z-fail) against cpu's, pixel by pixel.
struct StencilDifference {
  std::size_t differing = 0;  // pixels whose counts differ
  std::size_t shadowed = 0;   // pixels cpu counts non-zero
};

// `method` and cpu (the exact chain) drawing `soup` lit by `light` alone (one_light_renderer),
// seen by `camera`. Throws VolumeCapacityError when the method's volume overflowed.
inline StencilDifference stencil_difference_from_cpu(ShadowMethod method, const Soup& soup, const Light& light,
                                                     const Camera& camera) {
  const Prepared p = prepare(soup);
  const HomogeneousMesh cpu_mesh = cpu_volume(p, light);
  const OffscreenTarget target(camera.width, camera.height);
  const GrayImage cpu = one_light_renderer(ShadowMethod::cpu, soup, p, light, &cpu_mesh).render(target, camera).first_stencil;
  ShadowMethodRenderer renderer = one_light_renderer(method, soup, p, light, nullptr);
  const GrayImage counts = renderer.render(target, camera).first_stencil;
  renderer.check_capacity();
  StencilDifference out;
  for (std::size_t i = 0; i < cpu.pixels.size(); ++i) {
    out.differing += cpu.pixels[i] != counts.pixels.at(i);
    out.shadowed += cpu.pixels[i] != 0;
  }
  return out;
}

// `blades` triangles on the edge (0,0,0)-(0,1,0), apexes on the half circle x > 0 at y = 0.5,
// alternately flipped. With the light in the plane x = 0 every apex lies on one side of the
// plane (edge, light), so the edge's |m| is `blades` (docs/definitions.md#hard-cases: fans beyond one record,
// patch or invocation); nonmanifold_fan spreads its apexes all around and keeps |m| small.
inline Soup half_fan(std::uint32_t blades) {
  constexpr double kPi = 3.14159265358979323846;
  Soup fan;
  fan.vertices = {{0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  for (std::uint32_t i = 0; i < blades; ++i) {
    const double angle = -kPi / 2 + kPi * (i + 0.5) / blades;
    fan.vertices.push_back({std::cos(angle), 0.5, std::sin(angle)});
    fan.triangles.push_back(i % 2 == 0 ? Triangle{0, 1, i + 2} : Triangle{1, 0, i + 2});
  }
  return fan;
}

// half_fan(blades) and a 12 x 12 wall (two triangles) in the plane z = kHalfFanWallZ, behind the
// fan seen from kHalfFanLight (in the plane x = 0): it receives the fan's shadow.
inline constexpr double kHalfFanWallZ = 3.0;
inline const Light kHalfFanLight{{0.0, 0.5, -5.0, 1.0}};
inline Soup half_fan_and_wall(std::uint32_t blades) {
  constexpr double h = 6.0;
  Soup wall;
  wall.vertices = {{-h, -h, kHalfFanWallZ}, {h, -h, kHalfFanWallZ}, {h, h, kHalfFanWallZ}, {-h, h, kHalfFanWallZ}};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  Soup soup = half_fan(blades);
  append_soup(soup, wall);
  return soup;
}

// The soups a per-method test runs over, each with a name for traces.
using NamedSoups = std::vector<std::pair<std::string, Soup>>;

// For every soup of `soups` and light of `lights`: one `Volume` (ComputeShadowVolume,
// PerTriangleShadowVolume, or the record methods GeometryShaderShadowVolume and
// TessellationShadowVolume, which also take the edge table) per soup, on the uploaded soup,
// built for each light in turn; `check(volume, prepared, light)` runs after each build inside
// a SCOPED_TRACE naming the soup and the light's kind.
template <class Volume, class Check>
void for_each_build(const NamedSoups& soups, std::initializer_list<Light> lights, Check check,
                    SignMode sign = SignMode::exact) {
  for (const auto& [name, soup] : soups) {
    const Prepared p = prepare(soup);
    const ComputeVolumeSoup gpu_soup(p.canonical.soup, p.table);
    Volume volume = [&] {
      if constexpr (std::is_constructible_v<Volume, const ComputeVolumeSoup&, const EdgeTable&, SignMode>) {
        return Volume(gpu_soup, p.table, sign);
      } else {
        return Volume(gpu_soup, sign);
      }
    }();
    for (const Light& light : lights) {
      SCOPED_TRACE(name + (light.directional() ? ", directional" : ", point"));
      volume.build(light);
      check(volume, p, light);
    }
  }
}

// A multiplicity computation's triangle signs s(t) as the ints the GPU methods store.
inline std::vector<std::int32_t> triangle_signs(const EdgeMultiplicities& m) {
  std::vector<std::int32_t> out;
  out.reserve(m.triangle_sign.size());
  for (Sign s : m.triangle_sign) out.push_back(to_int(s));
  return out;
}

// Every directed edge (a, b) of the welded triangles minus its reverse: zero when closed.
inline std::map<std::pair<std::uint32_t, std::uint32_t>, int> unbalanced_edges(const std::vector<VolumeTriangle>& triangles) {
  std::map<std::array<std::uint32_t, 4>, std::uint32_t> ids;  // bitwise weld of vec4 vertices
  auto id = [&ids](const Vec4f& x) {
    const std::array<std::uint32_t, 4> bits{std::bit_cast<std::uint32_t>(x[0]), std::bit_cast<std::uint32_t>(x[1]),
                                            std::bit_cast<std::uint32_t>(x[2]), std::bit_cast<std::uint32_t>(x[3])};
    return ids.emplace(bits, static_cast<std::uint32_t>(ids.size())).first->second;
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> balance;
  for (const VolumeTriangle& t : triangles) {
    const std::array<std::uint32_t, 3> v{id(t[0]), id(t[1]), id(t[2])};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      if (a == b) continue;  // a degenerate triangle's collapsed edge bounds nothing
      balance[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
    }
  }
  std::erase_if(balance, [](const auto& entry) { return entry.second == 0; });
  return balance;
}

// What `volume` drew after its last build, read back: every vertex it asked for (no
// overflow), at least one triangle, and closed (unbalanced_edges empty). Returns the triangles.
template <class Volume>
std::vector<VolumeTriangle> expect_drawn_closed(const Volume& volume) {
  std::vector<VolumeTriangle> triangles = volume.read_triangles();
  EXPECT_EQ(triangles.size() * 3, volume.read_requested_vertices());
  EXPECT_FALSE(triangles.empty());
  EXPECT_TRUE(unbalanced_edges(triangles).empty());
  return triangles;
}

}  // namespace shadowcert::gpu::test
