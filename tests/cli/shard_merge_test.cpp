// Batch runs (docs/batch-runs.md): `fuzz --shard K/N` splits a campaign's cases, each shard
// writes its own JSON, and `shadowcert merge` combines them into the whole run's figures: the
// same tallies, families, lights, samples and reproducers as one run of every case. Files that
// are not shards of one run (another seed, a shard twice, one missing, another kind of file)
// are refused with exit 2, naming the file. Run through the real executable, as users run it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace shadowcert::cli_test;

void write_json(const fs::path& file, const json& value) { std::ofstream(file) << value.dump(2); }

// What a run's figures are, without what depends on the machine and the moment (times,
// threads) or on where the files went (a reproducer's path and command name its --out).
json figures(json run) {
  for (const char* key : {"seconds", "cases_per_second", "shrink_seconds", "threads", "shards"}) run.erase(key);
  if (run["gl"].is_object())
    for (const char* key : {"seconds", "cases_per_second", "exact_seconds", "shrink_seconds"}) run["gl"].erase(key);
  for (json& r : run["reproducers"]) {
    r.erase("file");
    r.erase("command");
  }
  return run;
}

// `fuzz ARGS` once whole and as N shards (--json each), then the shards merged in reverse
// order; the merge's exit code, the whole run's and the merged JSON's figures.
struct ShardedRun {
  int whole_exit = -1, merge_exit = -1;
  json whole, merged;
  std::vector<fs::path> shards;
  std::string output;
};

ShardedRun run_sharded(const std::string& arguments, int n, const fs::path& dir) {
  ShardedRun s;
  const RunResult whole = run_cli("fuzz " + arguments + " --out " + (dir / "whole").string() + " --json " +
                                  (dir / "whole.json").string());
  s.whole_exit = whole.exit_code;
  s.output = whole.output;
  if (whole.exit_code > 1) return s;
  s.whole = read_json(dir / "whole.json");
  std::string files;
  for (int k = n; k >= 1; --k) {
    const fs::path json_file = dir / ("shard" + std::to_string(k) + ".json");
    const RunResult shard = run_cli("fuzz " + arguments + " --shard " + std::to_string(k) + "/" + std::to_string(n) +
                                    " --out " + (dir / "shards").string() + " --json " + json_file.string());
    EXPECT_EQ(shard.exit_code, whole.exit_code == 0 ? 0 : shard.exit_code) << shard.output;
    s.shards.push_back(json_file);
    files += " " + json_file.string();
  }
  const RunResult merge = run_cli("merge" + files + " --json " + (dir / "merged.json").string());
  s.merge_exit = merge.exit_code;
  s.output += merge.output;
  if (merge.exit_code <= 1) s.merged = read_json(dir / "merged.json");
  return s;
}

// A campaign with findings: kim-float fails on some cases of seed 1 (--shrink-findings writes
// reproducers of them, the first two by case index).
const std::string kCampaign =
    "--seed 1 --cases 60 --triangles 30 --methods exact,kim-float,refedge-float --shrink-findings --max-reproducers 2";

TEST(FuzzShards, ThreeShardsMerged_EqualTheWholeRun) {
  const fs::path dir = empty_temp_dir("shard_test", "three");
  const ShardedRun s = run_sharded(kCampaign, 3, dir);
  ASSERT_EQ(s.whole_exit, 0) << s.output;
  ASSERT_EQ(s.merge_exit, 0) << s.output;
  // Each shard holds its own cases only: 20 each, i % 3 == K - 1.
  for (const fs::path& file : s.shards) {
    const json shard = read_json(file);
    EXPECT_EQ(shard["cases"], 20) << file;
    EXPECT_EQ(shard["case_count"], 60) << file;
    EXPECT_EQ(shard["shard"]["count"], 3) << file;
  }
  // The property that matters: the merge equals the whole run, key by key.
  ASSERT_GT(s.whole["methods"]["kim-float"]["failures"].get<int>(), 2) << "no findings: pick another seed";
  EXPECT_EQ(figures(s.merged), figures(s.whole));
  EXPECT_EQ(s.merged["shard"], json({{"index", 1}, {"count", 1}}));
  EXPECT_EQ(s.merged["shards"].size(), 3u);
  ASSERT_EQ(s.merged["reproducers"].size(), 2u);  // kim-float's first two failing cases, not each shard's
  EXPECT_EQ(s.merged["reproducers"][0]["case"], s.whole["reproducers"][0]["case"]);
}

