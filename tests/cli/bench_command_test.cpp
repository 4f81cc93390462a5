// `shadowcert bench` as users run it (docs/bench.md): on a tiny scene at a tiny size it writes
// every output, bench.json has the keys of its schema, bad options exit 2 naming the option, the
// shards split a suite's scenes by index, and --from rewrites the outputs from a bench.json.
// bench renders: without an EGL device it exits 2 naming EGL, and these tests skip.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;

using namespace shadowcert::cli_test;

const std::string kSource = SHADOWCERT_SOURCE_DIR;
const std::string kDefaultScene = kSource + "/data/scenes/default.json";
const std::string kSoftContact = kSource + "/data/scenes/soft_contact.json";
const std::string kSphere = kSource + "/data/scenes/smooth_sphere.json";
// A small run: one run of each family (cs: both signs), tiny images, one timed frame.
const std::string kTinyRun = " --size 32x24 --frames 1 --methods cpu,cs,shadowmap/512,pcf/3,smooth/0.01,edges/sobel";

// One bench of default.json shared by the tests that read its outputs.
class BenchOutputs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(empty_temp_dir("bench_test", "outputs"));
    run_ = new RunResult(run_cli("bench " + kDefaultScene + kTinyRun + " --out " + dir_->string()));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete run_;
  }
  void SetUp() override {
    if (render_unavailable(*run_)) GTEST_SKIP() << run_->output;
    ASSERT_EQ(run_->exit_code, 0) << run_->output;
  }
  static fs::path* dir_;
  static RunResult* run_;
};
fs::path* BenchOutputs::dir_ = nullptr;
RunResult* BenchOutputs::run_ = nullptr;

}  // namespace

TEST_F(BenchOutputs, TinyScene_WritesEveryOutput) {
  for (const char* file : {"bench.json", "bench.csv", "bench.md", "report.html", "images/scenes/default/exact_counts.png",
                           "images/scenes/default/exact_mask.png", "images/scenes/default/cpu_overlay.png",
                           "images/scenes/default/cs-float_overlay.png",
                           "images/scenes/default/shadowmap-512_soft_error.png"})
    EXPECT_TRUE(fs::exists(*dir_ / file)) << file;
  // The plots need a python3 with matplotlib; without one the command says so and goes on.
  if (run_->output.find("plots not drawn") == std::string::npos) {
    EXPECT_TRUE(fs::exists(*dir_ / "plots/index.json"));
    EXPECT_TRUE(fs::exists(*dir_ / "plots/time_vs_error_scenes.png"));
    EXPECT_TRUE(fs::exists(*dir_ / "plots/precision_recall.png"));
  }
}

