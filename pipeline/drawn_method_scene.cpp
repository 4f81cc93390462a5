#include "pipeline/drawn_method_scene.h"

#include <array>
#include <stdexcept>
#include <string>

#include "core/eye_frame.h"
#include "pipeline/mesh_palette.h"
#include "scene/merged_soup.h"

namespace shadowcert {

gpu::ShadowMethodScene DrawnMethodScene::method_scene() const {
  return shadowcert::method_scene(inputs, parts, scene.lights);
}

gpu::HostShadowOptions DrawnMethodScene::host_options() const {
  gpu::HostShadowOptions o;
  o.light_stencil = light_stencil;
  return o;
}

gpu::ShadowMethodOptions DrawnMethodScene::renderer_options() const {
  gpu::ShadowMethodOptions o;
  o.light_stencil = light_stencil;
  return o;
}

std::unique_ptr<DrawnMethodScene> prepare_drawn_method_scene(const Scene& world, gpu::ShadowMethod method,
                                                            StencilChoice stencil, const SilhouetteOptions& silhouette) {
  if (world.lights.empty()) throw std::invalid_argument("prepare_drawn_method_scene: the scene has no light");
  auto d = std::make_unique<DrawnMethodScene>();
  d->method = method;
  d->scene = eye_relative_scene(world);
  d->merged = merged_soup(d->scene);
  if (d->merged.triangles.empty()) throw std::invalid_argument("prepare_drawn_method_scene: no triangle");
  d->casters = merged_casters(d->scene);
  d->parts = shaded_parts(d->scene);
  const std::array methods{method};
  d->inputs = prepare_method_inputs(d->casters, d->scene.lights, methods);
  bool silhouette_method = gpu::is_silhouette_method(method);
  if (silhouette_method) {
    SilhouetteOptions o = silhouette;
    o.near_plane = d->scene.camera.near_plane;  // the scene is in the eye's frame
    const SilhouetteVolumes v = silhouette_volumes(d->scene.meshes, d->scene.lights, method, o);
    d->inputs.cpu_volumes = v.per_light;
    d->inputs.smooth_casters = v.gpu_casters;
  }
  // smoothie: every light's smoothies, once, with the default width and space (as render).
  if (method == gpu::ShadowMethod::smoothie)
    add_smoothies(d->inputs, d->scene.lights, gpu::soup_bounds(d->merged), SceneSmoothieOptions{});
  if (!gpu::draws_volume(method)) return d;  // the shadow maps count nothing: no stencil method
  // As render: the proof is about the exact chain, so a smooth-silhouette volume is counted with z-fail.
  d->light_stencil = stencil_methods(
      choose_stencil(silhouette_method ? StencilChoice::zfail : stencil, d->inputs, d->scene.lights, d->scene.camera));
  return d;
}

}  // namespace shadowcert
