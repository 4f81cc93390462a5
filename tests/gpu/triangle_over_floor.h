#pragma once
// The scene of the stencil and shadow-map renderer tests (stencil_shadow_renderer_test.cpp,
// shadow_map_renderer_test.cpp): one triangle occluder in the plane y = 1 over a 20 x 20 floor
// at y = 0, seen from the +x side, with floor points whose shadow status is known analytically
// for two lights; and the check of a frame at those points. Test code only.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "gpu/camera_transform.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu::test {

inline constexpr std::array<Vec3, 3> kOccluder{{{-1.0, 1.0, -1.0}, {1.0, 1.0, -1.0}, {0.0, 1.0, 1.0}}};
inline constexpr double kFloorHalfSize = 10.0;

// The floor (two triangles facing +y) and the occluder, one soup.
inline Soup triangle_over_floor() {
  Soup soup;
  const double h = kFloorHalfSize;
  soup.vertices = {{-h, 0.0, -h}, {h, 0.0, -h}, {h, 0.0, h}, {-h, 0.0, h}, kOccluder[0], kOccluder[1], kOccluder[2]};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}};
  return soup;
}

// Looking down at about 45 degrees from the +x side: the floor region the occluder hides from
// this eye (its projection from the eye onto y = 0) is x in [-2.75, -0.25], |z| <= 1.25,
// away from every test point below.
inline Camera side_camera() {
  Camera camera;
  camera.eye = {6.0, 5.0, 0.0};
  camera.target = {1.5, 0.0, -0.5};
  camera.up = {0.0, 1.0, 0.0};
  camera.fov_y_degrees = 60.0;
  camera.width = 128;
  camera.height = 96;
  return camera;
}

// Point light at (-3, 3, 0): a floor point of the shadow is L + 3/2 (p - L) for p on the
// occluder, so the shadow is the triangle (0, -1.5), (3, -1.5), (1.5, 1.5) in (x, z); at
// z = 0.5 it spans x in [1, 2], at z = -1 x in [0.25, 2.75]. Every point below is >= 0.4
// world units (several pixels at side_camera) from the shadow's boundary.
inline constexpr Light kSideLight{{-3.0, 3.0, 0.0, 1.0}};
inline constexpr std::array<Vec3, 3> kSideShadowed{{{1.5, 0.0, -0.5}, {1.5, 0.0, 0.5}, {1.0, 0.0, -1.0}}};
inline constexpr std::array<Vec3, 4> kSideLit{{{4.5, 0.0, -0.5}, {1.5, 0.0, -3.0}, {1.5, 0.0, 3.0}, {3.5, 0.0, 1.0}}};

// Directional light towards l = (-1, 1, 0): a floor point of the shadow is p + (1, -1, 0) for
// p on the occluder, the triangle (0, -1), (2, -1), (1, 1) in (x, z); at z = -0.3 it spans
// x in [0.35, 1.65], at z = -0.7 x in [0.15, 1.85].
inline constexpr Light kDirectionalSideLight{{-1.0, 1.0, 0.0, 0.0}};
inline constexpr std::array<Vec3, 2> kDirectionalShadowed{{{1.0, 0.0, -0.3}, {1.2, 0.0, -0.7}}};
inline constexpr std::array<Vec3, 3> kDirectionalLit{{{3.5, 0.0, -0.5}, {1.0, 0.0, 2.5}, {1.0, 0.0, -2.5}}};

struct Pixel {
  std::uint32_t x, row;  // row 0 at the top, as the frame's images
};

// The pixel whose square holds p's projection (gpu/camera_transform.h).
inline Pixel pixel_of(const Camera& camera, const Vec3& p) {
  const auto image = project_to_image(camera, p);
  return {static_cast<std::uint32_t>(std::floor(image.x)), static_cast<std::uint32_t>(std::floor(image.y))};
}

// At every `shadowed` floor point (at least one) the frame counts 1 and is unlit; at every
// `lit` one it counts 0, is lit, covered (alpha 255) and clearly brighter than the first
// shadowed point.
inline void expect_shadow_pattern(const Camera& camera, const StencilShadowFrame& frame,
                                  std::span<const Vec3> shadowed, std::span<const Vec3> lit) {
  const Pixel first = pixel_of(camera, shadowed[0]);
  const std::uint8_t shadowed_red = frame.colour.at(first.x, first.row)[0];
  for (const Vec3& p : shadowed) {
    const Pixel px = pixel_of(camera, p);
    EXPECT_EQ(*frame.first_stencil.at(px.x, px.row), 1)
        << "shadowed point (" << p[0] << ", " << p[2] << ") pixel " << px.x << "," << px.row;
    EXPECT_EQ(*frame.first_lit_mask.at(px.x, px.row), 0);
  }
  for (const Vec3& p : lit) {
    const Pixel px = pixel_of(camera, p);
    EXPECT_EQ(*frame.first_stencil.at(px.x, px.row), 0)
        << "lit point (" << p[0] << ", " << p[2] << ") pixel " << px.x << "," << px.row;
    EXPECT_EQ(*frame.first_lit_mask.at(px.x, px.row), 255);
    EXPECT_GT(frame.colour.at(px.x, px.row)[0], shadowed_red + 50) << "the lit floor must be brighter than the shadow";
    EXPECT_EQ(frame.colour.at(px.x, px.row)[3], 255) << "covered pixels have alpha 255";
  }
}

}  // namespace shadowcert::gpu::test
