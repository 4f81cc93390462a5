// gpu/shadow_method_renderer.h, the one layer behind `render`, the benchmark and the image
// comparison:
//  1. it draws exactly what the method's own classes draw (stencil counts and colour bit for
//     bit against a hand-wired StencilShadowRenderer / ShadowMapRenderer), options passed on;
//  2. what it reports of the first light's volume is what was drawn (the cpu mesh as given;
//     GPU volumes closed, their triangle count the draw's);
//  3. timed frames cover the method's stages; misuse and missing inputs are rejected.
#include "gpu/shadow_method_renderer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/gl_test_support.h"
#include "gpu/compute_volume.h"
#include "gpu/offscreen_target.h"
#include "gpu/stencil_shadow_renderer.h"
#include "support/volume_test_support.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;
using namespace test;

// Small enough for llvmpipe to draw every method quickly; default.json's shadows still cover
// a few hundred pixels at this size.
constexpr std::uint32_t kWidth = 160;
constexpr std::uint32_t kHeight = 120;
// Stages are disjoint parts of each frame, but the medians of parts need not add up to the
// median of the whole over a few frames on a shared machine: this much slack absorbs that.
constexpr double kMedianSumSlack = 0.25;

// default.json, sized down, with `more_lights` after its own, and its inputs for every method.
PreparedScene default_inputs(const std::vector<Light>& more_lights = {}) {
  Scene scene = default_scene();
  scene.camera.width = kWidth;
  scene.camera.height = kHeight;
  scene.lights.insert(scene.lights.end(), more_lights.begin(), more_lights.end());
  return PreparedScene(std::move(scene));
}

std::vector<VolumeTriangle> triangles_of(const HomogeneousMesh& mesh) {
  std::vector<VolumeTriangle> out;
  for (const auto& t : mesh.triangles) out.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
  return out;
}

using ShadowMethodRendererTest = GlTest;

// cs and cpu, z-pass, two lights (colours shared): the layer's frame equals the one wired by
// hand from the method's classes, bit for bit (same GL calls, same inputs). The eye sits under
// the open box, inside its volume, where z-pass and z-fail differ: so the option is passed on.
TEST_F(ShadowMethodRendererTest, TwoLightsZpass_SameFrameAsTheMethodsOwnClasses) {
  PreparedScene in = default_inputs({Light{{-2.0, 6.0, 1.0, 1.0}}});
  in.scene.camera.eye = {-0.2, 0.4, -1.2};
  in.scene.camera.target = {0.5, 0.2, 4.0};
  const OffscreenTarget target(kWidth, kHeight);
  const ShadedSoupMesh receivers(in.parts);
  StencilShadowOptions by_hand;
  by_hand.method = StencilMethod::zpass;
  for (float& c : by_hand.light_colour) c /= 2.0f;
  const StencilShadowRenderer stencil;
  ShadowMethodOptions options;
  options.stencil = StencilMethod::zpass;

  const ShadowVolumeMesh cpu0(in.cpu_volumes[0]), cpu1(in.cpu_volumes[1]);
  const std::vector<LightVolume> cpu_lights{{in.scene.lights[0], &cpu0}, {in.scene.lights[1], &cpu1}};
  const StencilShadowFrame cpu_expected = stencil.render(target, receivers, in.scene.camera, cpu_lights, by_hand);
  StencilShadowOptions zfail = by_hand;
  zfail.method = StencilMethod::zfail;
  ASSERT_NE(stencil.render(target, receivers, in.scene.camera, cpu_lights, zfail).first_stencil.pixels,
            cpu_expected.first_stencil.pixels)
      << "the eye should be inside a volume, where z-pass counts differ";
  ShadowMethodRenderer cpu(ShadowMethod::cpu, in.method_scene(), options);
  const StencilShadowFrame cpu_frame = cpu.render(target, in.scene.camera);
  EXPECT_EQ(cpu_frame.colour.pixels, cpu_expected.colour.pixels);
  EXPECT_EQ(cpu_frame.first_stencil.pixels, cpu_expected.first_stencil.pixels);

  const ComputeVolumeSoup soup(in.prepared.canonical.soup, in.prepared.table);
  ComputeShadowVolume cs0(soup), cs1(soup);
  cs0.build(in.scene.lights[0]);
  cs1.build(in.scene.lights[1]);
  const std::vector<LightVolume> cs_lights{{in.scene.lights[0], nullptr, cs0.draw()},
                                           {in.scene.lights[1], nullptr, cs1.draw()}};
  const StencilShadowFrame cs_expected = stencil.render(target, receivers, in.scene.camera, cs_lights, by_hand);
  ShadowMethodRenderer cs(ShadowMethod::cs, in.method_scene(), options);
  const StencilShadowFrame cs_frame = cs.render(target, in.scene.camera);
  EXPECT_EQ(cs_frame.colour.pixels, cs_expected.colour.pixels);
  EXPECT_EQ(cs_frame.first_stencil.pixels, cs_expected.first_stencil.pixels);
  std::size_t shadowed = 0;
  for (std::uint8_t count : cs_frame.first_stencil.pixels) shadowed += count != 0;
  EXPECT_GT(shadowed, 0u) << "the comparison should cover shadows";
}