TEST(FuzzShards, MoreShardsThanCases_EmptyShardsMergeToo) {
  const fs::path dir = empty_temp_dir("shard_test", "empty");
  const ShardedRun s = run_sharded("--seed 5 --cases 3 --triangles 20", 5, dir);
  ASSERT_EQ(s.whole_exit, 0) << s.output;
  ASSERT_EQ(s.merge_exit, 0) << s.output;
  EXPECT_EQ(read_json(s.shards.front())["cases"], 0);  // shard 5/5: no case below 3
  EXPECT_EQ(figures(s.merged), figures(s.whole));
}

// The GL part shards with the exact part. Float signs fail gl-cs on case 15 of seed 2
// (cli_test's GlFailure_...): the merge keeps the whole run's reproducers and exits 1 as it does.
TEST(FuzzShards, GlShardsMerged_EqualTheWholeRunFailureIncluded) {
  const fs::path dir = empty_temp_dir("shard_test", "gl");
  const ShardedRun s = run_sharded(
      "--gl --sign float --seed 2 --cases 20 --triangles 30 --methods exact --gl-methods cs,pertri --gl-size 32x24 "
      "--max-reproducers 1",
      2, dir);
  SHADOWCERT_SKIP_WITHOUT_GL((RunResult{s.whole_exit, s.output}));
  ASSERT_EQ(s.whole_exit, 1) << s.output;
  ASSERT_EQ(s.merge_exit, 1) << s.output;
  EXPECT_EQ(s.merged["must_not_fail_failed"], true);
  EXPECT_EQ(figures(s.merged), figures(s.whole));
  EXPECT_EQ(s.merged["gl"]["cases"], 20);
  bool case_15 = false;  // one reproducer per failing GL method at most (--max-reproducers 1)
  for (const json& r : s.merged["reproducers"]) case_15 = case_15 || (r["run"] == "gl-cs" && r["case"] == 15);
  EXPECT_TRUE(case_15) << s.merged["reproducers"].dump(2);
}

TEST(FuzzShards, MalformedShard_ExitsTwoNamingTheOption) {
  for (const char* shard : {"0/3", "4/3", "1/0", "3", "a/b", "1/3/4", "-1/3", "1/"}) {
    const RunResult r = run_cli(std::string("fuzz --cases 3 --shard ") + shard);
    EXPECT_EQ(r.exit_code, 2) << shard << ": " << r.output;
    EXPECT_NE(r.output.find("--shard"), std::string::npos) << shard << ": " << r.output;
  }
}

class MergeRefusal : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(empty_temp_dir("shard_test", "refusal"));
    for (int k = 1; k <= 3; ++k)
      ASSERT_EQ(run_cli("fuzz --seed 4 --cases 12 --triangles 20 --methods exact --shard " + std::to_string(k) + "/3" +
                        " --json " + file(k))
                    .exit_code,
                0);
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string file(int k) { return (*dir_ / ("s" + std::to_string(k) + ".json")).string(); }
  static std::string out() { return " --json " + (*dir_ / "merged.json").string(); }
  // merge ARGS: exit 2, the message naming `named`.
  static void expect_refused(const std::string& arguments, const std::string& named, const std::string& what) {
    const RunResult r = run_cli("merge " + arguments + out());
    EXPECT_EQ(r.exit_code, 2) << arguments << ": " << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << arguments << ": " << r.output;
    EXPECT_NE(r.output.find(what), std::string::npos) << arguments << ": " << r.output;
  }
  static fs::path* dir_;
};
fs::path* MergeRefusal::dir_ = nullptr;

TEST_F(MergeRefusal, AllShards_Merge) {
  const RunResult r = run_cli("merge " + file(1) + " " + file(2) + " " + file(3) + out());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_json(*dir_ / "merged.json")["cases"], 12);
}

TEST_F(MergeRefusal, AShardTwice_ExitsTwoNamingIt) {
  expect_refused(file(1) + " " + file(2) + " " + file(2) + " " + file(3), file(2), "again");
}

TEST_F(MergeRefusal, AShardMissing_ExitsTwoNamingIt) { expect_refused(file(1) + " " + file(3), "2/3", "missing"); }

TEST_F(MergeRefusal, AnotherSeed_ExitsTwoNamingTheFile) {
  json other = read_json(file(2));
  other["seed"] = 5;
  const std::string changed = (*dir_ / "other_seed.json").string();
  write_json(changed, other);
  expect_refused(file(1) + " " + changed + " " + file(3), changed, "'seed'");
}

TEST_F(MergeRefusal, AnotherSplit_ExitsTwoNamingTheFile) {
  const std::string quarter = (*dir_ / "quarter.json").string();
  ASSERT_EQ(run_cli("fuzz --seed 4 --cases 12 --triangles 20 --methods exact --shard 2/4 --json " + quarter).exit_code, 0);
  expect_refused(file(1) + " " + quarter + " " + file(3), quarter, "2/4");
}

