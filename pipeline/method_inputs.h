#pragma once
// What every method of gpu/shadow_method_renderer.h needs of a scene's casters, prepared once
// and in one place for `render`, `diff`, `fuzz --gl`, bench/render_bench and the GL tests, so
// that "scene S by method M" starts from the same data everywhere:
//   - the canonical soup of the casters (scene/canonical_soup.h) and its edge table
//     (scene/edge_table.h), which cs, gs, ts and pertri upload;
//   - for cpu, one exact chain per light of the float-rounded input, as homogeneous floats
//     (exact/cpu_volume.h);
//   - for smoothie, one smoothie mesh per light (pipeline/scene_smoothies.h, add_smoothies).
//
//   MethodInputs in = prepare_method_inputs(merged_soup(scene), scene.lights, methods);
//   gpu::ShadowMethodRenderer r(method, method_scene(in, shaded_parts(scene), scene.lights));
#include <cstddef>
#include <span>
#include <vector>

#include "core/homogeneous_mesh.h"
#include "core/light.h"
#include "core/soup.h"
#include "gpu/shadow_method_renderer.h"
#include "gpu/smooth_silhouette_volume.h"
#include "pipeline/scene_smoothies.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"

namespace shadowcert {

struct MethodInputs {
  CanonicalSoup canonical;  // of the casters; empty when no method draws a volume
  EdgeTable table;          // build_edge_table(canonical.soup)
  // cpu only: cpu_volume_mesh(canonical.soup, table, lights[k]) for every light k, in order;
  // empty when cpu is not among the methods.
  std::vector<HomogeneousMesh> cpu_volumes;
  // smooth-gpu only: the casters the GPU builds the smooth volume of (the caller's:
  // pipeline/silhouette_volumes.h's gpu_casters); empty otherwise.
  gpu::SmoothCasterArrays smooth_casters;
  // smoothie only: every light's smoothies (add_smoothies); empty otherwise.
  SceneSmoothies smoothies;
};

// `casters`: every caster triangle of the scene in one soup (scene/merged_soup.h), indices in
// range; `lights`: as core/light.h's Light::defined(); `methods`: the methods that will draw.
// Builds the canonical soup and table when a method draws a volume (all but the shadow-map
// methods) or is smoothie (its silhouette edges), and the cpu volumes when cpu is listed. Throws std::invalid_argument from canonical_soup and
// cpu_volume_mesh on input outside those preconditions.
[[nodiscard]] MethodInputs prepare_method_inputs(const Soup& casters, std::span<const Light> lights,
                                                 std::span<const gpu::ShadowMethod> methods);

// Adds cpu's volumes for `lights` to inputs prepared for a volume method but without cpu (the
// render benchmark prepares the 1M grid once and builds cpu's chain only when cpu runs). Throws
// std::logic_error when `inputs` has cpu volumes already, and as prepare_method_inputs otherwise.
void add_cpu_volumes(MethodInputs& inputs, std::span<const Light> lights);

// Adds the smoothies of `lights` (those `inputs` was prepared with, smoothie among its methods)
// to `inputs`: scene_smoothies of its canonical soup and table, with `bounds` the scene's (every
// receiver's, gpu::soup_bounds of the merged soup). Throws std::logic_error when `inputs` has
// smoothies already, and what scene_smoothies throws.
void add_smoothies(MethodInputs& inputs, std::span<const Light> lights, const gpu::SceneBounds& bounds,
                   const SceneSmoothieOptions& options = {});

// The renderer's view of `inputs` for every light of `lights` (those `inputs` was prepared
// with). The result points into `inputs`, `receivers` and `lights`: the renderer reads all but
// the cpu volumes while it is constructed, and the cpu volumes while it lives.
[[nodiscard]] gpu::ShadowMethodScene method_scene(const MethodInputs& inputs,
                                                  std::span<const gpu::ShadedSoupPart> receivers,
                                                  std::span<const Light> lights);

// Light `k` of `lights` alone; cpu draws `*cpu` when given (a planted volume, say), else
// inputs.cpu_volumes[k] when there is one; smoothie draws inputs.smoothies' k-th mesh when there is one; smooth-gpu builds `*smooth` when given, else
// inputs.smooth_casters. Throws std::out_of_range for k outside `lights`.
[[nodiscard]] gpu::ShadowMethodScene light_scene(const MethodInputs& inputs,
                                                 std::span<const gpu::ShadedSoupPart> receivers,
                                                 std::span<const Light> lights, std::size_t k,
                                                 const HomogeneousMesh* cpu = nullptr,
                                                 const gpu::SmoothCasterArrays* smooth = nullptr);

}  // namespace shadowcert
