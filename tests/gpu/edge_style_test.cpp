// gpu/edge_style.h: each style on hand-checkable scenes (a square facing the eye, a roof with a
// right-angled ridge), with and without a light amount; and the paper's orthogonality: the edge
// map drawn after any shadow method's frame equals the one drawn without it, bit for bit, and
// the edge passes and the composite leave that frame's stencil counts as they were.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"
#include "gpu/camera_transform.h"
#include "gpu/edge_map.h"
#include "gpu/edge_style.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method_renderer.h"
#include "support/gl_test_support.h"
#include "support/volume_test_support.h"
#include "triangle_over_floor.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;

// 8-bit colours: the shade texture and the target are RGBA8, so a style's exact colour comes
// back rounded once or twice to 1/255 (GL may round float to unorm either way).
constexpr int kByteRounding = 1;
constexpr float kAlbedo = 0.8f;  // ShadedSoupPart's default albedo

int byte(double v) { return static_cast<int>(std::lround(v * 255.0)); }

void expect_rgb(const RgbaImage& image, std::uint32_t x, std::uint32_t row, std::array<double, 3> rgb) {
  const std::uint8_t* p = image.at(x, row);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], byte(rgb[c]), kByteRounding) << "pixel " << x << ", " << row << " channel " << c;
}

// A 2 x 2 square at z = 0 facing +z, seen from (0, 0, 5) with a 90-degree field of view at
// 32 x 32: it covers pixels 13 to 18 both ways (a pixel spans 10/32 world units).
Soup facing_square() {
  Soup soup;
  soup.vertices = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}};
  return soup;
}

Camera front_camera(std::uint32_t side = 32) {
  Camera camera;
  camera.eye = {0.0, 0.0, 5.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.fov_y_degrees = 90.0;
  camera.width = side;
  camera.height = side;
  camera.near_plane = 0.1;
  return camera;
}

struct Drawn {
  RgbaImage image;
  EdgeMapImage map;
};

Drawn draw_style(const Soup& soup, EdgeStyle style, const Light& light, std::span<const float> amount = {},
                 double profile = profile_threshold(EdgeFilter::diagonal, kDefaultEdgeDepthStep),
                 double inner = inner_threshold(EdgeFilter::diagonal, kDefaultEdgeCreaseAngleDegrees)) {
  const Camera camera = front_camera();
  const std::array parts{ShadedSoupPart{&soup}};
  EdgeMapRenderer edges(parts);
  const OffscreenTarget target(camera.width, camera.height);
  Drawn drawn;
  drawn.map = edges.render(target, camera, EdgeFilter::diagonal);
  EdgeStyleOptions options;
  options.profile_threshold = profile;
  options.inner_threshold = inner;
  options.light = light;
  options.light_amount = amount;
  EdgeStyleRenderer renderer;
  drawn.image = renderer.render(target, edges, camera, style, options);
  return drawn;
}

const Light kHeadOn{{0.0, 0.0, 1.0, 0.0}};  // directional, along the square's normal: n . l = 1

using EdgeStyleTest = GlTest;

TEST_F(EdgeStyleTest, Edges_WhitePaperBlackProfileOnBothSidesOfTheOutline) {
  const Drawn d = draw_style(facing_square(), EdgeStyle::edges, kHeadOn);
  expect_rgb(d.image, 16, 16, {1.0, 1.0, 1.0});  // inside
  expect_rgb(d.image, 2, 2, {1.0, 1.0, 1.0});    // background: paper
  for (const std::uint32_t x : {12u, 13u, 18u, 19u}) expect_rgb(d.image, x, 16, {0.0, 0.0, 0.0});  // the outline
  expect_rgb(d.image, 15, 13, {0.0, 0.0, 0.0});
  for (std::size_t i = 0; i < std::size_t{32} * 32; ++i) EXPECT_EQ(d.image.pixels[4 * i + 3], 255);
}

TEST_F(EdgeStyleTest, Edges_InShadowTheGreyOfThePaper) {
  const std::vector<float> dark(32 * 32, 0.0f);
  const Drawn d = draw_style(facing_square(), EdgeStyle::edges, kHeadOn, dark);
  expect_rgb(d.image, 16, 16, {0.75, 0.75, 0.75});  // kEdgesShadowTone
}

TEST_F(EdgeStyleTest, Gooch_WarmTowardsTheLightCoolAway) {
  const double warm_r = 0.4 + 0.6 * kAlbedo, warm_b = 0.6 * kAlbedo, cool_r = 0.2 * kAlbedo, cool_b = 0.4 + 0.2 * kAlbedo;
  expect_rgb(draw_style(facing_square(), EdgeStyle::gooch, kHeadOn).image, 16, 16, {warm_r, warm_r, warm_b});
  const Light behind{{0.0, 0.0, -1.0, 0.0}};  // n . l = -1 (the normal is turned towards the eye)
  expect_rgb(draw_style(facing_square(), EdgeStyle::gooch, behind).image, 16, 16, {cool_r, cool_r, cool_b});
  const std::vector<float> dark(32 * 32, 0.0f);  // in shadow: t = 0, the cool tone
  expect_rgb(draw_style(facing_square(), EdgeStyle::gooch, kHeadOn, dark).image, 16, 16, {cool_r, cool_r, cool_b});
}

// Two faces of a roof meeting at the ridge x = 0 (on a pixel boundary) at a right angle, the
// ridge towards the eye: the ridge's two columns are inner edges (the diagonal filter's inner
// intensity there is (1 - cos 90) / 2 = 0.5), drawn white by gooch, black by toon.
Soup roof() {
  Soup soup;
  soup.vertices = {{-1, -1, -1}, {0, -1, 0}, {0, 1, 0}, {-1, 1, -1}, {1, -1, -1}, {1, 1, -1}};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 2}};
  return soup;
}

