// pipeline/bench_suite.h without GL: the run matrix, --methods selection, the suites' scene
// lists and the shard rule (docs/bench.md). The runs themselves: tests/cli/bench_command_test.cpp.
#include "pipeline/bench_suite.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>

namespace shadowcert {
namespace {

std::vector<std::string> ids(const std::vector<BenchVariant>& variants) {
  std::vector<std::string> out;
  for (const BenchVariant& v : variants) out.push_back(v.id);
  return out;
}

TEST(BenchVariants, TheMatrix_UniqueIdsInFamilyOrder) {
  const std::vector<BenchVariant> all = bench_variants();
  const std::vector<std::string> names = ids(all);
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
  EXPECT_EQ(names.front(), "cpu");
  for (const char* id : {"cs/exact", "cs/float", "pertri/float", "shadowmap/512", "shadowmap/4096", "pcf/9", "pcss",
                         "smoothie/R/4", "smoothie/R", "discrete", "accurate", "smooth/0.1", "smooth/0.003",
                         "smooth-gpu/0.01"})
    EXPECT_NE(std::find(names.begin(), names.end(), id), names.end()) << id;
  for (const BenchVariant& v : all) {
    SCOPED_TRACE(v.id);
    EXPECT_EQ(v.family == BenchFamily::shadow_map, gpu::uses_shadow_map(v.method));
    EXPECT_EQ(v.family == BenchFamily::silhouette, gpu::is_silhouette_method(v.method));
    // Robust: the chain methods with exact signs, and discrete.
    const bool robust = v.id == "cpu" || v.id == "discrete" || v.id.find("/exact") != std::string::npos;
    EXPECT_EQ(v.robust(), robust);
  }
}

TEST(BenchVariants, RayTraced_RtAndRtRobustAfterTheGlRunsNeverRobust) {
  const std::vector<BenchVariant> all = bench_variants();
  const std::vector<std::string> names = ids(all);
  const auto rt = std::find(names.begin(), names.end(), "rt");
  ASSERT_NE(rt, names.end());
  ASSERT_NE(rt + 1, names.end());
  EXPECT_EQ(*(rt + 1), "rt-robust");
  EXPECT_EQ(*(rt - 1), "smooth-gpu/0.01") << "after the GL methods' runs";
  for (const BenchVariant& v : all) {
    if (v.family != BenchFamily::ray_traced) continue;
    EXPECT_FALSE(v.robust()) << v.id;
    EXPECT_EQ(method_of(v), v.id);
  }
  EXPECT_EQ(ids(select_bench_variants("rt-robust,cpu")), (std::vector<std::string>{"cpu", "rt-robust"}));
  EXPECT_EQ(bench_family_name(BenchFamily::ray_traced), "ray_traced");
}

TEST(BenchVariants, Selection_ByMethodOrId_InTheMatrixOrder) {
  EXPECT_EQ(ids(select_bench_variants("pcf,cpu")), (std::vector<std::string>{"cpu", "pcf/3", "pcf/5", "pcf/9"}));
  EXPECT_EQ(ids(select_bench_variants("smooth/0.01,cs/float")), (std::vector<std::string>{"cs/float", "smooth/0.01"}));
  EXPECT_EQ(select_bench_variants("all").size(), bench_variants().size());
  EXPECT_EQ(select_bench_variants("").size(), bench_variants().size());
  EXPECT_THROW((void)select_bench_variants("cpu,bogus"), std::invalid_argument);
  EXPECT_THROW((void)select_bench_variants("cs/half"), std::invalid_argument);
}

TEST(BenchSuite, DefaultAndHard_AreTheSceneFolders) {
  const BenchPaths paths{SHADOWCERT_SOURCE_DIR, SHADOWCERT_SHARED_DATA};
  const std::vector<BenchSceneSpec> d = bench_suite("default", paths);
  ASSERT_FALSE(d.empty());
  EXPECT_TRUE(std::none_of(d.begin(), d.end(), [](const BenchSceneSpec& s) { return s.name == "sphere_grid_1m"; }));
  EXPECT_TRUE(std::is_sorted(d.begin(), d.end(), [](const BenchSceneSpec& a, const BenchSceneSpec& b) {
    return a.name < b.name;
  }));
  EXPECT_EQ(d.front().input.rfind("data/scenes/", 0), 0u) << d.front().input;
  const std::vector<BenchSceneSpec> h = bench_suite("hard", paths);
  EXPECT_GE(h.size(), 10u);
  for (const BenchSceneSpec& s : h) EXPECT_EQ(s.suite, "hard");
  const std::vector<BenchSceneSpec> all = bench_suite("all", paths);
  EXPECT_EQ(all.size(), d.size() + h.size() + real_meshes().size() + 16);
  std::set<std::string> keys;
  for (const BenchSceneSpec& s : all) EXPECT_TRUE(keys.insert(s.suite + "/" + s.name).second) << s.name;
  EXPECT_THROW((void)bench_suite("bogus", paths), std::invalid_argument);
}

TEST(BenchSuite, Analytic_SixteenGeneratedScenesWithTheFloorPlane) {
  const std::vector<BenchSceneSpec> a = bench_suite("analytic", {SHADOWCERT_SOURCE_DIR, SHADOWCERT_SHARED_DATA});
  ASSERT_EQ(a.size(), 16u);
  EXPECT_EQ(a.front().name, "sphere8x4-point");
  EXPECT_EQ(a.back().name, "ellipsoid32x16-sun");
  for (const BenchSceneSpec& s : a) {
    ASSERT_TRUE(s.receiver_plane.has_value());
    EXPECT_DOUBLE_EQ(s.receiver_plane->point[1], -1.5);
  }
  const Scene scene = load_bench_scene(a[1], 40, 30);
  EXPECT_EQ(scene.camera.width, 40u);
  EXPECT_TRUE(scene.meshes[1].ellipsoid.has_value());
}

// Without the developer meshes the real suite still runs the bundled ones (data/meshes/), and
// names each missing one instead of throwing.
TEST(BenchSuite, Real_BundledMeshesFromTheRepositoryMissingOnesNamed) {
  const std::vector<BenchSceneSpec> r = bench_suite("real", {SHADOWCERT_SOURCE_DIR, "/nonexistent/shared"});
  ASSERT_EQ(r.size(), real_meshes().size());
  std::size_t bundled = 0;
  for (const BenchSceneSpec& s : r) {
    SCOPED_TRACE(s.name);
    EXPECT_TRUE(s.framed);
    if (s.input.rfind("data/meshes/", 0) == 0) {
      ++bundled;
      EXPECT_TRUE(s.missing.empty()) << s.missing;
      EXPECT_TRUE(std::filesystem::exists(s.file));
    } else {
      EXPECT_NE(s.missing.find("is not here"), std::string::npos);
    }
  }
  EXPECT_EQ(bundled, 4u);  // spot, trimesh_bunny, thingi10k_65004, trimesh_featuretype
}

TEST(BenchSuite, SceneFiles_JsonAsIsMeshesFramedNamesUnique) {
  const std::vector<BenchSceneSpec> s = bench_scene_files({"a/x.json", "b/x.json", "c/m.obj"}, false);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].name, "x");
  EXPECT_EQ(s[1].name, "x-2");
  EXPECT_FALSE(s[0].framed);
  EXPECT_TRUE(s[2].framed);
  EXPECT_EQ(s[2].suite, "scenes");
  EXPECT_EQ(bench_scene_files({"m.obj"}, true)[0].suite, "real");
}

TEST(BenchShard, EverySceneInExactlyOneShard) {
  for (std::size_t n = 1; n <= 5; ++n)
    for (std::size_t i = 0; i < 23; ++i) {
      std::size_t shards = 0;
      for (std::size_t k = 1; k <= n; ++k) shards += in_shard(i, k, n) ? 1 : 0;
      EXPECT_EQ(shards, 1u) << i << " of " << n;
    }
  EXPECT_TRUE(in_shard(0, 1, 3));
  EXPECT_TRUE(in_shard(4, 2, 3));
  EXPECT_FALSE(in_shard(4, 1, 3));
}

}  // namespace
}  // namespace shadowcert
