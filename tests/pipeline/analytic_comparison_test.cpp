// pipeline/analytic_comparison.h on real GL frames: the smooth-silhouette methods against the
// analytic shadow of the sphere a coarse uv sphere approximates (the paper's claim, Mattausch
// et al. 2012): on a 12x6 sphere close to a point light, smooth disagrees with the analytic
// shadow in fewer floor pixels than discrete, and smooth's disagreement falls as epsilon
// falls; compare_scene attaches the counts to the silhouette runs only; compare_analytic
// counts by the truth's classes.
#include "pipeline/analytic_comparison.h"

#include <gtest/gtest.h>

#include <iostream>
#include <vector>

#include "pipeline/scene_comparison.h"
#include "scene/procedural_mesh.h"
#include "support/gl_test_support.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;

// data/scenes/smooth_sphere.json at 320x240: a 12x6 sphere of radius 1 close to a point light
// over a floor, its ellipsoid known.
Scene coarse_sphere_scene() {
  Scene scene;
  SceneMesh floor;
  floor.name = "floor";
  floor.soup = floor_quad(6.0);
  scene.meshes.push_back(floor);
  SceneMesh sphere;
  sphere.name = "sphere";
  sphere.soup = uv_sphere({0.0, 1.2, 0.0}, 1.0, 12, 6);
  sphere.ellipsoid = Ellipsoid{{0.0, 1.2, 0.0}, {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}};
  scene.meshes.push_back(sphere);
  scene.lights = {Light{{0.6, 3.6, 0.4, 1.0}}};
  scene.camera.eye = {0.0, 7.5, 6.5};
  scene.camera.target = {0.0, 0.0, -0.8};
  scene.camera.width = 320;
  scene.camera.height = 240;
  return scene;
}

AnalyticCounts analytic_of(const SceneComparison& c, ShadowMethod method) {
  for (const MethodRun& run : c.runs)
    if (run.method == method) {
      EXPECT_TRUE(run.analytic().has_value()) << shadow_method_name(method);
      return run.analytic().value_or(AnalyticCounts{});
    }
  ADD_FAILURE() << shadow_method_name(method) << " did not run";
  return {};
}

void print(const char* name, const AnalyticCounts& a) {
  std::cout << name << ": receivers " << a.receiver_agree << " agree, " << a.receiver_disagree << " disagree, "
            << a.receiver_ambiguous << " ambiguous; caster " << a.caster_agree << " agree, " << a.caster_disagree
            << " disagree, " << a.caster_band << " band, " << a.caster_ambiguous << " ambiguous\n";
}

class AnalyticComparisonTest : public GlTest {};

TEST_F(AnalyticComparisonTest, CoarseSphere_SmoothDisagreesLessThanDiscreteAndLessAsEpsilonFalls) {
  const Scene scene = coarse_sphere_scene();
  std::vector<std::uint64_t> smooth;  // receiver disagreement at eps 0.1, 0.01, 0.003
  AnalyticCounts discrete;
  for (double epsilon : {0.1, 0.01, 0.003}) {
    SceneComparisonOptions options;
    options.silhouette.epsilon = epsilon;
    const std::vector<ShadowMethod> methods =
        epsilon == 0.1 ? std::vector<ShadowMethod>{ShadowMethod::discrete, ShadowMethod::smooth}
                       : std::vector<ShadowMethod>{ShadowMethod::smooth};
    const SceneComparison c = compare_scene(scene, methods, options);
    ASSERT_TRUE(c.analytic.has_value());
    if (epsilon == 0.1) {
      discrete = analytic_of(c, ShadowMethod::discrete);
      print("discrete", discrete);
    }
    const AnalyticCounts s = analytic_of(c, ShadowMethod::smooth);
    print(("smooth " + std::to_string(epsilon)).c_str(), s);
    smooth.push_back(s.receiver_disagree);
  }
  // Not vacuous: the 12-gon's shadow misses the conic by many pixels at this size.
  EXPECT_GT(discrete.receiver_disagree, 100u);
  EXPECT_GT(discrete.receiver_agree, 20'000u);
  EXPECT_LT(smooth[1], discrete.receiver_disagree / 2);  // eps = 0.01, the paper's
  EXPECT_LE(smooth[1], smooth[0]);
  EXPECT_LE(smooth[2], smooth[1]);
  EXPECT_LT(smooth[2], smooth[0]);
}

TEST_F(AnalyticComparisonTest, CompareScene_AttachesCountsToSilhouetteRunsOnly) {
  Scene scene = coarse_sphere_scene();
  scene.camera.width = 96;
  scene.camera.height = 72;
  const SceneComparison c = compare_scene(scene, {ShadowMethod::cpu, ShadowMethod::accurate}, {});
  ASSERT_TRUE(c.analytic.has_value());
  EXPECT_EQ(c.analytic->analytic_casters, std::vector<std::uint32_t>{1});
  ASSERT_EQ(c.runs.size(), 2u);
  EXPECT_FALSE(c.runs[0].analytic().has_value());  // cpu
  ASSERT_TRUE(c.runs[1].analytic().has_value());   // accurate
  const AnalyticCounts a = *c.runs[1].analytic();
  EXPECT_GT(a.receiver_agree + a.caster_agree, std::uint64_t{96} * 72 / 2);
  // Without an ellipsoid, or with the option off: no analytic image.
  SceneComparisonOptions off;
  off.analytic = false;
  EXPECT_FALSE(compare_scene(scene, {ShadowMethod::accurate}, off).analytic.has_value());
  scene.meshes[1].ellipsoid.reset();
  EXPECT_FALSE(compare_scene(scene, {ShadowMethod::accurate}, {}).analytic.has_value());
}

TEST(CompareAnalytic, CountsEveryClass_AndAnUncoveredDecidedPixelDisagrees) {
  AnalyticShadowImage truth;
  truth.width = 8;
  truth.height = 1;
  truth.lights = {{AnalyticPixel::none, AnalyticPixel::lit, AnalyticPixel::shadowed, AnalyticPixel::ambiguous,
                   AnalyticPixel::caster_lit, AnalyticPixel::caster_shadowed, AnalyticPixel::caster_band,
                   AnalyticPixel::lit}};
  StencilShadowFrame frame;
  frame.colour = RgbaImage(8, 1);
  frame.first_lit_mask = GrayImage(8, 1);
  for (std::uint32_t x = 0; x < 7; ++x) frame.colour.at(x, 0)[3] = 255;  // the last pixel uncovered
  // GL: lit, lit, lit, shadowed, shadowed, shadowed, lit, (uncovered).
  for (std::uint32_t x : {0u, 1u, 2u, 6u, 7u}) frame.first_lit_mask.at(x, 0)[0] = 255;
  const AnalyticCounts c = compare_analytic(truth, 0, frame);
  EXPECT_EQ(c.receiver_agree, 1u);     // pixel 1
  EXPECT_EQ(c.receiver_disagree, 2u);  // pixel 2 (lit where shadowed), pixel 7 (uncovered)
  EXPECT_EQ(c.receiver_ambiguous, 1u);
  EXPECT_EQ(c.caster_agree, 1u);     // pixel 5
  EXPECT_EQ(c.caster_disagree, 1u);  // pixel 4
  EXPECT_EQ(c.caster_band, 1u);
  EXPECT_EQ(c.caster_ambiguous, 0u);
  EXPECT_THROW((void)compare_analytic(truth, 1, frame), std::invalid_argument);
  frame.colour = RgbaImage(4, 2);
  EXPECT_THROW((void)compare_analytic(truth, 0, frame), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert::gpu
