// `shadowcert bench` as users run it (docs/bench.md): on a tiny scene at a tiny size it writes
// every output, bench.json has the keys of its schema, bad options exit 2 naming the option, the
// shards split a suite's scenes by index, and --from rewrites the outputs from a bench.json.
// bench renders: without an EGL device it exits 2 naming EGL, and these tests skip.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_run.h"
#include "scene/framed_scene.h"  // the analytic scenes' light and floor (header constants only)
#include "support/chord_sag_bound.h"

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
    SHADOWCERT_SKIP_WITHOUT_GL(*run_);
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
                          "methods", "environment", "complete", "seconds", "totals", "scenes"})
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
  for (const char* key : {"index", "suite", "name", "input", "skipped", "triangles", "lights", "size", "exact_seconds", "exact_image_seconds",
                          "soft_reference", "analytic", "edge_truth_seconds", "seconds", "failure", "images", "runs"})
    EXPECT_TRUE(scene.contains(key)) << key;
  EXPECT_EQ(scene["index"], 0);
  EXPECT_EQ(scene["name"], "default");
  EXPECT_TRUE(scene["skipped"].is_null());
  EXPECT_EQ(scene["triangles"], 56);
  EXPECT_FALSE(scene["soft_reference"].is_null());  // a shadow-map run asks for it
  ASSERT_EQ(scene["runs"].size(), 7u);
  EXPECT_EQ(j["totals"], (nlohmann::json{{"scenes", 1}, {"skipped_scenes", 0}, {"runs", 7}, {"failed_runs", 0},
                                         {"failed_scenes", 0}}));
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

// The keys of bench.json that are not figures of the scenes, and so may differ between a whole
// run and the merge of its shards: how long something took or when it ran (every "seconds" and
// "*_seconds": the command's, a scene's, its exact image's, its soft reference's, its analytic
// image's, its exact edges'; a run's "time": its frame, stage and build ms; the environment's
// "date"), the state of the source tree when the command ran ("git_commit" and "git_dirty":
// other work may commit between the runs) and the command line ("command": --shard and --out
// differ). Every other key, at every depth, must be equal.
namespace {

const std::set<std::string> kNotFigures{"seconds",  "exact_seconds", "exact_image_seconds", "edge_truth_seconds", "time",
                                        "date",     "git_commit",    "git_dirty",          "command"};

// a == b recursively but for kNotFigures, each difference reported with its key path.
void expect_same_figures(const nlohmann::json& a, const nlohmann::json& b, const std::string& path = "") {
  if (a.is_object() && b.is_object()) {
    std::set<std::string> keys;
    for (const auto& item : a.items()) keys.insert(item.key());
    for (const auto& item : b.items()) keys.insert(item.key());
    for (const std::string& key : keys) {
      if (kNotFigures.count(key) != 0) continue;
      const std::string at = path.empty() ? key : path + "." + key;
      if (!a.contains(key) || !b.contains(key)) {
        ADD_FAILURE() << at << " is in one file only";
        continue;
      }
      expect_same_figures(a.at(key), b.at(key), at);
    }
  } else if (a.is_array() && b.is_array()) {
    EXPECT_EQ(a.size(), b.size()) << path;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
      expect_same_figures(a.at(i), b.at(i), path + "[" + std::to_string(i) + "]");
  } else {
    EXPECT_EQ(a, b) << path;
  }
}

}  // namespace

