#pragma once
// One GL method and one light of a scene against the exact image over a window of pixels: what
// the hard-scene campaign (campaign/gl_campaign.h) shrinks a failure with. At 1024x768 the two
// exact images of pipeline/scene_comparison.h's compare_scene (the scene and its float rounding)
// cost seconds even for a few triangles, and shrinking calls it hundreds of times; the failure
// is a few pixels, so only the pixels around them are imaged (ExactImageOptions::window). The
// frame is the whole image, drawn exactly as compare_scene draws it (the scene in its eye's
// frame, z-fail, the light alone), and each pixel of the window gets the verdict compare_scene
// gives it; the volume's closure is certified as there.
#include <cstddef>
#include <cstdint>

#include "core/scene.h"
#include "gpu/shadow_method_renderer.h"
#include "pipeline/scene_comparison.h"
#include "reference/exact_image.h"

namespace shadowcert {

// Light `light` of `scene` drawn alone by `method` (its options' sign; z-fail) and compared with
// the exact image over `window` (inside the camera's image); the pixels outside it are ambiguous
// (kOutsideWindow). Needs a current GL context. Throws std::invalid_argument
// ("compare_in_window: ...") for a light out of range, and what compare_scene throws.
[[nodiscard]] LightRun compare_in_window(const Scene& scene, gpu::ShadowMethod method, std::size_t light,
                                         const PixelWindow& window, const gpu::ShadowMethodOptions& options = {});

}  // namespace shadowcert
