// pipeline/silhouette_volumes.h: every mesh of a scene cast by its smooth-silhouette volume or,
// when it does not qualify, by the robust chain; every light's volume closed.
#include "pipeline/silhouette_volumes.h"

#include <gtest/gtest.h>

#include <filesystem>

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
  scene.meshes = {{"fan", nonmanifold_fan(4)}};
  scene.lights = {Light{{0.3, 5.0, 0.2, 1.0}}};
  const SilhouetteVolumes v = silhouette_volumes(scene.meshes, scene.lights, gpu::ShadowMethod::smooth);
  ASSERT_EQ(v.casters.size(), 1u);
  EXPECT_FALSE(v.casters[0].smooth);
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

}  // namespace
