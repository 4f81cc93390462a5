// The shadow map's soft methods (gpu/shadow_map_renderer.h, docs/smoothies.md) and the light
// image (StencilShadowFrame::first_light), drawn as `render --method` draws them
// (gpu/shadow_method_renderer.h, pipeline/method_inputs.h):
//  1. pcf with K = 1 is the hard shadow map, pixel for pixel (colour, marks, light image);
//  2. the light image is the lit mask (1 / 0, -1 where uncovered) for the hard map and for the
//     stencil methods cpu and cs;
//  3. pcss on a ramp that touches the floor: just inside the hard shadow's edge it is darker
//     near the contact than far from it, just outside it is brighter (the penumbra narrows);
//  4. smoothie on a square floating over a floor: the light beside one edge is the alpha
//     remapped by hand, a' = a / (1 - b / r) = 5 a there, rising monotonically away from the
//     shadow; it only ever darkens the hard map (stage 1 first);
//  5. misuse (an even pcf kernel, a negative light radius, smoothies not one per light) throws.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/pixel_ray.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_map_renderer.h"
#include "gpu/shadow_method_renderer.h"
#include "pipeline/method_inputs.h"
#include "pipeline/scene_smoothies.h"
#include "support/gl_test_support.h"
#include "support/volume_test_support.h"
#include "triangle_over_floor.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;
using namespace test;

// One soup (every triangle receives and casts) lit by one light, by `method`, one frame read back.
StencilShadowFrame render_method(ShadowMethod method, const Soup& soup, const Light& light, const Camera& camera,
                                 const ShadowMethodOptions& options = {}, const SceneSmoothieOptions& smoothie = {}) {
  const std::array lights{light};
  const std::array methods{method};
  MethodInputs inputs = prepare_method_inputs(soup, lights, methods);
  if (method == ShadowMethod::smoothie) add_smoothies(inputs, lights, soup_bounds(soup), smoothie);
  const std::array parts{ShadedSoupPart{&soup}};
  ShadowMethodRenderer renderer(method, method_scene(inputs, parts, lights), options);
  const OffscreenTarget target(camera.width, camera.height);
  return renderer.render(target, camera);
}

Soup default_soup() { return merged_soup(default_scene()); }

Camera small(Camera camera) {
  camera.width = 256;
  camera.height = 192;
  return camera;
}

// The light image holds 1 where the lit mask says lit, 0 where it says shadowed, -1 where no
// receiver covers the pixel.
void expect_light_image_is_lit_mask(const StencilShadowFrame& frame) {
  ASSERT_EQ(frame.first_light.size(), frame.first_lit_mask.pixels.size());
  std::size_t covered = 0, lit = 0;
  for (std::size_t p = 0; p < frame.first_light.size(); ++p) {
    const bool is_covered = frame.colour.pixels[4 * p + 3] != 0;
    const float expected = !is_covered ? kUncoveredLight : frame.first_lit_mask.pixels[p] != 0 ? 1.0f : 0.0f;
    ASSERT_EQ(frame.first_light[p], expected) << "pixel " << p;
    covered += is_covered ? 1 : 0;
    lit += expected == 1.0f ? 1 : 0;
  }
  EXPECT_GT(covered, frame.first_light.size() / 4);
  EXPECT_GT(lit, 0u);
  EXPECT_LT(lit, covered);
}

using SoftShadowMapTest = GlTest;