// Shard K of N runs the scenes whose index i has i % N == K - 1; together the shards run every
// scene once, and their merge is the single run, every figure but the times.
TEST(BenchShards, TwoShards_SplitTheScenesByIndex) {
  const std::string scenes = kDefaultScene + " " + kSoftContact + " " + kSphere;
  // A run of each family: pixel, closure, soft, silhouette and edge figures compared (no plots:
  // they are drawn from bench.json and cost seconds each).
  const std::string options =
      " --size 16x12 --frames 1 --methods cpu,cs/exact,shadowmap/512,pcf/3,smooth/0.01,edges/sobel --no-plots";
  const fs::path dir = empty_temp_dir("bench_test", "shards");
  const RunResult whole = run_cli("bench " + scenes + options + " --out " + (dir / "whole").string());
  SHADOWCERT_SKIP_WITHOUT_GL(whole);
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
  EXPECT_EQ(j["complete"], true);
  ASSERT_EQ(j["scenes"].size(), w["scenes"].size());
  // Every figure but the times, key by key: the merge is the whole run.
  expect_same_figures(j, w);
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
  SHADOWCERT_SKIP_WITHOUT_GL(r);
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
  // Within the closed-form chord-sag bound of the 8x4 sphere under the point light (0.2787).
  const double bound = shadowcert::test_support::chord_sag_bound(
      shadowcert::kAnalyticPointLight, 1.0, shadowcert::test_support::inscribed_radius(1.0, 8, 4),
      shadowcert::kAnalyticFloorHeight);
  EXPECT_NEAR(bound, 0.2787, 1e-4);
  EXPECT_LE(discrete["contour"]["max"].get<double>(), bound);
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
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "exact_counts.png"));
  EXPECT_TRUE(fs::exists(dir / "exact_counts_viridis.png"));
  const std::string html = read_text(dir / "report.html");
  EXPECT_NE(html.find("exact_counts (viridis, legend below)"), std::string::npos);
  EXPECT_NE(html.find("exact counts n(P), viridis:"), std::string::npos);
  EXPECT_NE(html.find("rgb(68,1,84)"), std::string::npos);  // viridis at count 0
  fs::remove_all(dir);
}