TEST_F(BenchOutputs, BenchJson_HasTheSchemasKeys) {
  const nlohmann::json j = read_json(*dir_ / "bench.json");
  for (const char* key : {"schema", "command", "suite", "shard", "scene_count", "size", "warm_up_frames", "frames",
                          "methods", "environment", "seconds", "totals", "scenes"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["schema"], "shadowcert-bench/1");
  EXPECT_EQ(j["suite"], "scenes");
  EXPECT_EQ(j["shard"], (nlohmann::json{{"index", 1}, {"count", 1}}));
  EXPECT_EQ(j["size"], (nlohmann::json{32, 24}));
  EXPECT_EQ(j["frames"], 1);
  // --methods expanded to run ids, in the matrix's order.
  EXPECT_EQ(j["methods"],
            (nlohmann::json{"cpu", "cs/exact", "cs/float", "shadowmap/512", "pcf/3", "smooth/0.01", "edges/sobel"}));
  for (const char* key : {"renderer", "gl_version", "device", "software_renderer", "stage_sync", "build_type",
                          "git_commit", "git_dirty", "date", "version", "host"})
    EXPECT_TRUE(j["environment"].contains(key)) << key;
  EXPECT_FALSE(j["environment"]["renderer"].get<std::string>().empty());
  EXPECT_EQ(j["environment"]["build_type"].is_null() || j["environment"]["build_type"].is_string(), true);
  ASSERT_EQ(j["scenes"].size(), 1u);
  const nlohmann::json& scene = j["scenes"][0];
  for (const char* key : {"index", "suite", "name", "input", "skipped", "triangles", "lights", "size", "exact_seconds",
                          "soft_reference", "analytic", "edge_truth_seconds", "seconds", "images", "runs"})
    EXPECT_TRUE(scene.contains(key)) << key;
  EXPECT_EQ(scene["index"], 0);
  EXPECT_EQ(scene["name"], "default");
  EXPECT_TRUE(scene["skipped"].is_null());
  EXPECT_EQ(scene["triangles"], 56);
  EXPECT_FALSE(scene["soft_reference"].is_null());  // a shadow-map run asks for it
  ASSERT_EQ(scene["runs"].size(), 7u);
  EXPECT_EQ(j["totals"], (nlohmann::json{{"scenes", 1}, {"skipped_scenes", 0}, {"runs", 7}, {"failed_runs", 0}}));
  for (const nlohmann::json& run : scene["runs"]) {
    SCOPED_TRACE(run["id"].get<std::string>());
    for (const char* key : {"id", "method", "family", "parameter", "robust", "failed", "time", "error"})
      EXPECT_TRUE(run.contains(key)) << key;
    for (const char* key : {"frame_ms", "gpu_ms", "cpu_ms", "build_ms"}) EXPECT_TRUE(run["time"].contains(key)) << key;
    const nlohmann::json& f = run["time"]["frame_ms"];
    EXPECT_LE(f["min"].get<double>(), f["median"].get<double>());
    EXPECT_LE(f["median"].get<double>(), f["max"].get<double>());
    EXPECT_GT(f["median"].get<double>(), 0.0);
    for (const char* key : {"hard_errors", "ambiguous", "agree", "coverage_errors", "lit_errors", "count_errors",
                            "closed", "volume_triangles", "capacity_error", "soft", "analytic", "contour", "edges",
                            "images"})
      EXPECT_TRUE(run["error"].contains(key)) << key;
    if (run["family"] == "edges") continue;  // no lit mask (below)
    EXPECT_GT(run["error"]["agree"].get<std::uint64_t>(), 0u);
    EXPECT_FALSE(run["error"]["soft"].is_null());
  }
  const nlohmann::json& cpu = scene["runs"][0];
  EXPECT_EQ(cpu["family"], "stencil");
  EXPECT_EQ(cpu["robust"], true);
  EXPECT_EQ(cpu["error"]["hard_errors"], 0);
  EXPECT_EQ(cpu["error"]["closed"], true);
  EXPECT_EQ(scene["runs"][2]["parameter"]["sign"], "float");
  EXPECT_EQ(scene["runs"][2]["robust"], false);  // the float baseline
  EXPECT_EQ(scene["runs"][3]["family"], "shadowmap");
  EXPECT_EQ(scene["runs"][3]["parameter"]["shadow_map_size"], 512);
  EXPECT_TRUE(scene["runs"][3]["error"]["closed"].is_null());
  EXPECT_EQ(scene["runs"][4]["parameter"]["pcf_kernel"], 3);
  EXPECT_EQ(scene["runs"][5]["family"], "silhouette");
  EXPECT_EQ(scene["runs"][5]["parameter"]["epsilon"], 0.01);
  const nlohmann::json& edges = scene["runs"][6];
  EXPECT_EQ(edges["family"], "edges");
  EXPECT_EQ(edges["method"], "edges");
  EXPECT_EQ(edges["parameter"]["filter"], "sobel");
  EXPECT_TRUE(edges["error"]["hard_errors"].is_null());
  ASSERT_FALSE(edges["error"]["edges"].is_null());
  for (const char* key : {"precision", "recall", "f1", "profile", "inner", "tolerance"})
    EXPECT_TRUE(edges["error"]["edges"].contains(key)) << key;
  EXPECT_GT(edges["error"]["edges"]["recall"].get<double>(), 0.0);
  EXPECT_TRUE(edges["time"]["gpu_ms"].contains("edge_filter"));
  EXPECT_TRUE(scene["edge_truth_seconds"].is_number());
}

TEST_F(BenchOutputs, CsvAndMarkdown_HoldEveryRun) {
  std::istringstream csv(read_text(*dir_ / "bench.csv"));
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(csv, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 8u);  // the header and seven runs
  EXPECT_EQ(lines[0].rfind("suite,scene,input,width,height,triangles,lights,run,method,family,", 0), 0u) << lines[0];
  EXPECT_NE(lines[2].find(",cs/exact,cs,stencil,exact,"), std::string::npos) << lines[2];
  const std::string md = read_text(*dir_ / "bench.md");
  for (const char* text : {"# shadowcert bench", "## Every run over the scenes", "| cs/float (baseline) |",
                           "## Soft-shadow error, scenes/default", "| shadowmap/512 |",
                           "## Edge maps against the exact edges", "| scenes/default | edges/sobel |"})
    EXPECT_NE(md.find(text), std::string::npos) << text;
  const std::string html = read_text(*dir_ / "report.html");
  EXPECT_NE(html.find("exact counts n(P)"), std::string::npos);  // the counts' legend
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
}

TEST_F(BenchOutputs, From_RewritesTheSameTablesWithoutRendering) {
  const fs::path again = empty_temp_dir("bench_test", "from");
  const RunResult r = run_cli("bench --from " + (*dir_ / "bench.json").string() + " --no-plots --out " + again.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_text(again / "bench.md"), read_text(*dir_ / "bench.md"));
  EXPECT_EQ(read_text(again / "bench.csv"), read_text(*dir_ / "bench.csv"));
  EXPECT_TRUE(fs::exists(again / "images/scenes/default/cpu_overlay.png"));
  EXPECT_NE(read_text(again / "report.html").find("data:image/png;base64,"), std::string::npos);
}

// Shard K of N runs the scenes whose index i has i % N == K - 1; together the shards run every
// scene once, with the single run's totals.
TEST(BenchShards, TwoShards_SplitTheScenesByIndex) {
  const std::string scenes = kDefaultScene + " " + kSoftContact + " " + kSphere;
  const std::string options = " --size 16x12 --frames 1 --methods cpu,shadowmap/512";
  const fs::path dir = empty_temp_dir("bench_test", "shards");
  const RunResult whole = run_cli("bench " + scenes + options + " --out " + (dir / "whole").string());
  if (render_unavailable(whole)) GTEST_SKIP() << whole.output;
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  std::set<std::string> names;
  std::size_t runs = 0;
  for (int k = 1; k <= 2; ++k) {
    const fs::path out = dir / ("shard" + std::to_string(k));
    const RunResult r = run_cli("bench " + scenes + options + " --shard " + std::to_string(k) + "/2 --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = read_json(out / "bench.json");
    EXPECT_EQ(j["shard"], (nlohmann::json{{"index", k}, {"count", 2}}));
    EXPECT_EQ(j["scene_count"], 3);
    for (const nlohmann::json& s : j["scenes"]) {
      EXPECT_EQ(s["index"].get<int>() % 2, k - 1);
      EXPECT_TRUE(names.insert(s["name"]).second) << s["name"];
    }
    EXPECT_EQ(j["scenes"].size(), k == 1 ? 2u : 1u);
    runs += j["totals"]["runs"].get<std::size_t>();
  }
  const nlohmann::json w = read_json(dir / "whole/bench.json");
  EXPECT_EQ(names, (std::set<std::string>{"default", "soft_contact", "smooth_sphere"}));
  EXPECT_EQ(runs, w["totals"]["runs"].get<std::size_t>());

  // `shadowcert merge` of the two shards is the whole run: its scenes in the same order with the
  // same runs, its totals; and `bench --from` makes its tables (docs/bench.md).
  const fs::path merged = dir / "merged.json";
  const RunResult m = run_cli("merge " + (dir / "shard2/bench.json").string() + " " +
                              (dir / "shard1/bench.json").string() + " --json " + merged.string());
  ASSERT_EQ(m.exit_code, 0) << m.output;
  const nlohmann::json j = read_json(merged);
  EXPECT_EQ(j["shard"], (nlohmann::json{{"index", 1}, {"count", 1}}));
  EXPECT_EQ(j["totals"], w["totals"]);
  ASSERT_EQ(j["scenes"].size(), w["scenes"].size());
  for (std::size_t i = 0; i < j["scenes"].size(); ++i) {
    EXPECT_EQ(j["scenes"][i]["index"], w["scenes"][i]["index"]);
    EXPECT_EQ(j["scenes"][i]["name"], w["scenes"][i]["name"]);
    ASSERT_EQ(j["scenes"][i]["runs"].size(), w["scenes"][i]["runs"].size());
    for (std::size_t r = 0; r < j["scenes"][i]["runs"].size(); ++r) {
      const nlohmann::json& a = j["scenes"][i]["runs"][r];
      const nlohmann::json& b = w["scenes"][i]["runs"][r];
      EXPECT_EQ(a["id"], b["id"]);
      // The exact figures do not depend on the shard (times do).
      EXPECT_EQ(a["error"]["hard_errors"], b["error"]["hard_errors"]) << a["id"];
      EXPECT_EQ(a["error"]["agree"], b["error"]["agree"]) << a["id"];
    }
  }
  const RunResult from = run_cli("bench --from " + merged.string() + " --no-plots --out " + (dir / "merged").string());
  ASSERT_EQ(from.exit_code, 0) << from.output;
  const std::string md = read_text(dir / "merged/bench.md");
  for (const char* scene : {"### scenes/default", "### scenes/soft_contact", "### scenes/smooth_sphere"})
    EXPECT_NE(md.find(scene), std::string::npos) << scene;
  fs::remove_all(dir);
}

// The analytic suite's first scene (shard 1 of 16): the silhouette runs' contour error against
// the conic, smooth below discrete on the 8x4 sphere (docs/smooth-silhouettes.md), and the
// per-pixel figures against the analytic shadow.
TEST(BenchAnalytic, FirstShapeUnderThePointLight_SmoothContourBeatsDiscrete) {
  const fs::path dir = empty_temp_dir("bench_test", "analytic");
  const RunResult r = run_cli("bench --suite analytic --shard 1/16 --size 32x24 --frames 1 --methods "
                              "discrete,smooth/0.01 --no-plots --out " + dir.string());
  if (render_unavailable(r)) GTEST_SKIP() << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(dir / "bench.json");
  EXPECT_EQ(j["scene_count"], 16);
  ASSERT_EQ(j["scenes"].size(), 1u);
  const nlohmann::json& scene = j["scenes"][0];
  EXPECT_EQ(scene["name"], "sphere8x4-point");
  EXPECT_TRUE(scene["soft_reference"].is_null());  // no shadow-map run
  ASSERT_FALSE(scene["analytic"].is_null());
  ASSERT_EQ(scene["runs"].size(), 2u);
  const nlohmann::json& discrete = scene["runs"][0]["error"];
  const nlohmann::json& smooth = scene["runs"][1]["error"];
  ASSERT_FALSE(discrete["contour"].is_null());
  ASSERT_FALSE(smooth["contour"].is_null());
  EXPECT_LT(smooth["contour"]["max"].get<double>(), discrete["contour"]["max"].get<double>());
  EXPECT_GT(discrete["contour"]["max"].get<double>(), 0.1);  // 0.195 in docs/smooth-silhouettes.md
  EXPECT_FALSE(smooth["analytic"].is_null());
  EXPECT_NE(read_text(dir / "bench.md").find("## Contour error on the floor, point light"), std::string::npos);
  fs::remove_all(dir);
}

TEST(BenchUsage, BadOptions_ExitTwoNamingTheOption) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--methods bogus", "--methods"},      {"--shard 0/2", "--shard"},      {"--shard 3/2", "--shard"},
      {"--shard two", "--shard"},            {"--size 0x5", "--size"},        {"--frames 0", "--frames"},
      {"--suite bogus", "--suite"},          {"--light-radius -1", "--light-radius"},
      {"--suite hard " + kDefaultScene, "--suite"}};
  for (const auto& [arguments, option] : cases) {
    SCOPED_TRACE(arguments);
    const RunResult r = run_cli("bench " + arguments + " --out " + empty_temp_dir("bench_test", "usage").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(option), std::string::npos) << r.output;
  }
  const RunResult missing =
      run_cli("bench /nonexistent/scene.json --out " + empty_temp_dir("bench_test", "usage").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("/nonexistent/scene.json"), std::string::npos) << missing.output;
}

// diff's counts picture (docs/diff.md): the counts in viridis beside the gray data file, and in
// the report with a legend of swatches.
TEST(DiffCountsPicture, OutAndReport_HaveTheViridisCountsAndItsLegend) {
  const fs::path dir = empty_temp_dir("bench_test", "diff_counts");
  const RunResult r = run_cli("diff " + kDefaultScene + " --size 48x36 --methods cpu --out " + dir.string() +
                              " --report " + (dir / "report.html").string());
  if (render_unavailable(r)) GTEST_SKIP() << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "exact_counts.png"));
  EXPECT_TRUE(fs::exists(dir / "exact_counts_viridis.png"));
  const std::string html = read_text(dir / "report.html");
  EXPECT_NE(html.find("exact_counts (viridis, legend below)"), std::string::npos);
  EXPECT_NE(html.find("exact counts n(P), viridis:"), std::string::npos);
  EXPECT_NE(html.find("rgb(68,1,84)"), std::string::npos);  // viridis at count 0
  fs::remove_all(dir);
}
