// pipeline/stencil_choice.h, GL-free: the tip it proves z-pass on holds GL's own near-plane tip
// (gpu/camera_transform.h), and `auto` picks z-pass where exact/zpass_proof.h proves it (the
// default scene) and z-fail with the reason elsewhere (the camera inside a volume; the scene at
// 1e6, whose float margin is wider than the camera's distance to the room).
#include "pipeline/stencil_choice.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/pixel_ray.h"
#include "core/scene.h"
#include "exact/light_orientation.h"
#include "gpu/camera_transform.h"
#include "io/soup_file.h"
#include "pipeline/method_inputs.h"
#include "scene/merged_soup.h"
#include "scene/scene_file.h"

namespace shadowcert {
namespace {

Scene load(const std::string& relative) {
  return load_scene(std::filesystem::path(SHADOWCERT_SOURCE_DIR) / relative,
                    [](const std::filesystem::path& f) { return read_soup(f); });
}

struct Loaded {
  Scene scene;
  MethodInputs inputs;
};

Loaded prepared(const std::string& relative) {
  Loaded l{load(relative), {}};
  const std::array methods{gpu::ShadowMethod::cs};
  l.inputs = prepare_method_inputs(merged_soup(l.scene), l.scene.lights, methods);
  return l;
}

// Whether p lies in the closed tetrahedron abcd (exact orientation signs).
bool in_tetrahedron(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto h = [](const Vec3& x) { return finite_point(x); };
  const Sign s = orient(h(a), h(b), h(c), h(d));
  for (const Sign t : {orient(h(p), h(b), h(c), h(d)), orient(h(a), h(p), h(c), h(d)), orient(h(a), h(b), h(p), h(d)),
                       orient(h(a), h(b), h(c), h(p))})
    if (t != Sign::zero && t != s) return false;
  return true;
}

bool in_tip(const NearTip& tip, const Vec3& p) {
  const auto& c = tip.corners;
  return in_tetrahedron(p, tip.apex, c[0], c[1], c[2]) || in_tetrahedron(p, tip.apex, c[0], c[2], c[3]);
}

TEST(GlNearTip, HoldsTheEyeAndGlsNearRectangle_AndProjectsOutsideTheViewport) {
  for (const char* file : {"data/scenes/default.json", "data/scenes/hard/camera_inside_volume.json",
                                  "data/scenes/hard/scale_1e-6.json"}) {
    SCOPED_TRACE(file);
    const Scene scene = load(file);
    const Soup casters = merged_soup(scene);
    const NearTip tip = gl_near_tip(scene.camera, scene_magnitude(casters, scene.lights, scene.camera));
    const CameraFrame f = camera_frame(scene.camera);
    const double n = scene.camera.near_plane;
    EXPECT_TRUE(in_tip(tip, f.eye));
    for (double a : {-1.0, 0.0, 1.0})
      for (double b : {-1.0, 0.0, 1.0}) {
        Vec3 p{};
        for (std::size_t k = 0; k < 3; ++k)
          p[k] = f.eye[k] + n * (f.forward[k] + a * f.half_width * f.right[k] + b * f.half_height * f.up[k]);
        EXPECT_TRUE(in_tip(tip, p)) << a << ", " << b;
      }
    // In GL's own matrices the enlarged corners lie beyond the viewport and the near plane.
    const glm::dmat4 world_to_clip = gpu::projection_matrix(scene.camera) * gpu::view_matrix(scene.camera);
    for (const Vec3& c : tip.corners) {
      const glm::dvec4 clip = world_to_clip * glm::dvec4(c[0], c[1], c[2], 1.0);
      EXPECT_GT(clip.w, n);  // view depth beyond the near plane
      EXPECT_GT(std::abs(clip.x / clip.w), 1.0);
      EXPECT_GT(std::abs(clip.y / clip.w), 1.0);
    }
    const glm::dvec4 apex = gpu::view_matrix(scene.camera) * glm::dvec4(tip.apex[0], tip.apex[1], tip.apex[2], 1.0);
    EXPECT_GT(apex.z, 0.0) << "the apex lies behind the eye";
  }
}

TEST(GlNearTip, BadMagnitude_Throws) {
  const Camera camera;
  EXPECT_THROW((void)gl_near_tip(camera, -1.0), std::invalid_argument);
  EXPECT_THROW((void)gl_near_tip(camera, std::numeric_limits<double>::infinity()), std::invalid_argument);
}

TEST(ChooseStencil, DefaultScene_AutoPicksProvenZPass) {
  const Loaded l = prepared("data/scenes/default.json");
  const std::vector<LightStencil> s = choose_stencil(StencilChoice::automatic, l.inputs, l.scene.lights, l.scene.camera);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].method, gpu::StencilMethod::zpass);
  ASSERT_TRUE(s[0].proof);
  EXPECT_EQ(s[0].proof->verdict, ZPassVerdict::proven);
  EXPECT_EQ(s[0].proof->apex_count, 0u);
  EXPECT_EQ(stencil_reason(s[0]), "proven");
  EXPECT_EQ(describe_stencil(s[0]), "zpass (proven: no face of the exact chain meets the near tip, n = 0 there)");
  EXPECT_EQ(stencil_methods(s), std::vector<gpu::StencilMethod>{gpu::StencilMethod::zpass});
}

