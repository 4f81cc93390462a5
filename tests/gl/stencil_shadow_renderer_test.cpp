// The stencil shadow pipeline on hand-built volumes of one triangle occluder over a floor
// (DESIGN.md §3: front cap, three side quads, back cap at infinity), with the shadow region
// computed analytically: pixels well inside it must count 1 and stay unlit, pixels well
// outside must count 0 and be lit; z-fail must survive an eye inside the volume where z-pass
// cannot; counts wrap modulo 256 (§5).
#include "gpu/stencil_shadow_renderer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <span>

#include "gl_test_support.h"
#include "gpu/camera_transform.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;

// The occluder: a triangle in the plane y = 1; the floor: a large square at y = 0.
constexpr std::array<Vec3, 3> kOccluder{{{-1.0, 1.0, -1.0}, {1.0, 1.0, -1.0}, {0.0, 1.0, 1.0}}};
constexpr double kFloorHalfSize = 10.0;

Soup scene_soup() {
  Soup soup;
  const double h = kFloorHalfSize;
  soup.vertices = {{-h, 0.0, -h}, {h, 0.0, -h}, {h, 0.0, h}, {-h, 0.0, h}, kOccluder[0], kOccluder[1], kOccluder[2]};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}};
  return soup;
}

std::array<float, 4> finite(const Vec3& p) {
  return {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]), 1.0f};
}

// The per-triangle volume V(t) of DESIGN.md §3, built by hand for one triangle.
ShadowVolumeGeometry triangle_volume(const Light& light) {
  const auto& L = light.position;
  Vec3 a = kOccluder[0], b = kOccluder[1], c = kOccluder[2];
  // Orient t' so that its normal points towards the light.
  const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const Vec3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const Vec3 to_light = light.directional() ? Vec3{L[0], L[1], L[2]} : Vec3{L[0] - a[0], L[1] - a[1], L[2] - a[2]};
  if (n[0] * to_light[0] + n[1] * to_light[1] + n[2] * to_light[2] < 0.0) std::swap(b, c);

  ShadowVolumeGeometry g;
  const std::array<Vec3, 3> t{a, b, c};
  for (const Vec3& p : t) g.vertices.push_back(finite(p));
  if (light.directional()) {
    g.vertices.push_back({static_cast<float>(-L[0]), static_cast<float>(-L[1]), static_cast<float>(-L[2]), 0.0f});
  } else {
    for (const Vec3& p : t) {
      g.vertices.push_back({static_cast<float>(p[0] - L[0]), static_cast<float>(p[1] - L[1]),
                            static_cast<float>(p[2] - L[2]), 0.0f});
    }
  }
  g.triangles.push_back({0, 1, 2});  // front cap t'
  for (std::uint32_t k = 0; k < 3; ++k) {
    const std::uint32_t p = k, q = (k + 1) % 3;  // directed edge (p, q) of t'
    if (light.directional()) {
      g.triangles.push_back({q, p, 3});  // quad (q, p, inf, inf)
    } else {
      // Side quad (q, p, p_inf, q_inf) split in two.
      g.triangles.push_back({q, p, p + 3});
      g.triangles.push_back({q, p + 3, q + 3});
    }
  }
  if (!light.directional()) g.triangles.push_back({3, 5, 4});  // back cap: t' at infinity, reversed
  return g;
}

// Looking down at about 45 degrees from the +x side: the floor region the occluder hides from
// this eye (its projection from the eye onto y = 0) is x in [-2.75, -0.25], |z| <= 1.25,
// away from every test point below.
Camera side_camera() {
  Camera camera;
  camera.eye = {6.0, 5.0, 0.0};
  camera.target = {1.5, 0.0, -0.5};
  camera.up = {0.0, 1.0, 0.0};
  camera.fov_y_degrees = 60.0;
  camera.width = 128;
  camera.height = 96;
  return camera;
}

