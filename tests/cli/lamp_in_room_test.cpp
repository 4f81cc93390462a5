// A point light at the exact centre of the scene's bounds (data/scenes/lamp_in_room.json: a lamp
// in a closed room): a valid scene that exited 3 ("a bug") from render with a shadow-map method,
// diff, diff --soft, edges and bench, where the map's frustum, the soft reference's disk and the
// light-space smoothies each threw for a light with no direction to aim at. Now every command
// answers: the shadow-map family draws the light with a cube map (gpu/shadow_map_renderer.h),
// the soft reference samples a ball around it (reference/disk_light.h), and no command exits 3.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using namespace shadowcert::cli_test;

const std::string kLamp = std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/lamp_in_room.json";

TEST(CliLampInRoom, RenderEveryShadowMapMethod_ACubeMapAndShadows) {
  const fs::path dir = temp_dir("lamp_in_room_test");
  for (const char* method : {"shadowmap", "pcf", "pcss", "smoothie", "cpu"}) {
    const fs::path json = dir / (std::string(method) + ".json");
    const RunResult r = run_cli("render " + kLamp + " --size 64x48 --method " + method + " --json " + json.string());
    SHADOWCERT_SKIP_WITHOUT_GL(r);
    ASSERT_EQ(r.exit_code, 0) << method << "\n" << r.output;
    const nlohmann::json j = read_json(json);
    EXPECT_GT(j["shadowed_pixels"].get<int>(), 100) << method;  // the table's shadow on the floor at least
    EXPECT_GT(j["lit_pixels"].get<int>(), 1000) << method;
    if (std::string(method) != "cpu") {
      EXPECT_EQ(j["cube_lights"], nlohmann::json::array({0})) << method;
      EXPECT_NE(r.output.find("light 0: inside or next to the scene's bounds: a cube map"), std::string::npos)
          << r.output;
    }
  }
  // Light-space smoothies measure their width at the light's distance to the bounds' centre: zero here.
  const RunResult light_space =
      run_cli("render " + kLamp + " --size 64x48 --method smoothie --smoothie-space light");
  EXPECT_EQ(light_space.exit_code, 0) << light_space.output;
}

TEST(CliLampInRoom, DiffWithSoftAndEdges_EveryMethodAnswers) {
  const fs::path json = temp_dir("lamp_in_room_test") / "diff.json";
  const RunResult r = run_cli("diff " + kLamp + " --size 64x48 --methods cpu,cs,shadowmap,pcf,pcss,smoothie --soft "
                              "--samples 16 --edges --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;  // 1 would be a robust method's hard error
  const nlohmann::json j = read_json(json);
  for (const char* m : {"cpu", "cs", "shadowmap", "pcf", "pcss", "smoothie"}) {
    ASSERT_TRUE(j["methods"].contains(m)) << m;
    EXPECT_EQ(j["methods"][m]["failed"], false) << m;
    ASSERT_EQ(j["methods"][m]["per_light"].size(), 1u) << m;
    EXPECT_GT(j["methods"][m]["per_light"][0]["soft"]["compared"].get<int>(), 1000) << m;
  }
  EXPECT_EQ(j["methods"]["cpu"]["hard_errors"], 0);
  // The cube map's hard shadow agrees with the exact image but on a few boundary pixels.
  EXPECT_LE(j["methods"]["shadowmap"]["hard_errors"].get<int>(), 15);
  ASSERT_EQ(j["soft_reference"]["per_light"].size(), 1u);
  EXPECT_GT(j["soft_reference"]["per_light"][0]["penumbra"].get<int>(), 0);
  EXPECT_TRUE(j.contains("edge_maps"));
}

TEST(CliLampInRoom, SoftReference_ABallAroundTheLamp) {
  const fs::path json = temp_dir("lamp_in_room_test") / "soft.json";
  const RunResult r = run_cli("soft " + kLamp + " --size 64x48 --samples 16 --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["light_shape"], "ball");
  EXPECT_EQ(j["samples"], 16);
  EXPECT_GT(j["pixels"]["penumbra"].get<int>(), 0);
  EXPECT_GT(j["pixels"]["umbra"].get<int>(), 0);
}

TEST(CliLampInRoom, EdgesWithEveryShadowMapMethod_ExitZero) {
  for (const char* method : {"shadowmap", "pcf", "pcss", "smoothie"}) {
    const RunResult r = run_cli("edges " + kLamp + " --size 64x48 --style gooch --shadows " + method);
    SHADOWCERT_SKIP_WITHOUT_GL(r);
    EXPECT_EQ(r.exit_code, 0) << method << "\n" << r.output;
  }
}

TEST(CliLampInRoom, BenchOfTheShadowMapFamily_EveryRunAnswers) {
  const fs::path dir = empty_temp_dir("lamp_in_room_test", "bench");
  const RunResult r = run_cli("bench " + kLamp + " --size 64x48 --frames 1 --no-plots --methods "
                              "shadowmap,pcf,pcss,smoothie --out " + dir.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(dir / "bench.json");
  ASSERT_EQ(j["scenes"].size(), 1u);
  const nlohmann::json& runs = j["scenes"][0]["runs"];
  EXPECT_GE(runs.size(), 4u);
  for (const nlohmann::json& run : runs) EXPECT_EQ(run["failed"], false) << run.dump();
}

}  // namespace