TEST(ChooseStencil, CameraInsideVolume_AutoPicksZFailForBothLights) {
  const Loaded l = prepared("data/scenes/hard/camera_inside_volume.json");
  const std::vector<LightStencil> s = choose_stencil(StencilChoice::automatic, l.inputs, l.scene.lights, l.scene.camera);
  ASSERT_EQ(s.size(), 2u);
  for (const LightStencil& light : s) {
    EXPECT_EQ(light.method, gpu::StencilMethod::zfail);
    ASSERT_TRUE(light.proof);
    EXPECT_EQ(light.proof->verdict, ZPassVerdict::camera_in_volume);
    EXPECT_EQ(light.proof->apex_count, 2u);
    EXPECT_EQ(stencil_reason(light), "camera_in_volume");
    EXPECT_EQ(describe_stencil(light), "zfail (camera in volume: n(eye) = 2)");
  }
}

TEST(ChooseStencil, SceneAt1e6_FloatMarginReachesTheRoomSoZFail) {
  const Loaded l = prepared("data/scenes/hard/offset_1e6.json");
  for (const LightStencil& s : choose_stencil(StencilChoice::automatic, l.inputs, l.scene.lights, l.scene.camera)) {
    EXPECT_EQ(s.method, gpu::StencilMethod::zfail);
    ASSERT_TRUE(s.proof);
    EXPECT_EQ(s.proof->verdict, ZPassVerdict::face_meets_tip);
    EXPECT_NE(describe_stencil(s).find("face meets the near tip"), std::string::npos);
  }
}

TEST(ChooseStencil, RequestedMethods_HaveNoProof) {
  const Loaded l = prepared("data/scenes/hard/camera_inside_volume.json");
  for (const auto& [choice, method] : {std::pair{StencilChoice::zfail, gpu::StencilMethod::zfail},
                                       std::pair{StencilChoice::zpass, gpu::StencilMethod::zpass}}) {
    for (const LightStencil& s : choose_stencil(choice, l.inputs, l.scene.lights, l.scene.camera)) {
      EXPECT_EQ(s.method, method);
      EXPECT_FALSE(s.proof);
      EXPECT_EQ(stencil_reason(s), "requested");
    }
  }
}

TEST(StencilChoiceName, RoundTrips) {
  for (StencilChoice c : {StencilChoice::zfail, StencilChoice::zpass, StencilChoice::automatic})
    EXPECT_EQ(parse_stencil_choice(stencil_choice_name(c)), c);
  EXPECT_EQ(stencil_choice_name(StencilChoice::automatic), "auto");
  EXPECT_EQ(parse_stencil_choice("automatic"), std::nullopt);
}

}  // namespace
}  // namespace shadowcert