struct Pixel {
  std::uint32_t x, row;
};
Pixel pixel_of(const Camera& camera, const Vec3& p) {
  const auto image = project_to_image(camera, p);
  return {static_cast<std::uint32_t>(std::floor(image.x)), static_cast<std::uint32_t>(std::floor(image.y))};
}

// Point light at (-3, 3, 0): a floor point of the shadow is L + 3/2 (p - L) for p on the
// occluder, so the shadow is the triangle (0, -1.5), (3, -1.5), (1.5, 1.5) in (x, z); at
// z = 0.5 it spans x in [1, 2], at z = -1 x in [0.25, 2.75]. Every test point is >= 0.4
// world units (several pixels at this camera) from the shadow's boundary.
constexpr Light kSideLight{{-3.0, 3.0, 0.0, 1.0}};
constexpr std::array<Vec3, 3> kShadowedPoint{{{1.5, 0.0, -0.5}, {1.5, 0.0, 0.5}, {1.0, 0.0, -1.0}}};
constexpr std::array<Vec3, 4> kLitPoint{{{4.5, 0.0, -0.5}, {1.5, 0.0, -3.0}, {1.5, 0.0, 3.0}, {3.5, 0.0, 1.0}}};

StencilShadowFrame render(const Camera& camera, const Light& light, StencilMethod method, int copies = 1) {
  ShadowVolumeGeometry g = triangle_volume(light);
  const std::size_t faces = g.triangles.size();
  for (int c = 1; c < copies; ++c)
    for (std::size_t f = 0; f < faces; ++f) g.triangles.push_back(g.triangles[f]);
  const ShadowVolumeMesh volume(g);
  const Soup soup = scene_soup();
  const ShadedSoupMesh receivers(soup);
  const StencilShadowRenderer renderer;
  const OffscreenTarget target(camera.width, camera.height);
  const std::array<LightVolume, 1> lights{{{light, &volume}}};
  return renderer.render(target, receivers, camera, lights, {.method = method});
}

std::uint8_t stencil_at(const StencilShadowFrame& f, Pixel p) { return *f.first_stencil.at(p.x, p.row); }
std::uint8_t red_at(const StencilShadowFrame& f, Pixel p) { return f.colour.at(p.x, p.row)[0]; }

void expect_shadow_pattern(const Camera& camera, const StencilShadowFrame& frame,
                           std::span<const Vec3> shadowed, std::span<const Vec3> lit) {
  const std::uint8_t shadowed_red = red_at(frame, pixel_of(camera, shadowed[0]));
  for (const Vec3& p : shadowed) {
    const Pixel px = pixel_of(camera, p);
    EXPECT_EQ(stencil_at(frame, px), 1) << "shadowed point (" << p[0] << ", " << p[2] << ") pixel " << px.x << "," << px.row;
    EXPECT_EQ(*frame.first_lit_mask.at(px.x, px.row), 0);
  }
  for (const Vec3& p : lit) {
    const Pixel px = pixel_of(camera, p);
    EXPECT_EQ(stencil_at(frame, px), 0) << "lit point (" << p[0] << ", " << p[2] << ") pixel " << px.x << "," << px.row;
    EXPECT_EQ(*frame.first_lit_mask.at(px.x, px.row), 255);
    EXPECT_GT(red_at(frame, px), shadowed_red + 50) << "the lit floor must be brighter than the shadow";
    EXPECT_EQ(frame.colour.at(px.x, px.row)[3], 255) << "covered pixels have alpha 255";
  }
}

TEST_F(GlTest, PointLightShadowOnTheFloorZFailAndZPass) {
  const Camera camera = side_camera();
  for (StencilMethod method : {StencilMethod::zfail, StencilMethod::zpass}) {
    SCOPED_TRACE(method == StencilMethod::zfail ? "zfail" : "zpass");
    const StencilShadowFrame frame = render(camera, kSideLight, method);
    expect_shadow_pattern(camera, frame, kShadowedPoint, kLitPoint);
  }
}

