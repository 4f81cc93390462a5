#include "pipeline/ray_traced_comparison.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/pixel_ray.h"
#include "core/vector3.h"
#include "pipeline/mesh_palette.h"
#include "pipeline/soft_shadow_comparison.h"
#include "reference/pixel_comparison.h"
#include "scene/merged_soup.h"

namespace shadowcert {
namespace {

// Per merged triangle, the scene mesh it came from (merged_soup keeps the meshes' order).
std::vector<std::uint32_t> triangle_meshes(const Scene& scene) {
  std::vector<std::uint32_t> meshes;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    meshes.insert(meshes.end(), scene.meshes[m].soup.triangles.size(), static_cast<std::uint32_t>(m));
  return meshes;
}

std::uint8_t to_byte(double x) { return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); }

}  // namespace

std::uint64_t RayTracedRun::sum(std::uint64_t PixelComparison::*figure) const {
  std::uint64_t n = 0;
  for (const LightRun& l : lights) n += l.comparison.*figure;
  return n;
}

raytrace::RayTracedImageOptions ray_traced_options(const Scene& scene, RayTracedMethod method, unsigned threads) {
  raytrace::RayTracedImageOptions options;
  options.mode = ray_traced_entry(method).mode;
  options.threads = threads;
  if (!std::all_of(scene.meshes.begin(), scene.meshes.end(), [](const SceneMesh& m) { return m.casts; }))
    options.casts = casting_triangles(scene);
  return options;
}

raytrace::RayTracedImage ray_traced_scene_image(const Scene& scene, RayTracedMethod method, unsigned threads) {
  return raytrace::ray_traced_image(merged_soup(scene), scene.lights, scene.camera,
                                    ray_traced_options(scene, method, threads));
}

gpu::StencilShadowFrame ray_traced_frame(const Scene& scene, const raytrace::RayTracedImage& image, std::size_t light,
                                         std::span<const float> soft_light) {
  const std::size_t pixels = std::size_t{image.width} * image.height;
  if (light >= image.lit.size())
    throw std::invalid_argument("ray_traced_frame: light " + std::to_string(light) + " of " +
                                std::to_string(image.lit.size()));
  if (image.hit_triangles.size() != pixels || (!soft_light.empty() && soft_light.size() != pixels))
    throw std::invalid_argument("ray_traced_frame: the images' sizes disagree");
  const Soup merged = merged_soup(scene);
  const std::vector<std::uint32_t> meshes = triangle_meshes(scene);
  const gpu::StencilShadowOptions shading;  // the GL frame's ambient and light colours
  const CameraFrame camera = camera_frame(scene.camera, "ray_traced_frame");
  gpu::StencilShadowFrame frame;
  frame.colour = gpu::RgbaImage(image.width, image.height);
  frame.first_stencil = gpu::GrayImage(image.width, image.height);
  frame.first_lit_mask = gpu::GrayImage(image.width, image.height);
  frame.first_light.assign(pixels, gpu::kUncoveredLight);
  for (std::size_t p = 0; p < pixels; ++p) {
    const std::uint32_t t = image.hit_triangles[p];
    if (t == raytrace::kMissed) continue;
    frame.first_lit_mask.pixels[p] = image.lit[light][p];
    frame.first_light[p] = soft_light.empty() ? (image.lit[light][p] != 0 ? 1.0f : 0.0f) : soft_light[p];
    // The face normal, turned towards the eye (two-sided, as the GL shader).
    const Triangle& tri = merged.triangles[t];
    const Vec3& a = merged.vertices[tri[0]];
    const Vec3 u{merged.vertices[tri[1]][0] - a[0], merged.vertices[tri[1]][1] - a[1], merged.vertices[tri[1]][2] - a[2]};
    const Vec3 v{merged.vertices[tri[2]][0] - a[0], merged.vertices[tri[2]][1] - a[1], merged.vertices[tri[2]][2] - a[2]};
    Vec3 n = cross(u, v);
    const double n_length = std::sqrt(dot(n, n));
    const Vec3 to_eye{camera.eye[0] - a[0], camera.eye[1] - a[1], camera.eye[2] - a[2]};
    if (dot(n, to_eye) < 0.0) n = {-n[0], -n[1], -n[2]};
    const std::array<float, 3>& albedo = kMeshPalette[meshes[t] % kMeshPalette.size()];
    std::array<double, 3> colour{};
    for (int c = 0; c < 3; ++c) colour[c] = shading.ambient[c];
    for (std::size_t k = 0; k < scene.lights.size(); ++k) {
      if (image.lit[k][p] == 0 || n_length == 0.0) continue;
      const Light& l = scene.lights[k];
      const Vec3 d = l.directional() ? Vec3{l.position[0], l.position[1], l.position[2]}
                                     : Vec3{l.position[0] - a[0], l.position[1] - a[1], l.position[2] - a[2]};
      const double d_length = std::sqrt(dot(d, d));
      if (d_length == 0.0) continue;
      const double lambert = std::max(dot(n, d) / (n_length * d_length), 0.0);
      for (int c = 0; c < 3; ++c) colour[c] += shading.light_colour[c] * lambert;
    }
    std::uint8_t* out = frame.colour.at(static_cast<std::uint32_t>(p % image.width), static_cast<std::uint32_t>(p / image.width));
    for (int c = 0; c < 3; ++c) out[c] = to_byte(albedo[c] * colour[c]);
    out[3] = 255;
  }
  return frame;
}

RayTracedRun compare_ray_traced(const Scene& scene, RayTracedMethod method, const ExactImage& exact,
                                std::span<const SoftReference> soft, unsigned threads) {
  const Soup merged = merged_soup(scene);
  const raytrace::RayTracedImageOptions options = ray_traced_options(scene, method, threads);
  const raytrace::RayTracedImage image = raytrace::ray_traced_image(merged, scene.lights, scene.camera, options);
  RayTracedRun run;
  run.method = method;
  run.build_seconds = image.stats.build_seconds;
  run.trace_seconds = image.stats.trace_seconds;
  std::vector<std::uint8_t> covered(image.hit_triangles.size());
  for (std::size_t p = 0; p < covered.size(); ++p) covered[p] = image.hit_triangles[p] != raytrace::kMissed ? 255 : 0;
  for (std::size_t k = 0; k < scene.lights.size(); ++k) {
    LightRun l;
    // rt's own K-sample soft image of the reference's very sample lights (reference/disk_light.h).
    std::vector<float> soft_light;
    if (!soft.empty()) {
      const raytrace::RayTracedSoftImage s =
          raytrace::ray_traced_soft_image(merged, soft[k].image.samples, scene.camera, options);
      run.soft_build_seconds += s.stats.build_seconds;
      run.soft_trace_seconds += s.stats.trace_seconds;
      soft_light = s.light;
    }
    l.frame = ray_traced_frame(scene, image, k, soft_light);
    const RenderedPixels rendered{image.width, image.height, covered, image.lit[k], {}};
    l.comparison = compare_pixels(exact, k, rendered);
    l.gl_ms = run.ms() / static_cast<double>(scene.lights.size());
    if (!soft.empty()) l.soft = compare_soft_shadow(soft[k], soft_light);
    run.lights.push_back(std::move(l));
  }
  return run;
}

}  // namespace shadowcert
