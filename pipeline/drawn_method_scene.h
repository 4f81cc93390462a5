#pragma once
// A scene prepared for one GL method exactly as `shadowcert render` prepares it with its default
// options (cli/render_command.cpp, steps 2 and 3): in its eye's frame (core/eye_frame.h), every
// mesh a receiver, the casters' canonical soup and edge table, cpu's exact chains or the
// smooth-silhouette volumes or smoothie's smoothies, and each light's stencil method (the volume
// methods). What the host layer's users in this tree (the viewer `shadowcert view`, the host
// tests) hand to gpu/host_shadow_volumes.h, and what the Python module's render draws, so that
// their frames equal render's.
//
//   auto d = prepare_drawn_method_scene(scene, gpu::ShadowMethod::cs, StencilChoice::zfail);
//   gpu::HostShadowVolumes shadows(d->method, d->method_scene(), d->host_options());
#include <memory>
#include <vector>

#include "core/scene.h"
#include "core/soup.h"
#include "gpu/host_shadow_volumes.h"
#include "gpu/shadow_method_renderer.h"
#include "pipeline/method_inputs.h"
#include "pipeline/silhouette_volumes.h"
#include "pipeline/stencil_choice.h"

namespace shadowcert {

struct DrawnMethodScene {
  gpu::ShadowMethod method = gpu::ShadowMethod::cpu;
  Scene scene;   // in its eye's frame: the camera's eye at the origin
  Soup merged;   // every mesh: the receivers (scene/merged_soup.h)
  Soup casters;  // the meshes that cast
  std::vector<gpu::ShadedSoupPart> parts;  // the receivers with their colours (pipeline/mesh_palette.h)
  MethodInputs inputs;
  std::vector<gpu::StencilMethod> light_stencil;  // one per light

  // The renderer's and the host layer's view; points into this object.
  [[nodiscard]] gpu::ShadowMethodScene method_scene() const;
  [[nodiscard]] gpu::HostShadowOptions host_options() const;
  [[nodiscard]] gpu::ShadowMethodOptions renderer_options() const;
};

// `scene` in world coordinates with at least one light and one triangle; `method` any GL method
// (the host layer takes the volume methods, gpu::draws_volume, only; light_stencil is empty for
// the others). Throws std::invalid_argument("prepare_drawn_method_scene: ...")
// otherwise, and what prepare_method_inputs, silhouette_volumes and choose_stencil throw.
// Held by pointer: its spans point into it.
[[nodiscard]] std::unique_ptr<DrawnMethodScene> prepare_drawn_method_scene(const Scene& scene, gpu::ShadowMethod method,
                                                                         StencilChoice stencil,
                                                                         const SilhouetteOptions& silhouette = {});

}  // namespace shadowcert