// A scene that throws (here a mesh file that exists but is no mesh: it passes the check that the
// given files are there and fails when the scene is read) is recorded in bench.json with its
// error; the scenes after it run; the command exits 1 after writing every output
// (docs/bench.md, "A scene that fails").
TEST(BenchFailure, OneSceneThrows_RecordedAndTheOthersRun) {
  const fs::path dir = empty_temp_dir("bench_test", "failure");
  const fs::path bad = dir / "not_a_mesh.obj";
  std::ofstream(bad) << "this is not a mesh\nv 1 2\nf 1 2 3\n";
  const RunResult r = run_cli("bench " + bad.string() + " " + kDefaultScene +
                              " --size 16x12 --frames 1 --methods cpu,shadowmap/512 --no-plots --out " +
                              (dir / "out").string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("FAILED"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(dir / "out/bench.json");
  EXPECT_EQ(j["complete"], true);
  ASSERT_EQ(j["scenes"].size(), 2u);
  const nlohmann::json& failed = j["scenes"][0];
  EXPECT_EQ(failed["name"], "not_a_mesh");
  ASSERT_TRUE(failed["failure"].is_object()) << failed.dump(2);
  EXPECT_TRUE(failed["failure"]["run"].is_null());  // it threw reading the mesh, before any run
  EXPECT_EQ(failed["failure"]["kind"], "input");
  EXPECT_NE(failed["failure"]["message"].get<std::string>().find("not_a_mesh.obj"), std::string::npos)
      << failed["failure"]["message"];
  EXPECT_TRUE(failed["runs"].empty());
  EXPECT_TRUE(failed["triangles"].is_null());
  EXPECT_TRUE(failed["skipped"].is_null());
  const nlohmann::json& good = j["scenes"][1];
  EXPECT_EQ(good["name"], "default");
  EXPECT_TRUE(good["failure"].is_null());
  ASSERT_EQ(good["runs"].size(), 2u);
  EXPECT_EQ(good["runs"][0]["error"]["hard_errors"], 0);
  EXPECT_EQ(j["totals"], (nlohmann::json{{"scenes", 2}, {"skipped_scenes", 0}, {"runs", 2}, {"failed_runs", 0},
                                         {"failed_scenes", 1}}));
  for (const char* file : {"bench.csv", "bench.md", "report.html"}) EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  const std::string md = read_text(dir / "out/bench.md");
  EXPECT_NE(md.find("## Scenes that failed"), std::string::npos);
  EXPECT_NE(md.find("| **scenes/not_a_mesh FAILED** | - | input | " + bad.string() + ":1: "), std::string::npos) << md;
  EXPECT_NE(read_text(dir / "out/report.html").find("scenes/not_a_mesh (FAILED)"), std::string::npos);
  // The file reads back (bench --from, into a folder that is not there yet: it copied the images
  // into it before making it, exit 3), and a merge of it fails the check as the run did.
  const RunResult from = run_cli("bench --from " + (dir / "out/bench.json").string() + " --no-plots --out " +
                                 (dir / "from").string());
  EXPECT_EQ(from.exit_code, 0) << from.output;
  EXPECT_EQ(read_text(dir / "from/bench.md"), md);
  const RunResult merge = run_cli("merge " + (dir / "out/bench.json").string() + " --json " + (dir / "m.json").string());
  EXPECT_EQ(merge.exit_code, 1) << merge.output;
  EXPECT_EQ(read_json(dir / "m.json")["totals"]["failed_scenes"], 1);
  fs::remove_all(dir);
}

// bench.json is rewritten after every scene with "complete": false, through a temporary file
// and a rename: a run killed after its first scene leaves a whole file holding that scene, which
// bench --from reads (saying it is incomplete) and merge refuses, naming it.
TEST(BenchIncremental, KilledAfterTheFirstScene_KeepsItAndMergeRefusesTheFile) {
  const fs::path dir = empty_temp_dir("bench_test", "killed");
  const fs::path out = dir / "out";
  // Two scenes, each timed over many frames so that the second takes seconds: the kill lands in it.
  std::vector<std::string> arguments{SHADOWCERT_CLI, "bench",  kDefaultScene, kDefaultScene, "--size",   "16x12",
                                     "--frames",     "6000",   "--methods",   "cpu",         "--no-plots", "--out",
                                     out.string()};
  std::vector<char*> argv;
  for (std::string& a : arguments) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log_file = (dir / "log.txt").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, SHADOWCERT_CLI, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ASSERT_EQ(spawned, 0);
  bool ended = false;  // by itself, before the kill
  nlohmann::json seen;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      ended = true;
      break;
    }
    if (fs::exists(out / "bench.json")) {
      seen = read_json(out / "bench.json");  // never half a file: it is replaced by a rename
      if (seen["scenes"].size() >= 1) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!ended) {
    ::kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
  }
  const RunResult log{ended ? 2 : 0, read_text(dir / "log.txt")};
  SHADOWCERT_SKIP_WITHOUT_GL(log);
  ASSERT_FALSE(ended) << "the bench ended before the test could kill it: " << log.output;
  ASSERT_EQ(seen["scenes"].size(), 1u) << log.output;

  const nlohmann::json j = read_json(out / "bench.json");
  EXPECT_EQ(j["complete"], false);
  ASSERT_EQ(j["scenes"].size(), 1u) << "the second scene finished before the kill: give it more frames";
  EXPECT_EQ(j["scenes"][0]["runs"][0]["error"]["hard_errors"], 0);
  EXPECT_EQ(j["totals"]["scenes"], 1);
  EXPECT_FALSE(fs::exists(out / "bench.csv"));  // the tables come at the end (or from --from)

  const RunResult merge = run_cli("merge " + (out / "bench.json").string() + " --json " + (dir / "m.json").string());
  EXPECT_EQ(merge.exit_code, 2) << merge.output;
  EXPECT_NE(merge.output.find((out / "bench.json").string() + ": 'complete' is false"), std::string::npos)
      << merge.output;
  const RunResult from =
      run_cli("bench --from " + (out / "bench.json").string() + " --no-plots --out " + (dir / "from").string());
  EXPECT_EQ(from.exit_code, 0) << from.output;
  EXPECT_NE(from.output.find("incomplete"), std::string::npos) << from.output;
  const std::string md = read_text(dir / "from/bench.md");
  EXPECT_NE(md.find("complete: NO"), std::string::npos) << md;
  EXPECT_NE(md.find("### scenes/default"), std::string::npos) << md;
  fs::remove_all(dir);
}

TEST_F(BenchOutputs, FinishedRun_CompleteAndNoTemporaryFileLeft) {
  const nlohmann::json j = read_json(*dir_ / "bench.json");
  EXPECT_EQ(j["complete"], true);
  EXPECT_FALSE(fs::exists(*dir_ / "bench.json.partial"));
  EXPECT_EQ(j["totals"]["failed_scenes"], 0);
  EXPECT_TRUE(j["scenes"][0]["failure"].is_null());
}

// bench --from and merge check every key they read (cli/bench_file.h): a missing key, a value of
// the wrong type, figures that disagree or text that is not JSON is exit 2 naming the file and
// the key, never a crash or a bug's exit 3.
TEST_F(BenchOutputs, FromAndMerge_MalformedFile_ExitTwoNamingTheFileAndTheKey) {
  const nlohmann::json good = read_json(*dir_ / "bench.json");
  const fs::path dir = empty_temp_dir("bench_test", "malformed");
  struct Case {
    std::string name;
    std::function<void(nlohmann::json&)> change;
    std::string named;  // in the message, after the file's name
  };
  const std::vector<Case> cases{
      {"no_frame_ms", [](nlohmann::json& j) { j["scenes"][0]["runs"][1]["time"].erase("frame_ms"); },
       "scenes[0].runs[1].time: no key 'frame_ms'"},
      {"failed_text", [](nlohmann::json& j) { j["scenes"][0]["runs"][0]["failed"] = "no"; },
       "scenes[0].runs[0].failed: expected true or false"},
      {"no_totals", [](nlohmann::json& j) { j.erase("totals"); }, "no key 'totals'"},
      {"totals_wrong", [](nlohmann::json& j) { j["totals"]["runs"] = 99; }, "totals.runs: 99, but the scenes add up to 7"},
      {"stage_sync_number", [](nlohmann::json& j) { j["environment"]["stage_sync"] = 3; },
       "environment.stage_sync: expected a string"},
      {"size_short", [](nlohmann::json& j) { j["size"] = {32}; }, "size: expected [width, height]"},
      {"index_text", [](nlohmann::json& j) { j["scenes"][0]["index"] = "0"; }, "scenes[0].index: expected an unsigned"},
      {"image_number", [](nlohmann::json& j) { j["scenes"][0]["images"]["exact_mask"] = 5; },
       "scenes[0].images.exact_mask: expected a string"},
      {"hard_errors_negative", [](nlohmann::json& j) { j["scenes"][0]["runs"][0]["error"]["hard_errors"] = -1; },
       "scenes[0].runs[0].error.hard_errors: expected an unsigned integer"},
      {"unknown_run", [](nlohmann::json& j) { j["scenes"][0]["runs"][0]["id"] = "bogus"; },
       "scenes[0].runs[0].id: run \"bogus\" is not one of"},
      {"scene_not_object", [](nlohmann::json& j) { j["scenes"][0]["runs"][2] = 7; },
       "scenes[0].runs[2]: expected an object"},
      {"no_failure_kind", [](nlohmann::json& j) { j["scenes"][0]["failure"] = {{"run", nullptr}, {"message", "x"}}; },
       "scenes[0].failure: no key 'kind'"},
      {"complete_text", [](nlohmann::json& j) { j["complete"] = "yes"; }, "complete: expected true or false"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    nlohmann::json changed = good;
    c.change(changed);
    const fs::path file = dir / (c.name + ".json");
    std::ofstream(file) << changed.dump(2);
    const RunResult from = run_cli("bench --from " + file.string() + " --no-plots --out " + (dir / "out").string());
    EXPECT_EQ(from.exit_code, 2) << from.output;
    EXPECT_NE(from.output.find(file.string() + ": " + c.named), std::string::npos) << from.output;
    const RunResult merge = run_cli("merge " + file.string() + " --json " + (dir / "merged.json").string());
    EXPECT_EQ(merge.exit_code, 2) << merge.output;
    EXPECT_NE(merge.output.find(file.string() + ": " + c.named), std::string::npos) << merge.output;
  }
  const fs::path text = dir / "text.json";
  std::ofstream(text) << "{\"schema\": \"shadowcert-bench/1\", \"scenes\": [";
  const RunResult from = run_cli("bench --from " + text.string() + " --no-plots --out " + (dir / "out").string());
  EXPECT_EQ(from.exit_code, 2) << from.output;
  EXPECT_NE(from.output.find(text.string() + ": not JSON"), std::string::npos) << from.output;
  const RunResult merge = run_cli("merge " + text.string() + " --json " + (dir / "merged.json").string());
  EXPECT_EQ(merge.exit_code, 2) << merge.output;
  EXPECT_NE(merge.output.find(text.string()), std::string::npos) << merge.output;
  // The file as the run wrote it is accepted by both.
  EXPECT_EQ(run_cli("merge " + (*dir_ / "bench.json").string() + " --json " + (dir / "merged.json").string()).exit_code, 0);
  fs::remove_all(dir);
}