TEST_F(MergeRefusal, AShardCutShort_ExitsTwoNamingTheFile) {
  json cut = read_json(file(3));
  cut["cases"] = 3;  // a job killed before its end would not write its JSON; a tampered one is refused
  const std::string changed = (*dir_ / "cut.json").string();
  write_json(changed, cut);
  expect_refused(file(1) + " " + file(2) + " " + changed, changed, "holds 3 cases");
}

TEST_F(MergeRefusal, AnotherSchema_ExitsTwoNamingTheFile) {
  json bench = read_json(file(2));
  bench["schema"] = "shadowcert-bench/1";
  const std::string changed = (*dir_ / "bench.json").string();
  write_json(changed, bench);
  expect_refused(file(1) + " " + changed + " " + file(3), changed, "schema");
  const std::string scene = std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/default.json";
  expect_refused(file(1) + " " + scene, scene, "schema");
}

TEST_F(MergeRefusal, NoJsonOrNoFile_ExitsTwo) {
  EXPECT_EQ(run_cli("merge " + file(1)).exit_code, 2);  // --json is required
  expect_refused(file(1) + " " + (*dir_ / "absent.json").string(), "absent.json", "cannot open");
}

// bench.json shards (docs/bench.md, "Shards and their merge"), written here by the schema (every
// key the merge checks, cli/bench_file.h): the scenes' union in index order, totals recomputed,
// seconds summed, the environments kept when they differ.
json bench_run(const std::string& id, bool failed) {
  return {{"id", id},
          {"method", id},
          {"family", "stencil"},
          {"parameter", json::object()},
          {"robust", true},
          {"failed", failed},
          {"time",
           {{"frame_ms", {{"median", 1.5}, {"min", 1.0}, {"max", 2.0}}},
            {"gpu_ms", json::object()},
            {"cpu_ms", json::object()},
            {"build_ms", 0.5}}},
          {"error",
           {{"hard_errors", failed ? 3 : 0}, {"ambiguous", 1}, {"agree", 100}, {"coverage_errors", 0},
            {"lit_errors", 0}, {"count_errors", 0}, {"closed", true}, {"volume_triangles", 12},
            {"capacity_error", nullptr}, {"soft", nullptr}, {"analytic", nullptr}, {"contour", nullptr},
            {"edges", nullptr}, {"images", json::object()}}}};
}

// Scene `index`: its cs run failed, or it was skipped, or it threw before its runs.
json bench_scene(int index, bool failed, bool skipped, bool threw = false) {
  json runs = json::array();
  if (!skipped && !threw) runs = json::array({bench_run("cs", failed), bench_run("pertri", false)});
  const bool ran = !skipped && !threw;
  return {{"index", index},
          {"suite", "default"},
          {"name", "scene" + std::to_string(index)},
          {"input", "data/scenes/scene" + std::to_string(index) + ".json"},
          {"skipped", skipped ? json("not here") : json(nullptr)},
          {"failure", threw ? json({{"run", nullptr}, {"kind", "input"}, {"message", "x.obj: not a mesh"}}) : json(nullptr)},
          {"triangles", ran ? json(12) : json(nullptr)},
          {"lights", ran ? json(1) : json(nullptr)},
          {"size", ran ? json({160, 120}) : json(nullptr)},
          {"exact_seconds", ran ? json(0.1) : json(nullptr)},
          {"soft_reference", nullptr},
          {"analytic", nullptr},
          {"edge_truth_seconds", nullptr},
          {"seconds", 1.0},
          {"images", json::object()},
          {"runs", runs}};
}

json bench_totals(const json& scenes) {
  int skipped = 0, runs = 0, failed = 0, threw = 0;
  for (const json& s : scenes) {
    skipped += s["skipped"].is_null() ? 0 : 1;
    threw += s["failure"].is_null() ? 0 : 1;
    for (const json& r : s["runs"]) {
      ++runs;
      failed += r["failed"].get<bool>() ? 1 : 0;
    }
  }
  return {{"scenes", scenes.size()}, {"skipped_scenes", skipped}, {"runs", runs}, {"failed_runs", failed},
          {"failed_scenes", threw}};
}

// Shard K of N of a suite of `scene_count` scenes: scene 4's cs run fails, scene 1 is skipped,
// scene 5 threw.
json bench_shard(int k, int n, int scene_count, const std::string& renderer) {
  json scenes = json::array();
  for (int i = k - 1; i < scene_count; i += n) scenes.push_back(bench_scene(i, i == 4, i == 1, i == 5));
  json environment{{"renderer", renderer}, {"gl_version", "4.5"},     {"device", nullptr},
                   {"software_renderer", true}, {"stage_sync", "finish"}, {"build_type", "Release"},
                   {"git_commit", nullptr},     {"git_dirty", nullptr},   {"date", "2026-12-0" + std::to_string(k)},
                   {"version", "shadowcert 0.1.0"}, {"host", {{"cpus", 2}}}};
  return {{"schema", "shadowcert-bench/1"},
          {"command", "shadowcert bench --shard " + std::to_string(k) + "/" + std::to_string(n)},
          {"suite", "default"},
          {"shard", {{"index", k}, {"count", n}}},
          {"scene_count", scene_count},
          {"size", {160, 120}},
          {"warm_up_frames", 2},
          {"frames", 10},
          {"methods", {"cs", "pertri"}},
          {"environment", environment},
          {"complete", true},
          {"seconds", 10.0 * k},
          {"totals", bench_totals(scenes)},
          {"scenes", scenes}};
}