TEST_F(SoftShadowMapTest, PcfWithOneTap_IsTheHardShadowMapPixelForPixel) {
  const Soup soup = default_soup();
  const Camera camera = small(default_scene().camera);
  const Light light = default_scene().lights.front();
  ShadowMethodOptions pcf;
  pcf.pcf_kernel = 1;
  const StencilShadowFrame hard = render_method(ShadowMethod::shadowmap, soup, light, camera);
  const StencilShadowFrame one_tap = render_method(ShadowMethod::pcf, soup, light, camera, pcf);
  EXPECT_EQ(hard.colour.pixels, one_tap.colour.pixels);
  EXPECT_EQ(hard.first_stencil.pixels, one_tap.first_stencil.pixels);
  EXPECT_EQ(hard.first_lit_mask.pixels, one_tap.first_lit_mask.pixels);
  EXPECT_EQ(hard.first_light, one_tap.first_light);
  // And a wider kernel is a different, soft picture: fractions of 1 / 9.
  const StencilShadowFrame three = render_method(ShadowMethod::pcf, soup, light, camera);
  std::size_t soft = 0;
  for (float a : three.first_light) {
    if (a > 0.0f && a < 1.0f) {
      ++soft;
      EXPECT_NEAR(a * 9.0f, std::round(a * 9.0f), 1e-4f);
    }
  }
  EXPECT_GT(soft, 100u);
}

TEST_F(SoftShadowMapTest, HardShadowMap_LightImageIsItsLitMask) {
  const Soup soup = default_soup();
  const Camera camera = small(default_scene().camera);
  expect_light_image_is_lit_mask(render_method(ShadowMethod::shadowmap, soup, default_scene().lights.front(), camera));
  expect_light_image_is_lit_mask(render_method(ShadowMethod::shadowmap, triangle_over_floor(), kDirectionalSideLight,
                                               side_camera()));
}

TEST_F(SoftShadowMapTest, StencilMethods_LightImageIsTheLitMask) {
  const Soup soup = default_soup();
  const Camera camera = small(default_scene().camera);
  for (ShadowMethod method : {ShadowMethod::cpu, ShadowMethod::cs}) {
    SCOPED_TRACE(std::string(shadow_method_name(method)));
    expect_light_image_is_lit_mask(render_method(method, soup, default_scene().lights.front(), camera));
  }
}

// A ramp from the floor (x = -2, y = 0) up to (x = 2, y = 2), z in [-1, 1], under a point light
// at (0, 10, 0): its edge z = 1 at x_e casts onto the floor at t (x_e, 0, 1), t = 10 / (10 - y).
Soup ramp_over_floor() {
  Soup soup = triangle_over_floor();
  soup.vertices.resize(4);  // the floor only
  soup.triangles.resize(2);
  const auto base = static_cast<std::uint32_t>(soup.vertices.size());
  soup.vertices.push_back({-2.0, 0.0, -1.0});
  soup.vertices.push_back({2.0, 2.0, -1.0});
  soup.vertices.push_back({2.0, 2.0, 1.0});
  soup.vertices.push_back({-2.0, 0.0, 1.0});
  soup.triangles.push_back({base, base + 1, base + 2});
  soup.triangles.push_back({base, base + 2, base + 3});
  return soup;
}

TEST_F(SoftShadowMapTest, Pcss_ContactShadowIsDarkerAndNarrowerNearTheContact) {
  const Soup soup = ramp_over_floor();
  const Light light{{0.0, 10.0, 0.0, 1.0}};
  Camera camera;
  camera.eye = {0.0, 8.0, 8.0};
  camera.target = {0.0, 0.0, 1.0};
  camera.up = {0.0, 1.0, 0.0};
  camera.fov_y_degrees = 45.0;
  camera.width = 512;
  camera.height = 384;
  ShadowMethodOptions options;
  options.light_radius = 1.0;
  const StencilShadowFrame frame = render_method(ShadowMethod::pcss, soup, light, camera, options);
  // The floor point `offset` beyond (> 0: outside the shadow) the shadow of edge point x_e.
  const auto light_at = [&](double x_edge, double offset) {
    const double t = 10.0 / (10.0 - (x_edge + 2.0) / 2.0);
    const Pixel px = pixel_of(camera, {x_edge * t, 0.0, t + offset});
    return frame.first_light[std::size_t{px.row} * camera.width + px.x];
  };
  // Near the contact (edge 0.25 above the floor) the penumbra is about R 0.25 / 9.75 = 0.03
  // wide, far from it (1.75 above) about R 1.75 / 8.25 = 0.21: 0.1 inside, near is dark and far
  // partly lit; 0.1 outside, near is lit and far partly dark.
  const float inside_near = light_at(-1.5, -0.1), inside_far = light_at(1.5, -0.1);
  const float outside_near = light_at(-1.5, 0.1), outside_far = light_at(1.5, 0.1);
  EXPECT_LT(inside_near, 0.05f);
  EXPECT_GT(inside_far, inside_near + 0.1f);
  EXPECT_GT(outside_near, 0.95f);
  EXPECT_LT(outside_far, outside_near - 0.1f);
  // Deep inside and far outside, no penumbra at all.
  EXPECT_EQ(light_at(0.0, -0.6), 0.0f);
  EXPECT_EQ(light_at(0.0, 1.5), 1.0f);
}

