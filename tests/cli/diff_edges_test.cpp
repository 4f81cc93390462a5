// `shadowcert diff --edges` as users run it (docs/edge-maps.md#scores): every filter's edge map
// scored against the exact edge ground truth joins the diff's table, its JSON (key edge_maps),
// its --out files and its report; the scores never change the exit code. diff renders: without
// an EGL device it exits 2 naming EGL, and this test skips.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace {

namespace fs = std::filesystem;

struct RunResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

RunResult run_cli(const std::string& arguments) {
  const std::string command = std::string(SHADOWCERT_CLI) + " " + arguments + " 2>&1";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) result.output += buffer;
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

TEST(CliDiffEdges, ScoresJoinTheTableJsonFilesAndReport) {
  const fs::path dir = fs::temp_directory_path() / ("shadowcert_diff_edges_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string scene = std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/default.json";
  const RunResult r = run_cli("diff " + scene + " --size 160x120 --methods cpu --edges --out " + (dir / "out").string() +
                              " --json " + (dir / "diff.json").string() + " --report " + (dir / "diff.html").string());
  if (r.exit_code == 2 && r.output.find("EGL") != std::string::npos) GTEST_SKIP() << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("edge maps against the exact ground truth"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("diagonal  profile"), std::string::npos) << r.output;

  std::ifstream in(dir / "diff.json");
  const nlohmann::json j = nlohmann::json::parse(in);
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
  std::ifstream html(dir / "diff.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("edge_diagonal_inner_verdicts"), std::string::npos);
  EXPECT_NE(page.find("edges, c1 any"), std::string::npos);
  // Without --edges nothing of it.
  const RunResult plain = run_cli("diff " + scene + " --size 64x48 --methods cpu --json " + (dir / "plain.json").string());
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  std::ifstream plain_in(dir / "plain.json");
  EXPECT_FALSE(nlohmann::json::parse(plain_in).contains("edge_maps"));
  fs::remove_all(dir);
}

}  // namespace