TEST(MergeBench, ShardsOfTheSchema_MergeIntoTheWholeRunsScenesAndTotals) {
  const fs::path dir = empty_temp_dir("shard_test", "bench");
  for (int k = 1; k <= 3; ++k) write_json(dir / ("b" + std::to_string(k) + ".json"), bench_shard(k, 3, 7, "llvmpipe"));
  const std::string files =
      " " + (dir / "b3.json").string() + " " + (dir / "b1.json").string() + " " + (dir / "b2.json").string();
  const RunResult r = run_cli("merge" + files + " --json " + (dir / "merged.json").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;  // scene 4's cs failed: the whole run would exit 1
  const json merged = read_json(dir / "merged.json");
  ASSERT_EQ(merged["scenes"].size(), 7u);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(merged["scenes"][i]["index"], i);
  EXPECT_EQ(merged["totals"],
            json({{"scenes", 7}, {"skipped_scenes", 1}, {"runs", 10}, {"failed_runs", 1}, {"failed_scenes", 1}}));
  EXPECT_EQ(merged["scenes"][5]["failure"]["kind"], "input");  // the failure record goes through
  EXPECT_EQ(merged["complete"], true);
  EXPECT_EQ(merged["shard"], json({{"index", 1}, {"count", 1}}));
  EXPECT_DOUBLE_EQ(merged["seconds"].get<double>(), 60.0);
  EXPECT_EQ(merged["command"], "shadowcert bench --shard 1/3");  // the first shard's
  EXPECT_FALSE(merged["environment"].contains("shards"));        // only the dates differ

  // Another renderer on one shard: every shard's environment is kept.
  write_json(dir / "b2.json", bench_shard(2, 3, 7, "NVIDIA"));
  ASSERT_EQ(run_cli("merge" + files + " --json " + (dir / "merged.json").string()).exit_code, 1);
  EXPECT_EQ(read_json(dir / "merged.json")["environment"]["shards"].size(), 3u);

  // A scene in the wrong shard, or twice: refused, naming the file.
  json wrong = bench_shard(2, 3, 7, "llvmpipe");
  wrong["scenes"].push_back(bench_scene(2, false, false));
  write_json(dir / "b2.json", wrong);
  RunResult refused = run_cli("merge" + files + " --json " + (dir / "merged.json").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("b2.json"), std::string::npos) << refused.output;
  // A different frame count: not the same run.
  json frames = bench_shard(2, 3, 7, "llvmpipe");
  frames["frames"] = 20;
  write_json(dir / "b2.json", frames);
  refused = run_cli("merge" + files + " --json " + (dir / "merged.json").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("'frames'"), std::string::npos) << refused.output;
  // A scene missing from its shard: that shard's file is named.
  json short_of_one = bench_shard(2, 3, 7, "llvmpipe");
  short_of_one["scenes"].erase(1);
  write_json(dir / "b2.json", short_of_one);
  refused = run_cli("merge" + files + " --json " + (dir / "merged.json").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("b2.json: scene index 4"), std::string::npos) << refused.output;
  // A shard that was interrupted ("complete": false, its first scenes only): refused, named.
  json interrupted = bench_shard(2, 3, 7, "llvmpipe");
  interrupted["scenes"].erase(1);
  interrupted["totals"] = bench_totals(interrupted["scenes"]);
  interrupted["complete"] = false;
  write_json(dir / "b2.json", interrupted);
  refused = run_cli("merge" + files + " --json " + (dir / "merged.json").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("b2.json: 'complete' is false: shard 2/3 was interrupted after 1 of its 2 scenes"),
            std::string::npos)
      << refused.output;
  // Totals that are not the scenes' sums: not a file bench wrote.
  json tampered = bench_shard(2, 3, 7, "llvmpipe");
  tampered["totals"]["failed_runs"] = 0;
  write_json(dir / "b2.json", tampered);
  refused = run_cli("merge" + files + " --json " + (dir / "merged.json").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("b2.json: totals.failed_runs: 0, but the scenes add up to 1"), std::string::npos)
      << refused.output;
}

}  // namespace
