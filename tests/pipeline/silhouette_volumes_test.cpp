// pipeline/silhouette_volumes.h: every mesh of a scene cast by its smooth-silhouette volume or,
// when it does not qualify, by the robust chain; every light's volume closed; a mesh's own
// "silhouette", "epsilon" and "casts" (core/scene.h) obeyed for that mesh only.
#include "pipeline/silhouette_volumes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <vector>

#include "core/float_rounding.h"
#include "exact/cpu_volume.h"
#include "exact/volume_closure.h"
#include "io/soup_file.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_file.h"

namespace {

using namespace shadowcert;

Scene load(const std::string& name) {
  return load_scene(std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "scenes" / name,
                    [](const std::filesystem::path& f) { return read_soup(f); });
}

TEST(SilhouetteVolumes, BundledScenes_EveryMethodEveryLightClosed) {
  for (const char* name : {"default.json", "closed_casters.json", "smooth_sphere.json", "hard/light_inside_closed_caster.json"}) {
    const Scene scene = load(name);
    for (gpu::ShadowMethod method : gpu::kSilhouetteMethods) {
      SCOPED_TRACE(std::string(name) + ", " + std::string(gpu::shadow_method_name(method)));
      const SilhouetteVolumes v = silhouette_volumes(scene.meshes, scene.lights, method);
      ASSERT_EQ(v.per_light.size(), scene.lights.size());
      ASSERT_EQ(v.casters.size(), scene.meshes.size());
      for (const HomogeneousMesh& mesh : v.per_light) EXPECT_TRUE(certify_volume_closure(mesh).certificate.closed);
    }
  }
}

TEST(SilhouetteVolumes, NonManifoldMesh_IsCastByTheRobustChainAndSaysWhy) {
  Scene scene;
  SceneMesh& fan = scene.meshes.emplace_back();
  fan.name = "fan";
  fan.soup = nonmanifold_fan(4);
  scene.lights = {Light{{0.3, 5.0, 0.2, 1.0}}};
  const SilhouetteVolumes v = silhouette_volumes(scene.meshes, scene.lights, gpu::ShadowMethod::smooth);
  ASSERT_EQ(v.casters.size(), 1u);
  EXPECT_FALSE(v.casters[0].cast_by.has_value());
  EXPECT_NE(v.casters[0].qualification.find("non-manifold edge"), std::string::npos);
  // Exactly the robust chain of the float-rounded input.
  const CanonicalSoup canonical = canonical_soup(nonmanifold_fan(4));
  const HomogeneousMesh chain = cpu_volume_mesh(canonical.soup, build_edge_table(canonical.soup), scene.lights[0]);
  EXPECT_EQ(v.per_light[0].triangles, chain.triangles);
  EXPECT_EQ(v.per_light[0].vertices, chain.vertices);
}

TEST(SilhouetteVolumes, NotASilhouetteMethodOrBadEpsilon_Throws) {
  const Scene scene = load("smooth_sphere.json");
  EXPECT_THROW((void)silhouette_volumes(scene.meshes, scene.lights, gpu::ShadowMethod::cs), std::invalid_argument);
  EXPECT_THROW((void)silhouette_volumes(scene.meshes, scene.lights, gpu::ShadowMethod::smooth, {0.0, 60.0}),
               std::invalid_argument);
}

// A 12x6 sphere (it qualifies) named `name`.
SceneMesh sphere_at(const std::string& name, const Vec3& centre) {
  SceneMesh mesh;
  mesh.name = name;
  mesh.soup = uv_sphere(centre, 1.0, 12, 6);
  return mesh;
}

const std::vector<Light> kLights{Light{{0.6, 3.6, 0.4, 1.0}}, Light{{-2.0, 5.0, 1.0, 0.0}}};

// The first light's volume of `meshes` under `method`.
HomogeneousMesh first_volume(const std::vector<SceneMesh>& meshes, gpu::ShadowMethod method,
                             const SilhouetteOptions& options = {}) {
  return silhouette_volumes(meshes, kLights, method, options).per_light.front();
}

// `a` then `b`, as silhouette_volumes appends the meshes' volumes in their order.
HomogeneousMesh joined(HomogeneousMesh a, const HomogeneousMesh& b) {
  const auto offset = static_cast<std::uint32_t>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return a;
}

void expect_same_mesh(const HomogeneousMesh& got, const HomogeneousMesh& expected) {
  EXPECT_EQ(got.vertices, expected.vertices);
  EXPECT_EQ(got.triangles, expected.triangles);
}

TEST(SilhouetteVolumes, MeshAsksForTheChain_IsCastByTheRobustChainUnderEveryMethod) {
  SceneMesh sphere = sphere_at("sphere", {0, 1.2, 0});
  sphere.silhouette = MeshSilhouette::chain;
  const CanonicalSoup canonical = canonical_soup(float_rounded(sphere.soup));
  const EdgeTable table = build_edge_table(canonical.soup);
  for (gpu::ShadowMethod method : gpu::kSilhouetteMethods) {
    SCOPED_TRACE(std::string(gpu::shadow_method_name(method)));
    const SilhouetteVolumes v = silhouette_volumes(std::vector{sphere}, kLights, method);
    ASSERT_EQ(v.casters.size(), 1u);
    // The sphere qualifies, yet the scene's word wins, and the report says it was the scene's.
    EXPECT_FALSE(v.casters[0].cast_by.has_value());
    EXPECT_EQ(v.casters[0].qualification, "the scene asks for the chain");
    for (std::size_t k = 0; k < kLights.size(); ++k)
      expect_same_mesh(v.per_light[k], cpu_volume_mesh(canonical.soup, table, kLights[k]));
  }
}

TEST(SilhouetteVolumes, MeshSilhouette_OverridesTheCommandsMethodForThatMeshOnly) {
  SceneMesh asks_discrete = sphere_at("a", {-2, 1.2, 0});
  asks_discrete.silhouette = MeshSilhouette::discrete;
  const SceneMesh plain = sphere_at("b", {2, 1.2, 0});
  const SilhouetteVolumes v = silhouette_volumes(std::vector{asks_discrete, plain}, kLights, gpu::ShadowMethod::smooth);
  ASSERT_EQ(v.casters.size(), 2u);
  EXPECT_EQ(v.casters[0].cast_by, gpu::ShadowMethod::discrete);
  EXPECT_EQ(v.casters[1].cast_by, gpu::ShadowMethod::smooth);
  // Exactly the volume each mesh casts alone under its method.
  SceneMesh a_alone = asks_discrete;
  a_alone.silhouette.reset();
  expect_same_mesh(v.per_light.front(), joined(first_volume({a_alone}, gpu::ShadowMethod::discrete),
                                               first_volume({plain}, gpu::ShadowMethod::smooth)));
  // And a mesh asking for smooth is cast smooth under discrete.
  SceneMesh asks_smooth = plain;
  asks_smooth.silhouette = MeshSilhouette::smooth;
  const SilhouetteVolumes w = silhouette_volumes(std::vector{asks_smooth}, kLights, gpu::ShadowMethod::discrete);
  EXPECT_EQ(w.casters[0].cast_by, gpu::ShadowMethod::smooth);
  expect_same_mesh(w.per_light.front(), first_volume({plain}, gpu::ShadowMethod::smooth));
}

TEST(SilhouetteVolumes, MeshEpsilon_OverridesTheOptionWheneverTheMeshIsCastSmooth) {
  SceneMesh own = sphere_at("a", {-2, 1.2, 0});
  own.epsilon = 0.05;
  const SceneMesh plain = sphere_at("b", {2, 1.2, 0});
  const SceneMesh own_plain = sphere_at("a", {-2, 1.2, 0});
  const SilhouetteOptions wide{0.05, kDefaultCreaseAngleDegrees};
  // Otherwise the test could not tell the two epsilons apart.
  ASSERT_NE(first_volume({own_plain}, gpu::ShadowMethod::smooth, wide).vertices,
            first_volume({own_plain}, gpu::ShadowMethod::smooth).vertices);

  const SilhouetteVolumes v = silhouette_volumes(std::vector{own, plain}, kLights, gpu::ShadowMethod::smooth);
  EXPECT_EQ(v.casters[0].epsilon, 0.05);
  EXPECT_EQ(v.casters[1].epsilon, kDefaultContourEpsilon);
  expect_same_mesh(v.per_light.front(), joined(first_volume({own_plain}, gpu::ShadowMethod::smooth, wide),
                                               first_volume({plain}, gpu::ShadowMethod::smooth)));

  // Under discrete the mesh's epsilon is unused until the mesh itself asks for smooth.
  EXPECT_EQ(silhouette_volumes(std::vector{own}, kLights, gpu::ShadowMethod::discrete).casters[0].epsilon, 0.0);
  own.silhouette = MeshSilhouette::smooth;
  const SilhouetteVolumes w = silhouette_volumes(std::vector{own}, kLights, gpu::ShadowMethod::discrete);
  EXPECT_EQ(w.casters[0].epsilon, 0.05);
  expect_same_mesh(w.per_light.front(), first_volume({own_plain}, gpu::ShadowMethod::smooth, wide));
}

TEST(SilhouetteVolumes, NonCastingMesh_IsInNoVolumeAndReportedAsCastingNothing) {
  SceneMesh floor;
  floor.name = "floor";
  floor.soup = floor_quad(6.0);
  const SceneMesh sphere = sphere_at("sphere", {0, 1.2, 0});
  // A casting floor does cast, so an unchanged volume below is the key at work.
  ASSERT_FALSE(first_volume({floor}, gpu::ShadowMethod::smooth).triangles.empty());
  floor.casts = false;
  for (gpu::ShadowMethod method : gpu::kSilhouetteMethods) {
    SCOPED_TRACE(std::string(gpu::shadow_method_name(method)));
    const SilhouetteVolumes v = silhouette_volumes(std::vector{floor, sphere}, kLights, method);
    ASSERT_EQ(v.casters.size(), 2u);
    EXPECT_FALSE(v.casters[0].casts);
    EXPECT_FALSE(v.casters[0].cast_by.has_value());
    EXPECT_EQ(v.casters[0].qualification, "the scene says it casts nothing");
    const SilhouetteVolumes alone = silhouette_volumes(std::vector{sphere}, kLights, method);
    for (std::size_t k = 0; k < kLights.size(); ++k) expect_same_mesh(v.per_light[k], alone.per_light[k]);
  }
}

TEST(SilhouetteVolumes, MeshEpsilonNotPositiveOrNotFinite_Throws) {
  for (double bad : {0.0, -0.01, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    SceneMesh sphere = sphere_at("sphere", {0, 1.2, 0});
    sphere.epsilon = bad;
    EXPECT_THROW((void)silhouette_volumes(std::vector{sphere}, kLights, gpu::ShadowMethod::smooth),
                 std::invalid_argument);
  }
}

}  // namespace
