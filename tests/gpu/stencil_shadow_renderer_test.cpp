// The stencil shadow pipeline on hand-built volumes of one triangle occluder over a floor
// (docs/definitions.md#counts: front cap, three side quads, back cap at infinity), with the shadow region
// computed analytically: pixels well inside it must count 1 and stay unlit, pixels well
// outside must count 0 and be lit; z-fail must survive an eye inside the volume where z-pass
// cannot; counts wrap modulo 256 (docs/definitions.md#pixel-protocol).
#include "core/homogeneous_mesh.h"
#include "core/vector3.h"
#include "gpu/stencil_shadow_renderer.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <utility>

#include "support/gl_test_support.h"
#include "triangle_over_floor.h"

namespace shadowcert::gpu {
namespace {

using namespace test;  // the scene: triangle_over_floor.h

std::array<float, 4> finite(const Vec3& p) {
  return {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]), 1.0f};
}

// The per-triangle volume V(t) of docs/definitions.md#counts, built by hand for one triangle.
HomogeneousMesh triangle_volume(const Light& light) {
  const auto& L = light.position;
  Vec3 a = kOccluder[0], b = kOccluder[1], c = kOccluder[2];
  // Orient t' so that its normal points towards the light.
  const Vec3 n = cross(difference(b, a), difference(c, a));
  const Vec3 to_light = light.directional() ? Vec3{L[0], L[1], L[2]} : Vec3{L[0] - a[0], L[1] - a[1], L[2] - a[2]};
  if (n[0] * to_light[0] + n[1] * to_light[1] + n[2] * to_light[2] < 0.0) std::swap(b, c);

  HomogeneousMesh g;
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

// `light_stencil`, when set, is the light's own method (LightVolume::stencil), over `method`.
StencilShadowFrame render(const Camera& camera, const Light& light, StencilMethod method, int copies = 1,
                          std::optional<StencilMethod> light_stencil = std::nullopt) {
  HomogeneousMesh g = triangle_volume(light);
  const std::size_t faces = g.triangles.size();
  for (int c = 1; c < copies; ++c)
    for (std::size_t f = 0; f < faces; ++f) g.triangles.push_back(g.triangles[f]);
  const ShadowVolumeMesh volume(g);
  const Soup soup = triangle_over_floor();
  const ShadedSoupMesh receivers(soup);
  const StencilShadowRenderer renderer;
  const OffscreenTarget target(camera.width, camera.height);
  const std::array<LightVolume, 1> lights{{{light, &volume, {}, light_stencil}}};
  return renderer.render(target, receivers, camera, lights, {.method = method});
}

std::uint8_t stencil_at(const StencilShadowFrame& f, Pixel p) { return *f.first_stencil.at(p.x, p.row); }
// The GL context fixture (support/gl_test_support.h) under this unit's name, for
// --gtest_filter=StencilShadowRendererTest.*
class StencilShadowRendererTest : public GlTest {};

// Point light kSideLight (triangle_over_floor.h): both stencil methods count the floor shadow.
TEST_F(StencilShadowRendererTest, PointLightShadowOnTheFloorZFailAndZPass) {
  const Camera camera = side_camera();
  for (StencilMethod method : {StencilMethod::zfail, StencilMethod::zpass}) {
    SCOPED_TRACE(method == StencilMethod::zfail ? "zfail" : "zpass");
    const StencilShadowFrame frame = render(camera, kSideLight, method);
    expect_shadow_pattern(camera, frame, kSideShadowed, kSideLit);
  }
}

// The eye between occluder and floor, inside V(t), looking down at shadowed floor.
// Light at (0, 3, 0): the volume below the occluder widens by (3 - y) / 2 from the y axis.
constexpr Light kOverheadLight{{0.0, 3.0, 0.0, 1.0}};
Camera camera_inside_the_volume() {
  Camera camera;
  camera.eye = {0.0, 0.6, 0.0};     // inside: at y = 0.6 the volume's section at z = 0 spans x in [-0.6, 0.6]
  camera.target = {0.0, 0.0, -0.3}; // floor shadow at z = -0.3 spans x in [-0.9, 0.9]
  camera.up = {0.0, 1.0, 0.0};
  camera.fov_y_degrees = 30.0;
  camera.width = 32;
  camera.height = 32;
  return camera;
}

// z-fail counts the faces behind P (the volume's exit below the floor) and gets 1; z-pass sees
// no face between the eye and P and gets 0, the textbook failure z-fail exists to avoid.
TEST_F(StencilShadowRendererTest, EyeInsideTheVolumeZFailCountsRightZPassDoesNot) {
  const Camera camera = camera_inside_the_volume();
  const Pixel centre{16, 16};
  const StencilShadowFrame zfail = render(camera, kOverheadLight, StencilMethod::zfail);
  EXPECT_EQ(stencil_at(zfail, centre), 1);
  EXPECT_EQ(*zfail.first_lit_mask.at(centre.x, centre.row), 0);
  const StencilShadowFrame zpass = render(camera, kOverheadLight, StencilMethod::zpass);
  EXPECT_EQ(stencil_at(zpass, centre), 0) << "z-pass misses the volume the eye is inside";
}

// LightVolume::stencil overrides StencilShadowOptions::method for its light, both ways, so a
// frame can count each light its own way (pipeline/stencil_choice.h's --stencil auto).
TEST_F(StencilShadowRendererTest, LightsOwnStencilMethod_OverridesTheOptions) {
  const Camera camera = camera_inside_the_volume();
  const Pixel centre{16, 16};
  EXPECT_EQ(stencil_at(render(camera, kOverheadLight, StencilMethod::zpass, 1, StencilMethod::zfail), centre), 1);
  EXPECT_EQ(stencil_at(render(camera, kOverheadLight, StencilMethod::zfail, 1, StencilMethod::zpass), centre), 0);
  EXPECT_EQ(stencil_at(render(camera, kOverheadLight, StencilMethod::zpass, 1, StencilMethod::zpass), centre), 0);
  EXPECT_EQ(stencil_method_name(StencilMethod::zfail), "zfail");
  EXPECT_EQ(stencil_method_name(StencilMethod::zpass), "zpass");
}

// Directional light (triangle_over_floor.h's kDirectionalSideLight): side faces meet the one
// far vertex (-l, 0); there is no back cap.
TEST_F(StencilShadowRendererTest, DirectionalLightShadow) {
  const Camera camera = side_camera();
  for (StencilMethod method : {StencilMethod::zfail, StencilMethod::zpass}) {
    SCOPED_TRACE(method == StencilMethod::zfail ? "zfail" : "zpass");
    const StencilShadowFrame frame = render(camera, kDirectionalSideLight, method);
    expect_shadow_pattern(camera, frame, kDirectionalShadowed, kDirectionalLit);
  }
}

// 257 copies of the same volume: the count is 257 mod 256 = 1 (GL_INCR_WRAP / GL_DECR_WRAP).
TEST_F(StencilShadowRendererTest, CountsWrapModulo256) {
  const Camera camera = side_camera();
  const StencilShadowFrame frame = render(camera, kSideLight, StencilMethod::zfail, 257);
  for (const Vec3& p : kSideShadowed) EXPECT_EQ(stencil_at(frame, pixel_of(camera, p)), 1);
  for (const Vec3& p : kSideLit) EXPECT_EQ(stencil_at(frame, pixel_of(camera, p)), 0);
  const StencilShadowFrame two = render(camera, kSideLight, StencilMethod::zfail, 2);
  EXPECT_EQ(stencil_at(two, pixel_of(camera, kSideShadowed[0])), 2);
}

// Regression: each receiver triangle is drawn twice, the second copy reversed, and the copy
// that wins the depth pre-pass is the one the lit pass shades. The copy kept the first one's
// normals, so where it won, the shader (which turns the normal towards the viewer by
// gl_FrontFacing) lit it from behind: a floor seen at a shallow angle showed dark striped wedges
// in the colour frame of every method, while the masks were right. No occluder here: every
// covered pixel must be lit, clearly above the ambient term.
TEST_F(StencilShadowRendererTest, ReversedCopyWinsTheDepthPass_IsLitAlike) {
  Soup floor;
  floor.vertices = {{-8.0, -1.5, -8.0}, {-8.0, -1.5, 8.0}, {8.0, -1.5, 8.0}, {8.0, -1.5, -8.0}};
  floor.normals = {{0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  Camera camera;
  camera.eye = {-2.5, 5.5, 6.5};
  camera.target = {-0.4, -0.9, -0.3};
  camera.width = 256;
  camera.height = 192;
  const Light light{{1.2, 4.0, 0.8, 1.0}};
  const ShadowVolumeMesh nothing{HomogeneousMesh{}};
  const ShadedSoupMesh receivers(floor);
  const StencilShadowRenderer renderer;
  const OffscreenTarget target(camera.width, camera.height);
  const std::array<LightVolume, 1> lights{{{light, &nothing}}};
  const StencilShadowFrame frame = renderer.render(target, receivers, camera, lights);
  // Albedo 0.8: ambient alone is 0.8 * 0.15 * 255 = 31; the light adds 0.8 * 0.85 * 255 times
  // a Lambert term of at least 0.4 over this floor (the light is 5.5 above it, at most 13 away).
  constexpr std::uint8_t kAboveAmbient = 80;
  std::size_t covered = 0, dark = 0;
  for (std::size_t i = 0; i < frame.colour.pixels.size() / 4; ++i) {
    if (frame.colour.pixels[4 * i + 3] == 0) continue;
    ++covered;
    dark += frame.colour.pixels[4 * i] < kAboveAmbient;
  }
  EXPECT_GT(covered, 10000u);
  EXPECT_EQ(dark, 0u);
}

TEST_F(StencilShadowRendererTest, LightWithoutVolumeIsRejected) {
  const Soup soup = triangle_over_floor();
  const ShadedSoupMesh receivers(soup);
  const StencilShadowRenderer renderer;
  const OffscreenTarget target(8, 8);
  const std::array<LightVolume, 1> lights{{{kSideLight, nullptr}}};
  EXPECT_THROW((void)renderer.render(target, receivers, side_camera(), lights), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert::gpu
