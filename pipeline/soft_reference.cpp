#include "pipeline/soft_reference.h"

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/box.h"
#include "core/pixel_ray.h"
#include "core/vector3.h"
#include "exact/box_tree.h"
#include "exact/light_orientation.h"
#include "scene/merged_soup.h"

namespace shadowcert {
namespace {

// The distance from p to the segment [a, b] (a point when a == b), in double.
double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = difference(b, a), ap = difference(p, a);
  const double length2 = dot(ab, ab);
  const double t = length2 > 0.0 ? std::clamp(dot(ap, ab) / length2, 0.0, 1.0) : 0.0;
  const Vec3 d{ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
  return std::sqrt(dot(d, d));
}

// The distance from p to the closed triangle abc (any shape, degenerate included), in double:
// to the plane when p projects inside, else to the nearest edge.
double triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(difference(b, a), difference(c, a));
  const double n2 = dot(n, n);
  if (n2 > 0.0) {
    const bool inside = dot(cross(difference(b, a), difference(p, a)), n) >= 0.0 &&
                        dot(cross(difference(c, b), difference(p, b)), n) >= 0.0 &&
                        dot(cross(difference(a, c), difference(p, c)), n) >= 0.0;
    if (inside) return std::abs(dot(difference(p, a), n)) / std::sqrt(n2);
  }
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

std::vector<Box> casting_boxes(const Soup& soup, std::span<const std::uint8_t> casts) {
  std::vector<Box> boxes(soup.triangles.size());
  for (std::size_t t = 0; t < boxes.size(); ++t) {
    const Triangle& tri = soup.triangles[t];
    if (!casts.empty() && casts[t] == 0) {
      // A box no query reaches: a point at the first vertex, skipped by the visitor anyway.
      boxes[t] = {soup.vertices[tri[0]], soup.vertices[tri[0]]};
      continue;
    }
    boxes[t] = bounding_box({soup.vertices[tri[0]], soup.vertices[tri[1]], soup.vertices[tri[2]]});
  }
  return boxes;
}

// The bar of `shadowcert soft` on stderr, in scene_comparison.cpp's style.
void print_progress(std::string_view stage, std::uint64_t done, std::uint64_t total) {
  constexpr int kBarWidth = 32;
  const double fraction = total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total);
  const auto filled = static_cast<std::size_t>(fraction * kBarWidth);
  fmt::print(stderr, "\rsoft reference, {:<7} [{}{}] {:3.0f}%", stage, std::string(filled, '#'),
             std::string(kBarWidth - filled, '.'), 100.0 * fraction);
  if (done >= total) fmt::print(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace

std::vector<std::uint8_t> contact_pixels(const Soup& soup, std::span<const std::uint8_t> casts, const Camera& camera,
                                         const SoftShadowImage& image, double contact_pixels) {
  if (!std::isfinite(contact_pixels) || contact_pixels < 0.0)
    throw std::invalid_argument("contact_pixels: the distance in pixels must be finite and >= 0, got " +
                                std::to_string(contact_pixels));
  if (image.width != camera.width || image.height != camera.height || image.hit_triangles.size() != image.pixels())
    throw std::invalid_argument("contact_pixels: the image is not of the camera's size");
  if (!casts.empty() && casts.size() != soup.triangles.size())
    throw std::invalid_argument("contact_pixels: casts has " + std::to_string(casts.size()) + " flags for " +
                                std::to_string(soup.triangles.size()) + " triangles");
  for (std::uint32_t h : image.hit_triangles)
    if (h != kNoHit && h >= soup.triangles.size())
      throw std::invalid_argument("contact_pixels: a hit triangle is out of range");
  std::vector<std::uint8_t> contact(image.pixels(), 0);
  if (contact_pixels == 0.0 || soup.triangles.empty()) return contact;

  const CameraFrame frame = camera_frame(camera, "contact_pixels");
  const detail::BoxTree tree(casting_boxes(soup, casts), detail::LeafTest::exact);
  const auto vertex = [&](std::uint32_t t, int k) -> const Vec3& {
    return soup.vertices[soup.triangles[t][static_cast<std::size_t>(k)]];
  };
  const double pixel_per_depth = 2.0 * frame.half_height / camera.height;  // a pixel's side at depth 1
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, camera.height), [&](const auto& rows) {
    for (std::uint32_t r = rows.begin(); r != rows.end(); ++r)
      for (std::uint32_t i = 0; i < camera.width; ++i) {
        const std::size_t p = std::size_t{r} * camera.width + i;
        if (image.region(p) != SoftRegion::umbra || image.faces_light[p] == 0) continue;
        const std::uint32_t h = image.hit_triangles[p];
        const Vec3 &a = vertex(h, 0), &b = vertex(h, 1), &c = vertex(h, 2);
        // P: the centre ray against the hit triangle's plane, in double.
        const PixelRay ray = pixel_ray(frame, i + 0.5, r + 0.5);
        const Vec3 n = cross(difference(b, a), difference(c, a));
        const double t = dot(n, difference(a, ray.origin)) / dot(n, ray.direction);
        const Vec3 point{ray.origin[0] + t * ray.direction[0], ray.origin[1] + t * ray.direction[1],
                         ray.origin[2] + t * ray.direction[2]};
        const double distance = contact_pixels * pixel_per_depth * dot(difference(point, frame.eye), frame.forward);
        if (!(distance > 0.0) || !std::isfinite(distance)) continue;
        const HomogeneousPoint ha = finite_point(a), hb = finite_point(b), hc = finite_point(c);
        bool near = false;
        tree.dilated_segment_query(point, {point[0] + distance, point[1], point[2]}, {distance, distance, distance},
                                   [&](std::uint32_t id) {
                                     if (id == h || (!casts.empty() && casts[id] == 0)) return true;
                                     bool in_plane = true;  // exact: all three vertices on the hit plane
                                     for (int k = 0; k < 3 && in_plane; ++k)
                                       in_plane = orient(ha, hb, hc, finite_point(vertex(id, k))) == Sign::zero;
                                     if (in_plane) return true;
                                     if (triangle_distance(point, vertex(id, 0), vertex(id, 1), vertex(id, 2)) > distance)
                                       return true;
                                     near = true;
                                     return false;
                                   });
        contact[p] = near ? 1 : 0;
      }
  });
  return contact;
}

SoftReference soft_reference(const Scene& scene, std::size_t light, const SoftReferenceOptions& options) {
  if (light >= scene.lights.size())
    throw std::invalid_argument("soft_reference: light " + std::to_string(light) + " of a scene with " +
                                std::to_string(scene.lights.size()) + " light(s)");
  const Soup soup = merged_soup(scene);
  SoftShadowOptions soft;
  if (!std::all_of(scene.meshes.begin(), scene.meshes.end(), [](const SceneMesh& m) { return m.casts; }))
    soft.casts = casting_triangles(scene);
  if (options.progress) soft.progress = print_progress;
  SoftReference reference;
  reference.image = disk_light_shadow_image(soup, scene.lights[light], options.sampling, scene.camera, soft);
  reference.hard = (scene.lights[light].directional() ? options.sampling.angle_degrees : options.sampling.radius) == 0.0;
  const auto start = std::chrono::steady_clock::now();
  reference.contact = contact_pixels(soup, soft.casts, scene.camera, reference.image, options.contact_pixels);
  reference.contact_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return reference;
}

}  // namespace shadowcert
