// `shadowcert diff --edges` as users run it (docs/edge-maps.md#scores): every filter's edge map
// scored against the exact edge ground truth joins the diff's table, its JSON (key edge_maps),
// its --out files and its report; the scores never change the exit code. diff renders: without
// an EGL device it exits 2 naming EGL, and this test skips.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;

using namespace shadowcert::cli_test;

TEST(CliDiffEdges, ScoresJoinTheTableJsonFilesAndReport) {
  const fs::path dir = temp_dir("diff_edges_test");
  const std::string scene = std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/default.json";
  const RunResult r = run_cli("diff " + scene + " --size 160x120 --methods cpu --edges --out " + (dir / "out").string() +
                              " --json " + (dir / "diff.json").string() + " --report " + (dir / "diff.html").string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("edge maps against the exact ground truth"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("diagonal  profile"), std::string::npos) << r.output;

  const nlohmann::json j = read_json(dir / "diff.json");
  ASSERT_TRUE(j.contains("edge_maps"));
  const nlohmann::json& e = j["edge_maps"];
  EXPECT_GT(e["truth"]["profile_pixels"].get<int>(), 100);
  EXPECT_EQ(e["tolerances"], nlohmann::json({"1px", "2px", "bsds"}));
  for (const char* filter : {"diagonal", "c1", "sobel"})
    for (const char* cls : {"profile", "inner", "any"})
      for (const char* tolerance : {"1px", "2px", "bsds"}) {
        const nlohmann::json& m = e["filters"][filter][cls][tolerance];
        for (const char* key : {"precision", "recall", "f1"}) {
          EXPECT_GE(m[key].get<double>(), 0.0) << filter << " " << cls << " " << tolerance << " " << key;
          EXPECT_LE(m[key].get<double>(), 1.0) << filter << " " << cls << " " << tolerance << " " << key;
        }
      }
  // Every filter finds most of the scene's edges in the any class, within a pixel.
  for (const char* filter : {"diagonal", "c1", "sobel"})
    EXPECT_GT(e["filters"][filter]["any"]["1px"]["f1"].get<double>(), 0.8) << filter;
  for (const char* file : {"edge_truth.png", "edge_c1_profile_map.png", "edge_sobel_any_verdicts.png"})
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  const std::string page = read_text(dir / "diff.html");
  EXPECT_NE(page.find("edge_diagonal_inner_verdicts"), std::string::npos);
  EXPECT_NE(page.find("edges, c1 any"), std::string::npos);
  // Without --edges nothing of it.
  const RunResult plain = run_cli("diff " + scene + " --size 64x48 --methods cpu --json " + (dir / "plain.json").string());
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_FALSE(read_json(dir / "plain.json").contains("edge_maps"));
  fs::remove_all(dir);
}

}  // namespace