TEST_F(ShadowMethodRendererTest, ShadowMap_SameFrameAsShadowMapRendererWithItsOptions) {
  const PreparedScene in = default_inputs();
  const OffscreenTarget target(kWidth, kHeight);
  ShadowMethodOptions options;
  options.shadow_map_size = 512;
  options.shadow_map_bias = 3.0e-4f;
  options.shadow_map_slope = 1.5f;
  ShadowMethodRenderer renderer(ShadowMethod::shadowmap, in.method_scene(), options);
  const StencilShadowFrame frame = renderer.render(target, in.scene.camera);

  const ShadowMapRenderer by_hand(512);
  ShadowMapOptions o;
  o.depth_bias = 3.0e-4f;
  o.slope_scale = 1.5f;
  const StencilShadowFrame expected =
      by_hand.render(target, ShadedSoupMesh(in.parts), soup_bounds(in.soup), in.scene.camera, in.scene.lights, o);
  EXPECT_EQ(frame.colour.pixels, expected.colour.pixels);
  EXPECT_EQ(frame.first_stencil.pixels, expected.first_stencil.pixels);
  EXPECT_EQ(renderer.volume_triangles(), 0u);
  EXPECT_THROW((void)renderer.first_volume(), std::logic_error);
  EXPECT_NO_THROW(renderer.check_capacity());
}

// For every volume method: the first volume as reported is what was drawn (cpu: the mesh it
// was given; GPU methods: closed, one triangle per three drawn vertices).
TEST_F(ShadowMethodRendererTest, EveryVolumeMethod_FirstVolumeIsWhatWasDrawn) {
  const PreparedScene in = default_inputs();
  const OffscreenTarget target(kWidth, kHeight);
  for (ShadowMethod method : kVolumeMethods) {
    SCOPED_TRACE(std::string(shadow_method_name(method)));
    ShadowMethodRenderer renderer(method, in.method_scene());
    (void)renderer.render(target, in.scene.camera);
    EXPECT_NO_THROW(renderer.check_capacity());
    const HomogeneousMesh volume = renderer.first_volume();
    EXPECT_EQ(renderer.volume_triangles(), volume.triangles.size());
    if (method == ShadowMethod::cpu) {
      EXPECT_EQ(volume.vertices, in.cpu_volumes.front().vertices);
      EXPECT_EQ(volume.triangles, in.cpu_volumes.front().triangles);
    } else {
      EXPECT_EQ(volume.vertices.size(), 3 * volume.triangles.size());
    }
    EXPECT_GT(volume.triangles.size(), 0u);
    EXPECT_TRUE(unbalanced_edges(triangles_of(volume)).empty()) << "the drawn volume is open";
  }
}

TEST_F(ShadowMethodRendererTest, TimedFrames_CoverTheMethodsStages) {
  const PreparedScene in = default_inputs();
  const OffscreenTarget target(kWidth, kHeight);
  ShadowMethodRenderer renderer(ShadowMethod::gs, in.method_scene());
  EXPECT_EQ(renderer.render_frames(target, in.scene.camera, 3).size(), 3u);
  const FrameTiming t = renderer.time_frames(target, in.scene.camera, 1, 4, StageSync::finish);
  EXPECT_EQ(t.frames, 4u);
  EXPECT_EQ(t.stages, method_stages(ShadowMethod::gs));
  double stages = 0.0;
  for (RenderStage s : t.stages) {
    EXPECT_GT(t.wall(s).min_ms, 0.0) << render_stage_name(s) << ": every stage of gs does work";
    stages += t.wall(s).median_ms;
  }
  EXPECT_LE(stages, t.frame_cpu.median_ms * (1.0 + kMedianSumSlack));
  EXPECT_EQ(t.gpu(RenderStage::shadow_map).max_ms, 0.0);
  EXPECT_THROW((void)renderer.time_frames(target, in.scene.camera, 0, 0, StageSync::none), std::invalid_argument);
}

