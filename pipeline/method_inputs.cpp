#include "pipeline/method_inputs.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "exact/cpu_volume.h"

namespace shadowcert {

MethodInputs prepare_method_inputs(const Soup& casters, std::span<const Light> lights,
                                   std::span<const gpu::ShadowMethod> methods) {
  MethodInputs inputs;
  if (std::any_of(methods.begin(), methods.end(), gpu::draws_volume) ||
      std::find(methods.begin(), methods.end(), gpu::ShadowMethod::smoothie) != methods.end()) {
    inputs.canonical = canonical_soup(casters);
    inputs.table = build_edge_table(inputs.canonical.soup);
  }
  if (std::find(methods.begin(), methods.end(), gpu::ShadowMethod::cpu) != methods.end())
    add_cpu_volumes(inputs, lights);
  return inputs;
}

void add_cpu_volumes(MethodInputs& inputs, std::span<const Light> lights) {
  if (!inputs.cpu_volumes.empty()) throw std::logic_error("add_cpu_volumes: the inputs have cpu volumes already");
  inputs.cpu_volumes.reserve(lights.size());
  for (const Light& light : lights)
    inputs.cpu_volumes.push_back(cpu_volume_mesh(inputs.canonical.soup, inputs.table, light));
}

void add_smoothies(MethodInputs& inputs, std::span<const Light> lights, const gpu::SceneBounds& bounds,
                   const SceneSmoothieOptions& options) {
  if (!inputs.smoothies.per_light.empty()) throw std::logic_error("add_smoothies: the inputs have smoothies already");
  inputs.smoothies = scene_smoothies(inputs.canonical.soup, inputs.table, lights, bounds, options);
}

gpu::ShadowMethodScene method_scene(const MethodInputs& inputs, std::span<const gpu::ShadedSoupPart> receivers,
                                    std::span<const Light> lights) {
  gpu::ShadowMethodScene scene;
  scene.receivers = receivers;
  scene.lights = lights;
  scene.canonical = &inputs.canonical.soup;
  scene.table = &inputs.table;
  scene.cpu_volumes = inputs.cpu_volumes;
  scene.smooth_casters = &inputs.smooth_casters;
  scene.smoothies = inputs.smoothies.per_light;
  return scene;
}

gpu::ShadowMethodScene light_scene(const MethodInputs& inputs, std::span<const gpu::ShadedSoupPart> receivers,
                                   std::span<const Light> lights, std::size_t k, const HomogeneousMesh* cpu,
                                   const gpu::SmoothCasterArrays* smooth) {
  if (k >= lights.size())
    throw std::out_of_range("light_scene: light " + std::to_string(k) + " of " + std::to_string(lights.size()));
  gpu::ShadowMethodScene scene = method_scene(inputs, receivers, lights.subspan(k, 1));
  if (cpu != nullptr)
    scene.cpu_volumes = std::span<const HomogeneousMesh>(cpu, 1);
  else if (k < inputs.cpu_volumes.size())
    scene.cpu_volumes = std::span<const HomogeneousMesh>(&inputs.cpu_volumes[k], 1);
  else
    scene.cpu_volumes = {};
  if (smooth != nullptr) scene.smooth_casters = smooth;
  if (k < inputs.smoothies.per_light.size())
    scene.smoothies = std::span<const SmoothieMesh>(&inputs.smoothies.per_light[k], 1);
  else
    scene.smoothies = {};
  return scene;
}

}  // namespace shadowcert