TEST_F(EdgeStyleTest, GoochAndToon_RidgeIsAnInnerEdge_WhiteAndBlack) {
  // Profile threshold 2, above every intensity: the faces' steep depth ramps (the range is fitted
  // to the roof alone) are left out, only the crease is drawn.
  const Light above{{0.0, 1.0, 0.0, 0.0}};  // n . l = 0 on both faces: gooch's middle tone
  const Drawn gooch = draw_style(roof(), EdgeStyle::gooch, above, {}, 2.0);
  for (const std::uint32_t x : {15u, 16u}) {
    EXPECT_NEAR(gooch.map.inner[gooch.map.index(x, 16)], 0.5, 1e-5);
    expect_rgb(gooch.image, x, 16, {1.0, 1.0, 1.0});
  }
  const double mid_r = 0.5 * (0.2 * kAlbedo + 0.4 + 0.6 * kAlbedo), mid_b = 0.5 * (0.4 + 0.2 * kAlbedo + 0.6 * kAlbedo);
  expect_rgb(gooch.image, 14, 16, {mid_r, mid_r, mid_b});
  const Drawn toon = draw_style(roof(), EdgeStyle::toon, above, {}, 2.0);
  for (const std::uint32_t x : {15u, 16u}) expect_rgb(toon.image, x, 16, {0.0, 0.0, 0.0});
  expect_rgb(toon.image, 14, 16, {kToonShades[0] * kAlbedo, kToonShades[0] * kAlbedo, kToonShades[0] * kAlbedo});
}

// Lake's texture with nearest filtering: n . l = 1, 0.6 and 0.3 fall in the bands 1.0, 0.7 and
// 0.35; in shadow the amount 0 drops n . l to the lowest band.
TEST_F(EdgeStyleTest, Toon_LakesBandsByNDotL_ShadowTheLowestBand) {
  for (const auto& [n_dot_l, shade] : {std::pair{1.0, kToonShades[3]}, std::pair{0.6, kToonShades[2]},
                                       std::pair{0.3, kToonShades[1]}}) {
    const double s = std::sqrt(1.0 - n_dot_l * n_dot_l);
    const Light light{{s, 0.0, n_dot_l, 0.0}};
    const RgbaImage image = draw_style(facing_square(), EdgeStyle::toon, light).image;
    const double v = shade * kAlbedo;
    expect_rgb(image, 16, 16, {v, v, v});
  }
  const std::vector<float> dark(32 * 32, 0.0f);
  const double v = kToonShades[0] * kAlbedo;
  expect_rgb(draw_style(facing_square(), EdgeStyle::toon, kHeadOn, dark).image, 16, 16, {v, v, v});
}

// The cartoon map is anti-aliased: where the light amount steps from 1 to 0 between two
// columns inside the square, the two pixels beside the step take the tent's blend
// (3/4 of their own band, 1/4 of the other), as the paper smooths its colour patches.
TEST_F(EdgeStyleTest, Toon_CartoonMapAntiAliasedAcrossBands) {
  std::vector<float> amount(32 * 32, 1.0f);
  for (std::uint32_t row = 0; row < 32; ++row)
    for (std::uint32_t x = 16; x < 32; ++x) amount[row * 32 + x] = 0.0f;
  const RgbaImage image = draw_style(facing_square(), EdgeStyle::toon, kHeadOn, amount).image;
  const double lit = kToonShades[3] * kAlbedo, dark = kToonShades[0] * kAlbedo;
  const double left = 0.75 * lit + 0.25 * dark, right = 0.25 * lit + 0.75 * dark;
  // Within a pixel of rounding: the band colours are rounded to bytes before the blend.
  expect_rgb(image, 15, 16, {left, left, left});
  expect_rgb(image, 16, 16, {right, right, right});
  expect_rgb(image, 14, 16, {lit, lit, lit});
  expect_rgb(image, 17, 16, {dark, dark, dark});
}

