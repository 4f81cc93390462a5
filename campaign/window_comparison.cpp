#include "campaign/window_comparison.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "core/eye_frame.h"
#include "gpu/depth_precision.h"
#include "gpu/offscreen_target.h"
#include "pipeline/mesh_palette.h"
#include "pipeline/method_inputs.h"
#include "reference/input_rounding.h"
#include "scene/merged_soup.h"

namespace shadowcert {

LightRun compare_in_window(const Scene& scene, gpu::ShadowMethod method, std::size_t light, const PixelWindow& window,
                           const gpu::ShadowMethodOptions& options) {
  if (light >= scene.lights.size()) throw std::invalid_argument("compare_in_window: no such light");
  Scene one = scene;  // the light alone, as compare_scene renders each light
  one.lights = {scene.lights[light]};
  const Soup merged = merged_soup(one);
  if (merged.triangles.empty()) throw std::invalid_argument("compare_in_window: the scene has no triangle");

  // compare_scene's reference (pipeline/scene_comparison.h reference_image) over the window: the
  // GL depth band of the camera's near plane, the casting meshes, the float-rounded scene's marks.
  ExactImageOptions exact_options;
  exact_options.depth_band = [near = one.camera.near_plane](double view_depth) {
    return gpu::depth_band(view_depth, near);
  };
  if (!std::all_of(one.meshes.begin(), one.meshes.end(), [](const SceneMesh& m) { return m.casts; }))
    exact_options.casts = casting_triangles(one);
  exact_options.window = window;
  const ExactImage exact = exact_image_of_float_input(merged, one.lights, one.camera, exact_options);

  // compare_scene's frame: the scene in its eye's frame, z-fail.
  const Scene drawn = eye_relative_scene(one);
  const std::vector<gpu::ShadowMethod> methods{method};
  const MethodInputs inputs = prepare_method_inputs(merged_casters(drawn), drawn.lights, methods);
  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(drawn);
  const gpu::OffscreenTarget target(one.camera.width, one.camera.height);
  gpu::ShadowMethodOptions method_options = options;
  method_options.stencil = gpu::StencilMethod::zfail;
  method_options.light_stencil.clear();
  gpu::ShadowMethodRenderer renderer(method, light_scene(inputs, parts, drawn.lights, 0), method_options);
  return compare_light(renderer, exact, 0, target, drawn.camera);
}

}  // namespace shadowcert
