#pragma once
// The ray-traced methods (rt, rt-robust: pipeline/method_registry.h's RayTracedMethod,
// docs/ray-tracing.md) on a scene, as a GL method is on it (pipeline/scene_comparison.h): the
// Embree image of the scene's world-space soup (every mesh receives, the meshes that cast cast),
// its pictures in the shape of a GL frame (so that diff's and bench's pictures, overlays and
// soft error images are the same code), and each light's lit mask against the exact image.
//
//   const RayTracedRun run = compare_ray_traced(scene, RayTracedMethod::rt_robust, exact, soft, 2);
//   run.sum(&PixelComparison::hard_errors)   // rt's error: reported, never a failure
#include <cstddef>
#include <span>
#include <vector>

#include "core/scene.h"
#include "gpu/stencil_shadow_renderer.h"
#include "pipeline/method_registry.h"
#include "pipeline/scene_comparison.h"
#include "pipeline/soft_reference.h"
#include "raytrace/ray_traced_image.h"
#include "reference/exact_image.h"

namespace shadowcert {

// The ray tracer's options for `method` on `scene`: its build mode, the scene's casting flags
// (empty when every mesh casts) and `threads`.
[[nodiscard]] raytrace::RayTracedImageOptions ray_traced_options(const Scene& scene, RayTracedMethod method,
                                                                 unsigned threads = 0);

// The hard image of `scene` (merged_soup, world space, as the exact image) by `method`.
// Throws what raytrace::ray_traced_image throws.
[[nodiscard]] raytrace::RayTracedImage ray_traced_scene_image(const Scene& scene, RayTracedMethod method,
                                                              unsigned threads = 0);

// Light `light` of `image` (ray_traced_scene_image of `scene`) as a GL frame holds it: colour
// shaded as gpu/stencil_shadow_renderer.h shades (each mesh's palette colour, ambient plus the
// lit lights' two-sided Lambert term of the face normal; alpha 255 where the centre ray hits),
// first_lit_mask rt's lit mask, first_stencil empty-valued (0), first_light 1/0 where hit
// (lit/shadowed) or `soft_light` (rt's K-sample light, when given), kNoLight elsewhere. A picture
// for the pictures' code; nothing is decided from its colours. Throws std::invalid_argument
// ("ray_traced_frame: ...") for a light out of range or sizes that disagree.
[[nodiscard]] gpu::StencilShadowFrame ray_traced_frame(const Scene& scene, const raytrace::RayTracedImage& image,
                                                       std::size_t light,
                                                       std::span<const float> soft_light = {});

// `method` on `scene` against `exact` (reference_image of the scene, its camera's size): per
// light the lit mask compared as a mask-only method's (coverage: the centre ray hits), and with
// `soft` (one SoftReference per light, or empty) rt's soft image of the reference's own sample
// lights against it. Throws what the ray tracer and compare_pixels throw.
[[nodiscard]] RayTracedRun compare_ray_traced(const Scene& scene, RayTracedMethod method, const ExactImage& exact,
                                              std::span<const SoftReference> soft = {}, unsigned threads = 0);

}  // namespace shadowcert