// A unit square floating at height h = 2 over the floor (x, z in [-1, 1]), a point light at
// height H = 10 above its centre.
Soup square_over_floor() {
  Soup soup = triangle_over_floor();
  soup.vertices.resize(4);
  soup.triangles.resize(2);
  const auto base = static_cast<std::uint32_t>(soup.vertices.size());
  for (const Vec3& v : {Vec3{-1.0, 2.0, -1.0}, Vec3{1.0, 2.0, -1.0}, Vec3{1.0, 2.0, 1.0}, Vec3{-1.0, 2.0, 1.0}})
    soup.vertices.push_back(v);
  soup.triangles.push_back({base, base + 1, base + 2});
  soup.triangles.push_back({base, base + 2, base + 3});
  return soup;
}

TEST_F(SoftShadowMapTest, Smoothie_RemappedAlphaBesideOneEdgeAsComputedByHand) {
  constexpr double kHeight = 2.0, kLightHeight = 10.0, kWidth = 0.5;
  // Absorbs the smoothie map's texel: alpha is taken at the centre of the texel holding the
  // point, at most half a texel (4096^2 over the map's 20.4 units at the square's depth: 0.0025
  // units) from it, 0.005 of alpha, 0.025 after the remap's factor 5; and the float rounding of
  // the depths in b / r.
  constexpr float kRemapTolerance = 0.03f;
  const Soup soup = square_over_floor();
  const Light light{{0.0, kLightHeight, 0.0, 1.0}};
  Camera camera = side_camera();
  camera.width = 512;
  camera.height = 384;
  ShadowMethodOptions options;
  options.shadow_map_size = 4096;
  SceneSmoothieOptions smoothie;
  smoothie.width = kWidth;
  const StencilShadowFrame frame = render_method(ShadowMethod::smoothie, soup, light, camera, options, smoothie);
  const StencilShadowFrame hard = render_method(ShadowMethod::shadowmap, soup, light, camera, options);

  const CameraFrame view = camera_frame(camera);
  std::size_t checked = 0, partial = 0;
  std::vector<std::pair<double, float>> profile;  // (x on the floor, light) along z ~ 0
  for (std::uint32_t row = 0; row < camera.height; ++row) {
    for (std::uint32_t x = 0; x < camera.width; ++x) {
      const std::size_t p = std::size_t{row} * camera.width + x;
      // Smoothies only darken what the hard map lights (stage 1 first), never the reverse.
      ASSERT_LE(frame.first_light[p], hard.first_light[p]) << "pixel " << x << "," << row;
      const PixelRay ray = pixel_ray(view, x + 0.5, row + 0.5);
      if (!(ray.direction[1] < 0.0)) continue;
      const double t = -ray.origin[1] / ray.direction[1];
      const double floor_x = ray.origin[0] + t * ray.direction[0], floor_z = ray.origin[2] + t * ray.direction[2];
      // Where the ray to the light crosses the square's plane, and how far beyond the edge x = 1.
      const double scale = (kLightHeight - kHeight) / kLightHeight;
      const double beyond = floor_x * scale - 1.0, across = floor_z * scale;
      if (std::abs(across) > 0.6 || beyond < 0.02 || beyond > 0.45) continue;  // the edge's smoothie, off its corners
      // a = beyond / D; b / r = (H - h) / H along the ray, so a' = a H / h.
      const double expected = std::min(1.0, beyond / kWidth * kLightHeight / kHeight);
      EXPECT_NEAR(frame.first_light[p], expected, kRemapTolerance)
          << "floor point (" << floor_x << ", " << floor_z << "), alpha " << beyond / kWidth;
      ++checked;
      if (expected < 0.9) ++partial;
      if (std::abs(floor_z) < 0.02) profile.push_back({floor_x, frame.first_light[p]});
    }
  }
  EXPECT_GT(checked, 200u);
  EXPECT_GT(partial, 20u);
  // Monotone from the edge outwards along one line across the penumbra.
  std::sort(profile.begin(), profile.end());
  ASSERT_GT(profile.size(), 5u);
  for (std::size_t i = 1; i < profile.size(); ++i)
    EXPECT_GE(profile[i].second, profile[i - 1].second - kRemapTolerance) << "at x " << profile[i].first;
}