// The eye between occluder and floor, inside V(t): looking down at shadowed floor. z-fail
// counts the faces behind P (the volume's exit below the floor) and gets 1; z-pass sees no face between the
// eye and P and gets 0, the textbook failure z-fail exists to avoid.
TEST_F(GlTest, EyeInsideTheVolumeZFailCountsRightZPassDoesNot) {
  // Light at (0, 3, 0): the volume below the occluder widens by (3 - y) / 2 from the y axis.
  constexpr Light kOverheadLight{{0.0, 3.0, 0.0, 1.0}};
  Camera camera;
  camera.eye = {0.0, 0.6, 0.0};     // inside: at y = 0.6 the volume's section at z = 0 spans x in [-0.6, 0.6]
  camera.target = {0.0, 0.0, -0.3}; // floor shadow at z = -0.3 spans x in [-0.9, 0.9]
  camera.up = {0.0, 1.0, 0.0};
  camera.fov_y_degrees = 30.0;
  camera.width = 32;
  camera.height = 32;
  const Pixel centre{16, 16};
  const StencilShadowFrame zfail = render(camera, kOverheadLight, StencilMethod::zfail);
  EXPECT_EQ(stencil_at(zfail, centre), 1);
  EXPECT_EQ(*zfail.first_lit_mask.at(centre.x, centre.row), 0);
  const StencilShadowFrame zpass = render(camera, kOverheadLight, StencilMethod::zpass);
  EXPECT_EQ(stencil_at(zpass, centre), 0) << "z-pass misses the volume the eye is inside";
}

// Directional light towards l = (-1, 1, 0): a floor point of the shadow is p + (1, -1, 0) for
// p on the occluder, the triangle (0, -1), (2, -1), (1, 1) in (x, z); at z = -0.3 it spans
// x in [0.35, 1.65], at z = -0.7 x in [0.15, 1.85]. Side faces meet the one far vertex
// (-l, 0); there is no back cap.
TEST_F(GlTest, DirectionalLightShadow) {
  const Camera camera = side_camera();
  constexpr Light kDirectional{{-1.0, 1.0, 0.0, 0.0}};
  constexpr std::array<Vec3, 2> kShadowed{{{1.0, 0.0, -0.3}, {1.2, 0.0, -0.7}}};
  constexpr std::array<Vec3, 3> kLit{{{3.5, 0.0, -0.5}, {1.0, 0.0, 2.5}, {1.0, 0.0, -2.5}}};
  for (StencilMethod method : {StencilMethod::zfail, StencilMethod::zpass}) {
    SCOPED_TRACE(method == StencilMethod::zfail ? "zfail" : "zpass");
    const StencilShadowFrame frame = render(camera, kDirectional, method);
    expect_shadow_pattern(camera, frame, kShadowed, kLit);
  }
}

// 257 copies of the same volume: the count is 257 mod 256 = 1 (GL_INCR_WRAP / GL_DECR_WRAP).
TEST_F(GlTest, CountsWrapModulo256) {
  const Camera camera = side_camera();
  const StencilShadowFrame frame = render(camera, kSideLight, StencilMethod::zfail, 257);
  for (const Vec3& p : kShadowedPoint) EXPECT_EQ(stencil_at(frame, pixel_of(camera, p)), 1);
  for (const Vec3& p : kLitPoint) EXPECT_EQ(stencil_at(frame, pixel_of(camera, p)), 0);
  const StencilShadowFrame two = render(camera, kSideLight, StencilMethod::zfail, 2);
  EXPECT_EQ(stencil_at(two, pixel_of(camera, kShadowedPoint[0])), 2);
}

TEST_F(GlTest, LightWithoutVolumeIsRejected) {
  const Soup soup = scene_soup();
  const ShadedSoupMesh receivers(soup);
  const StencilShadowRenderer renderer;
  const OffscreenTarget target(8, 8);
  const std::array<LightVolume, 1> lights{{{kSideLight, nullptr}}};
  EXPECT_THROW((void)renderer.render(target, receivers, side_camera(), lights), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert::gpu