TEST_F(ShadowMethodRendererTest, MissingInputs_Throw) {
  const PreparedScene in = default_inputs();
  ShadowMethodScene no_light = in.method_scene();
  no_light.lights = {};
  EXPECT_THROW(ShadowMethodRenderer(ShadowMethod::shadowmap, no_light), std::invalid_argument);
  ShadowMethodScene no_cpu_volume = in.method_scene();
  no_cpu_volume.cpu_volumes = {};
  EXPECT_THROW(ShadowMethodRenderer(ShadowMethod::cpu, no_cpu_volume), std::invalid_argument);
  ShadowMethodScene no_table = in.method_scene();
  no_table.table = nullptr;
  EXPECT_THROW(ShadowMethodRenderer(ShadowMethod::ts, no_table), std::invalid_argument);
  ShadowMethodScene no_receiver = in.method_scene();
  no_receiver.receivers = {};
  EXPECT_THROW(ShadowMethodRenderer(ShadowMethod::cs, no_receiver), std::invalid_argument);
}

// A light docs/definitions.md#inputs does not define (a NaN coordinate, w outside {0, 1}, the null
// direction) is rejected by every GPU-built method's build, in the first frame, naming it.
TEST_F(ShadowMethodRendererTest, UndefinedLights_RejectedByEveryGpuBuild) {
  const PreparedScene in = default_inputs();
  const OffscreenTarget target(kWidth, kHeight);
  const std::array<Light, 3> undefined{Light{{std::nan(""), 4.0, 0.0, 1.0}}, Light{{1.0, 4.0, 0.0, 0.5}},
                                       Light{{0.0, 0.0, 0.0, 0.0}}};
  for (ShadowMethod method : kGpuBuiltMethods) {
    for (const Light& light : undefined) {
      SCOPED_TRACE(std::string(shadow_method_name(method)) + ", w = " + std::to_string(light.position[3]));
      ShadowMethodRenderer renderer(method, one_light_scene(in.parts, in.prepared, light, nullptr));
      try {
        (void)renderer.render(target, in.scene.camera);
        ADD_FAILURE() << "the light was accepted";
      } catch (const std::invalid_argument& error) {
        // core/light.h's require_defined wording, naming the build.
        const std::string what = error.what();
        EXPECT_TRUE(what.find("::build: the light needs finite coordinates") != std::string::npos ||
                    what.find("::build: a directional light needs a nonzero direction") != std::string::npos)
            << what;
      }
    }
  }
}

// ShadowMethodOptions::light_stencil: one frame, each light counted its own way (--stencil auto,
// pipeline/stencil_choice.h). The eye under the open box is inside the first light's volume,
// where z-pass and z-fail differ: the first light's counts follow its own method, and the frame
// is the one StencilShadowRenderer draws with those LightVolume::stencil.
TEST_F(ShadowMethodRendererTest, PerLightStencil_EachLightCountedItsOwnWayInOneFrame) {
  PreparedScene in = default_inputs({Light{{-2.0, 6.0, 1.0, 1.0}}});
  in.scene.camera.eye = {-0.2, 0.4, -1.2};
  in.scene.camera.target = {0.5, 0.2, 4.0};
  const OffscreenTarget target(kWidth, kHeight);
  constexpr StencilMethod zpass = StencilMethod::zpass, zfail = StencilMethod::zfail;
  for (ShadowMethod method : {ShadowMethod::cpu, ShadowMethod::cs}) {
    SCOPED_TRACE(std::string(shadow_method_name(method)));
    const auto frame = [&](std::vector<StencilMethod> per_light) {
      ShadowMethodOptions options;
      options.light_stencil = std::move(per_light);
      ShadowMethodRenderer renderer(method, in.method_scene(), options);
      return renderer.render(target, in.scene.camera);
    };
    const StencilShadowFrame all_zpass = frame({zpass, zpass}), all_zfail = frame({zfail, zfail});
    const StencilShadowFrame mixed = frame({zpass, zfail}), reversed = frame({zfail, zpass});
    ASSERT_NE(all_zpass.first_stencil.pixels, all_zfail.first_stencil.pixels);
    EXPECT_EQ(mixed.first_stencil.pixels, all_zpass.first_stencil.pixels);
    EXPECT_EQ(reversed.first_stencil.pixels, all_zfail.first_stencil.pixels);
    if (method == ShadowMethod::cpu) {
      StencilShadowOptions by_hand;
      for (float& c : by_hand.light_colour) c /= 2.0f;
      const ShadowVolumeMesh cpu0(in.cpu_volumes[0]), cpu1(in.cpu_volumes[1]);
      const std::vector<LightVolume> lights{{in.scene.lights[0], &cpu0, {}, zpass},
                                            {in.scene.lights[1], &cpu1, {}, zfail}};
      const StencilShadowFrame expected =
          StencilShadowRenderer().render(target, ShadedSoupMesh(in.parts), in.scene.camera, lights, by_hand);
      EXPECT_EQ(mixed.colour.pixels, expected.colour.pixels);
    }
  }
  ShadowMethodOptions wrong_size;
  wrong_size.light_stencil = {zpass};
  EXPECT_THROW(ShadowMethodRenderer(ShadowMethod::cpu, in.method_scene(), wrong_size), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert::gpu