// A wide filter compares taps away from the point's texel, where a receiver tilted to the light
// lies at another depth: without the receiver-plane depth bias (shadow_filter.glsl) PCF 9x9 and
// PCSS darkened most of a lit floor (PCSS: 166,530 of 186,974 lit pixels of soft_contact.json at
// 640x480). A floor 8 wide lit from a light close above it, nothing casting onto it: every
// covered pixel keeps its full light.
TEST_F(SoftShadowMapTest, WideFiltersOnALitTiltedFloor_NoAcne) {
  Soup floor;
  floor.vertices = {{-4.0, 0.0, -4.0}, {-4.0, 0.0, 4.0}, {4.0, 0.0, 4.0}, {4.0, 0.0, -4.0}};
  floor.normals = {{0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  Camera camera;
  camera.eye = {0.5, 4.5, 6.0};
  camera.target = {-0.2, 0.2, -0.5};
  camera.width = 256;
  camera.height = 192;
  const Light light{{1.25, 4.0, 1.5, 1.0}};
  for (const auto& [method, kernel] : {std::pair{ShadowMethod::pcf, 9u}, std::pair{ShadowMethod::pcss, 3u}}) {
    ShadowMethodOptions options;
    options.pcf_kernel = kernel;
    options.light_radius = 0.25;
    const StencilShadowFrame frame = render_method(method, floor, light, camera, options);
    std::size_t covered = 0, darkened = 0;
    for (float amount : frame.first_light) {
      if (amount < 0.0f) continue;
      ++covered;
      darkened += amount < 0.95f;
    }
    EXPECT_GT(covered, 20000u) << shadow_method_name(method);
    EXPECT_EQ(darkened, 0u) << shadow_method_name(method);
  }
}

TEST_F(SoftShadowMapTest, Misuse_Throws) {
  const Soup soup = triangle_over_floor();
  const std::array lights{kSideLight};
  const std::array methods{ShadowMethod::smoothie};
  const MethodInputs inputs = prepare_method_inputs(soup, lights, methods);
  const std::array parts{ShadedSoupPart{&soup}};
  const ShadowMethodScene scene = method_scene(inputs, parts, lights);
  ShadowMethodOptions even;
  even.pcf_kernel = 2;
  EXPECT_THROW(ShadowMethodRenderer(ShadowMethod::pcf, scene, even), std::invalid_argument);
  ShadowMethodOptions negative;
  negative.light_radius = -1.0;
  EXPECT_THROW(ShadowMethodRenderer(ShadowMethod::pcss, scene, negative), std::invalid_argument);
  EXPECT_THROW(ShadowMethodRenderer(ShadowMethod::smoothie, scene), std::invalid_argument);  // no smoothies
}

}  // namespace
}  // namespace shadowcert::gpu