TEST_F(EdgeStyleTest, Misuse_Throws) {
  const Soup soup = facing_square();
  const std::array parts{ShadedSoupPart{&soup}};
  EdgeMapRenderer edges(parts);
  EdgeStyleRenderer style;
  const Camera camera = front_camera();
  const OffscreenTarget target(camera.width, camera.height);
  EXPECT_THROW(style.draw(target, edges, camera, EdgeStyle::edges, {}), std::logic_error);  // no edge map yet
  edges.draw(16, 16, camera, EdgeFilter::diagonal);
  EXPECT_THROW(style.draw(target, edges, camera, EdgeStyle::edges, {}), std::invalid_argument);  // another size
  edges.draw(camera.width, camera.height, camera, EdgeFilter::diagonal);
  const std::vector<float> wrong(10, 1.0f);
  EdgeStyleOptions options;
  options.light_amount = wrong;
  EXPECT_THROW(style.draw(target, edges, camera, EdgeStyle::edges, options), std::invalid_argument);
}

TEST(EdgeStyleNames, RoundTrip_UnknownIsNullopt) {
  for (EdgeStyle s : kEdgeStyles) EXPECT_EQ(parse_edge_style(edge_style_name(s)), s);
  EXPECT_EQ(parse_edge_style("cartoon"), std::nullopt);
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// The paper's orthogonality claim (§4, "Rendering Passes"): the edge map lives in textures of
// its own, so a shadow method's frame (its stencil counts in the target) and the edge map do not
// interfere. For the exact chain (cpu), a GPU-built volume (cs) and the shadow map, and every
// filter: the edge map (and the G-buffer) drawn after the shadow frame equals the one drawn
// before it, bit for bit; the edge passes and the style composited over the frame leave the
// frame's stencil as it was and the edge map as it was; and the shadows do reach the style (a shadowed floor point
// is darker than without shadows), so the comparison is not vacuous.
TEST_F(EdgeStyleTest, Orthogonality_EdgeMapWithShadowsEqualsWithout_StencilUntouched) {
  const Soup soup = test::triangle_over_floor();
  const Camera camera = test::side_camera();
  const test::Prepared prepared = test::prepare(soup);
  const HomogeneousMesh cpu_mesh = test::cpu_volume(prepared, test::kSideLight);
  const std::array parts{ShadedSoupPart{&soup}};
  const OffscreenTarget target(camera.width, camera.height);
  EdgeStyleRenderer style;
  const glm::dvec2 shadowed = project_to_image(camera, test::kSideShadowed[0]);
  const auto sx = static_cast<std::uint32_t>(shadowed.x), srow = static_cast<std::uint32_t>(shadowed.y);
  for (const ShadowMethod method : {ShadowMethod::cpu, ShadowMethod::cs, ShadowMethod::shadowmap}) {
    ShadowMethodRenderer shadows = test::one_light_renderer(method, soup, prepared, test::kSideLight, &cpu_mesh);
    for (const EdgeFilter filter : kEdgeFilters) {
      SCOPED_TRACE(std::string(shadow_method_name(method)) + ", " + std::string(edge_filter_name(filter)));
      EdgeMapRenderer edges(parts);
      edges.draw(camera.width, camera.height, camera, filter);
      const std::vector<float> alone = edges.edge_map().read_texels();
      const std::vector<float> g_alone = edges.g_buffer().read();
      EdgeStyleOptions options;
      options.profile_threshold = profile_threshold(filter, kDefaultEdgeDepthStep);
      options.inner_threshold = inner_threshold(filter, kDefaultEdgeCreaseAngleDegrees);
      options.light = test::kSideLight;
      const RgbaImage unshadowed = style.render(target, edges, camera, EdgeStyle::gooch, options);

      const StencilShadowFrame frame = shadows.render(target, camera);
      // The stencil as the frame left it (its lit pass counts lit pixels up: not first_stencil).
      const GrayImage stencil = target.read_stencil();
      ASSERT_EQ(frame.first_light[srow * camera.width + sx], 0.0f) << "the test point is in shadow";
      edges.draw(camera.width, camera.height, camera, filter);
      EXPECT_TRUE(same_bits(edges.edge_map().read_texels(), alone)) << "edge map after the shadow frame";
      EXPECT_TRUE(same_bits(edges.g_buffer().read(), g_alone)) << "G-buffer after the shadow frame";

      options.light_amount = frame.first_light;
      const RgbaImage with_shadows = style.render(target, edges, camera, EdgeStyle::gooch, options);
      EXPECT_EQ(target.read_stencil().pixels, stencil.pixels) << "the frame's stencil after the edges";
      EXPECT_TRUE(same_bits(edges.edge_map().read_texels(), alone)) << "edge map after the composite";
      EXPECT_LT(with_shadows.at(sx, srow)[0] + 0, unshadowed.at(sx, srow)[0] + 0) << "shadowed point: cooler";
    }
  }
}

}  // namespace
}  // namespace shadowcert::gpu
