// The `shadowcert` command as users run it: exit codes (0 ok, 1 a check failed, 2 usage,
// input or environment), messages on stderr naming the file and line, and the JSON keys
// the issues promise.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;

using namespace shadowcert::cli_test;

const std::string kSource = SHADOWCERT_SOURCE_DIR;
const std::string kDefaultScene = kSource + "/data/scenes/default.json";
const std::string kCube = std::string(SHADOWCERT_TEST_DATA) + "/good/cube_quads.off";

}  // namespace

TEST(CliUsage, NoSubcommand_ExitsTwo) { EXPECT_EQ(run_cli("").exit_code, 2); }

TEST(CliUsage, Help_ExitsZero) {
  const RunResult r = run_cli("inspect --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("--json"), std::string::npos);
}

TEST(CliUsage, UnknownOption_ExitsTwo) { EXPECT_EQ(run_cli("inspect " + kCube + " --bogus").exit_code, 2); }

TEST(CliInspect, Cube_JsonHasEveryKeyAndRightFigures) {
  const fs::path json = temp_dir("cli_test") / "cube.json";
  const RunResult r = run_cli("inspect " + kCube + " --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  for (const char* key : {"vertices", "welded_vertices", "triangles", "degenerate_triangles", "duplicate_triangles",
                          "edges", "border_edges", "nonmanifold_edges", "nonmanifold_vertices", "components",
                          "closed", "manifold", "consistently_oriented", "self_intersecting", "seconds"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["triangles"], 12);
  EXPECT_EQ(j["edges"], 18);
  EXPECT_EQ(j["border_edges"], 0);
  EXPECT_EQ(j["closed"], true);
  EXPECT_EQ(j["manifold"], true);
  EXPECT_EQ(j["self_intersecting"], false);
}

TEST(CliInspect, DefaultScene_ReportsNonManifoldCastersPerMesh) {
  const fs::path json = temp_dir("cli_test") / "default.json";
  const RunResult r = run_cli("inspect " + kDefaultScene + " --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_GT(j["nonmanifold_edges"].get<int>(), 0);
  EXPECT_EQ(j["closed"], false);
  ASSERT_TRUE(j.contains("meshes"));
  EXPECT_GE(j["meshes"].size(), 2u);
}

// data/scenes/noncasting_floor.json: the floor and the pane only receive ("casts": false), so
// inspect and certify work on the sphere (528 triangles) and the box (12) alone.
TEST(CliInspect, NonCastingMeshes_LeftOutOfTheCastersAndNamed) {
  const fs::path json = temp_dir("cli_test") / "noncasting_inspect.json";
  const RunResult r = run_cli("inspect " + kSource + "/data/scenes/noncasting_floor.json --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["triangles"], 540);
  ASSERT_EQ(j["meshes"].size(), 4u);
  EXPECT_EQ(j["meshes"][0]["casts"], false);
  EXPECT_FALSE(j["meshes"][0].contains("triangles"));
  EXPECT_EQ(j["meshes"][2]["casts"], true);
  EXPECT_EQ(j["meshes"][2]["triangles"], 528);
  EXPECT_NE(r.output.find("mesh floor: receives only"), std::string::npos) << r.output;
}

TEST(CliCertify, NonCastingMeshes_CertifiesTheCastersOnlyAndNeedsOne) {
  const fs::path json = temp_dir("cli_test") / "noncasting_certify.json";
  const RunResult r = run_cli("certify " + kSource + "/data/scenes/noncasting_floor.json --method exact --samples 200 "
                              "--json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_json(json)["triangles"], 540);
  const fs::path nothing = temp_dir("cli_test") / "nothing_casts.json";
  std::ofstream(nothing) << R"({"meshes": [{"generator": "floor", "casts": false}]})";
  const RunResult none = run_cli("certify " + nothing.string());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.output.find("no casting triangle"), std::string::npos) << none.output;
}

TEST(CliInspect, BadFile_ExitsTwoNamingFileAndLine) {
  const fs::path bad = temp_dir("cli_test") / "bad.obj";
  std::ofstream(bad) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  const RunResult r = run_cli("inspect " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(bad.string() + ":4"), std::string::npos) << r.output;
}

TEST(CliInspect, MissingFile_ExitsTwoNamingFile) {
  const RunResult r = run_cli("inspect /nonexistent/mesh.obj");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("/nonexistent/mesh.obj"), std::string::npos) << r.output;
}

TEST(CliInspect, BadScene_ExitsTwoNamingKey) {
  const fs::path scene = temp_dir("cli_test") / "scene.json";
  std::ofstream(scene) << R"({"meshes": [{"generator": "box", "colour": 1}]})";
  const RunResult r = run_cli("inspect " + scene.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("colour"), std::string::npos) << r.output;
}

TEST(CliCertify, DefaultScene_JsonHasEveryMethodAndExactIsCertified) {
  const fs::path json = temp_dir("cli_test") / "certify.json";
  const RunResult r = run_cli("certify " + kDefaultScene + " --samples 400 --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  for (const char* key : {"triangles", "edges", "light", "methods"}) EXPECT_TRUE(j.contains(key)) << key;
  for (const char* method : {"exact", "kim", "peciva", "refedge"}) {
    ASSERT_TRUE(j["methods"].contains(method)) << method;
    for (const char* key : {"closed", "unbalanced_edges", "count_checks", "count_failures", "silhouette_edges",
                            "max_multiplicity", "zero_facing_triangles", "seconds"})
      EXPECT_TRUE(j["methods"][method].contains(key)) << method << "." << key;
  }
  EXPECT_EQ(j["methods"]["exact"]["closed"], true);
  EXPECT_EQ(j["methods"]["exact"]["count_failures"], 0);
  EXPECT_GT(j["methods"]["exact"]["count_checks"].get<int>(), 300);
}

TEST(CliCertify, CubeUnderDirectionalLight_ClosedAndVolumeWritten) {
  const fs::path dir = temp_dir("cli_test");
  const RunResult r = run_cli("certify " + kCube + " --method refedge --precision double --light 1,2,3,0 --volume-out " +
                              (dir / "volume.off").string() + " --json " + (dir / "c.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(dir / "c.json");
  EXPECT_EQ(j["methods"]["refedge"]["closed"], true);
  EXPECT_EQ(j["methods"]["refedge"]["max_multiplicity"], 2);
  EXPECT_TRUE(fs::exists(dir / "volume.off"));
}

TEST(CliCertify, BadLight_ExitsTwo) {
  EXPECT_EQ(run_cli("certify " + kCube + " --light 1,2,3,0.5").exit_code, 2);
  EXPECT_EQ(run_cli("certify " + kCube + " --light 0,0,0,0").exit_code, 2);
  EXPECT_EQ(run_cli("certify " + kCube + " --method magic").exit_code, 2);
}

TEST(CliCertify, BadPointFile_ExitsTwoNamingLine) {
  const fs::path points = temp_dir("cli_test") / "points.txt";
  std::ofstream(points) << "# comment\n1 2 3\n4 five 6\n";
  const RunResult r = run_cli("certify " + kCube + " --points " + points.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(points.string() + ":3"), std::string::npos) << r.output;
}

TEST(CliCertify, UserPoints_AreChecked) {
  const fs::path dir = temp_dir("cli_test");
  std::ofstream(dir / "p.txt") << "5 5 4\n-3 0.3 0.2\n";
  const RunResult r = run_cli("certify " + kCube + " --method exact --samples 0 --light 10,0.5,0.5,1 --points " +
                              (dir / "p.txt").string() + " --json " + (dir / "u.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(dir / "u.json");
  EXPECT_EQ(j["methods"]["exact"]["count_checks"], 2);
  EXPECT_EQ(j["methods"]["exact"]["count_failures"], 0);
}

namespace {

void capture_and_certify(const std::string& method) {
  const fs::path volume = temp_dir("cli_test") / ("capture_" + method + ".vol");
  const RunResult render =
      run_cli("render " + kDefaultScene + " --method " + method + " --size 64x48 --capture " + volume.string());
  SHADOWCERT_SKIP_WITHOUT_GL(render);
  ASSERT_EQ(render.exit_code, 0) << render.output;
  const fs::path json = temp_dir("cli_test") / ("capture_" + method + ".json");
  const RunResult r = run_cli("certify --volume " + volume.string() + " --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("closed                 yes"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["closed"], true);
  EXPECT_EQ(j["unbalanced_edges"], 0);
  EXPECT_GT(j["triangles"].get<int>(), 0);
  EXPECT_GT(j["vertices"].get<int>(), 0);
}

}  // namespace

TEST(CliCapture, CpuVolumeAsDrawn_IsClosed) { capture_and_certify("cpu"); }

TEST(CliCapture, CsVolumeAsDrawn_IsClosed) { capture_and_certify("cs"); }

// gs: the transform-feedback capture of the geometry shader (gpu/geometry_shader_volume.h).
TEST(CliCapture, GsVolumeAsDrawn_IsClosed) { capture_and_certify("gs"); }

TEST(CliCapture, PlantedFault_OneFaceDeleted_ExitsOneWithUnbalancedEdges) {
  const fs::path volume = temp_dir("cli_test") / "capture_fault.vol";
  const RunResult render = run_cli("render " + kDefaultScene + " --method cs --size 64x48 --capture " + volume.string());
  SHADOWCERT_SKIP_WITHOUT_GL(render);
  ASSERT_EQ(render.exit_code, 0) << render.output;
  std::ifstream in(volume);
  std::ostringstream kept;
  bool deleted = false;
  for (std::string line; std::getline(in, line);) {
    if (!deleted && line.rfind("f ", 0) == 0) {
      deleted = true;
      continue;
    }
    kept << line << '\n';
  }
  in.close();
  ASSERT_TRUE(deleted);
  std::ofstream(volume) << kept.str();
  const fs::path json = temp_dir("cli_test") / "capture_fault.json";
  const RunResult r = run_cli("certify --volume " + volume.string() + " --json " + json.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("unbalanced edges"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["closed"], false);
  EXPECT_EQ(j["unbalanced_edges"], 3);
}

TEST(CliCapture, BadVolumeFile_ExitsTwoNamingLine) {
  const fs::path volume = temp_dir("cli_test") / "bad.vol";
  std::ofstream(volume) << "v 0 0 0 1\nv 1 0 0 2\n";
  const RunResult r = run_cli("certify --volume " + volume.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bad.vol:2:"), std::string::npos) << r.output;
}

TEST(CliCapture, CertifyWithoutInputOrVolume_ExitsTwo) {
  const RunResult r = run_cli("certify");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--volume"), std::string::npos) << r.output;
}

namespace {

// render --timing (docs/cli.md): the medians of a frame's stages are parts of that frame, but
// medians of parts need not add up to the median of the whole (one slow stage in one frame,
// another in the next, on a shared machine); this much slack over the frame's median absorbs it.
constexpr double kStageSumTolerance = 0.25;

// Checks a {"median", "min", "max"} object: non-negative and ordered. Returns the median.
double checked_summary(const nlohmann::json& s, const std::string& what) {
  EXPECT_TRUE(s.contains("median") && s.contains("min") && s.contains("max")) << what << ": " << s.dump();
  const double median = s.value("median", -1.0), min = s.value("min", -1.0), max = s.value("max", -1.0);
  EXPECT_GE(min, 0.0) << what;
  EXPECT_LE(min, median) << what;
  EXPECT_LE(median, max) << what;
  return median;
}

// Checks render's "timing" object (docs/cli.md) for the method's `stages`: exactly those and
// the frame on the GPU side; the frame (and the stages, when bounded by glFinish) on the CPU
// side; every summary ordered and non-negative; stage medians adding up to about the frame.
void check_timing(const nlohmann::json& t, const std::vector<std::string>& stages) {
  EXPECT_EQ(t["frames"], 5);
  EXPECT_EQ(t["warm_up_frames"], 2);
  const std::string sync = t["stage_sync"];
  EXPECT_TRUE(sync == "none" || sync == "finish") << sync;
  ASSERT_EQ(t["gpu_ms"].size(), stages.size() + 1) << t.dump(2);
  ASSERT_EQ(t["cpu_ms"].size(), sync == "finish" ? stages.size() + 1 : 1) << t.dump(2);
  double gpu_sum = 0.0, cpu_sum = 0.0;
  for (const std::string& stage : stages) {
    ASSERT_TRUE(t["gpu_ms"].contains(stage)) << stage;
    gpu_sum += checked_summary(t["gpu_ms"][stage], "gpu " + stage);
    if (sync == "finish") cpu_sum += checked_summary(t["cpu_ms"][stage], "cpu " + stage);
  }
  const double gpu_frame = checked_summary(t["gpu_ms"]["frame"], "gpu frame");
  const double cpu_frame = checked_summary(t["cpu_ms"]["frame"], "cpu frame");
  EXPECT_LE(gpu_sum, gpu_frame * (1.0 + kStageSumTolerance)) << t.dump(2);
  EXPECT_LE(cpu_sum, cpu_frame * (1.0 + kStageSumTolerance)) << t.dump(2);
}

// `render default.json --timing --frames 5` at a small size, its JSON report.
struct TimedRender {
  RunResult run;
  nlohmann::json report;
};
TimedRender render_timed(const std::string& method) {
  const fs::path json = temp_dir("cli_test") / ("timing_" + method + ".json");
  TimedRender r{run_cli("render " + kDefaultScene + " --method " + method + " --size 128x96 --timing --frames 5 " +
                        "--json " + json.string()),
                nullptr};
  if (r.run.exit_code == 0) r.report = read_json(json);
  return r;
}

}  // namespace

TEST(CliTiming, VolumeMethod_GpuStagesAndFrameInJson) {
  const TimedRender r = render_timed("cs");
  SHADOWCERT_SKIP_WITHOUT_GL(r.run);
  ASSERT_EQ(r.run.exit_code, 0) << r.run.output;
  EXPECT_NE(r.run.output.find("frame"), std::string::npos) << r.run.output;  // the printed table
  EXPECT_GE(r.report["frame_ms"].get<double>(), 0.0);
  check_timing(r.report["timing"], {"volume", "depth", "stencil", "lit"});
}

TEST(CliTiming, CpuMethod_VolumeStageIsEmpty) {
  const TimedRender r = render_timed("cpu");
  SHADOWCERT_SKIP_WITHOUT_GL(r.run);
  ASSERT_EQ(r.run.exit_code, 0) << r.run.output;
  const nlohmann::json& t = r.report["timing"];
  check_timing(t, {"volume", "depth", "stencil", "lit"});
  EXPECT_EQ(t["gpu_ms"]["volume"]["max"], 0.0);  // cpu's volume is built before the frames
  if (t["stage_sync"] == "finish") {
    EXPECT_EQ(t["cpu_ms"]["volume"]["max"], 0.0);
  }
}

TEST(CliTiming, ShadowMap_DepthShadowMapAndLitStages) {
  const TimedRender r = render_timed("shadowmap");
  SHADOWCERT_SKIP_WITHOUT_GL(r.run);
  ASSERT_EQ(r.run.exit_code, 0) << r.run.output;
  check_timing(r.report["timing"], {"depth", "shadow_map", "lit"});
}

TEST(CliTiming, FramesWithoutTimingOrZero_ExitsTwo) {
  EXPECT_EQ(run_cli("render " + kDefaultScene + " --frames 3").exit_code, 2);
  EXPECT_EQ(run_cli("render " + kDefaultScene + " --timing --frames 0").exit_code, 2);
}

// ---- shadowcert fuzz -----------------------------------------------------------------------

TEST(CliFuzz, TinyCampaign_ExitsZeroJsonHasCasesSecondsAndEveryMethod) {
  const fs::path dir = temp_dir("cli_test") / "fuzz";
  const fs::path json = dir / "fuzz.json";
  const RunResult r = run_cli("fuzz --seed 3 --cases 60 --triangles 30 --out " + (dir / "out").string() + " --json " +
                              json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("refedge-float"), std::string::npos) << r.output;  // the summary table
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["cases"], 60);
  EXPECT_EQ(j["triangles"], 30);
  EXPECT_GE(j["seconds"].get<double>(), 0.0);
  EXPECT_GT(j["cases_per_second"].get<double>(), 0.0);
  for (const char* run :
       {"exact", "kim-float", "kim-double", "peciva-float", "peciva-double", "refedge-float", "refedge-double"}) {
    ASSERT_TRUE(j["methods"].contains(run)) << run;
    const nlohmann::json& m = j["methods"][run];
    for (const char* key : {"failures", "closure_failures", "count_failures", "exact_mismatch_cases",
                            "sign_disagreement_cases", "light_on_triangle_cases", "must_not_fail"})
      EXPECT_TRUE(m.contains(key)) << run << "." << key;
    EXPECT_LE(m["closure_failures"].get<std::uint64_t>(), m["failures"].get<std::uint64_t>()) << run;
    if (m["must_not_fail"].get<bool>()) {
      EXPECT_EQ(m["failures"], 0) << run;
    }
  }
  std::uint64_t families = 0;
  for (const auto& [name, count] : j["families"].items()) families += count.get<std::uint64_t>();
  EXPECT_EQ(families, 60u);
  EXPECT_EQ(j["must_not_fail_failed"], false);
  EXPECT_FALSE(fs::exists(dir / "out"));  // no failure, no reproducer
}

TEST(CliFuzz, SameSeed_SameFiguresWhateverTheThreads) {
  const fs::path dir = temp_dir("cli_test") / "fuzz_threads";
  const std::string common = "fuzz --seed 9 --cases 40 --triangles 20 --out " + (dir / "out").string();
  ASSERT_EQ(run_cli(common + " --threads 1 --json " + (dir / "one.json").string()).exit_code, 0);
  ASSERT_EQ(run_cli(common + " --threads 2 --json " + (dir / "two.json").string()).exit_code, 0);
  nlohmann::json one = read_json(dir / "one.json"), two = read_json(dir / "two.json");
  EXPECT_EQ(one["methods"], two["methods"]);
  EXPECT_EQ(one["samples"], two["samples"]);
}

TEST(CliFuzz, ShrinkFindings_KimReproducersThatCertifyReplays) {
  const fs::path dir = temp_dir("cli_test") / "fuzz_findings";
  const RunResult r = run_cli("fuzz --seed 1 --cases 30 --methods exact,kim-float --shrink-findings --max-reproducers 1 "
                              "--out " + (dir / "out").string() + " --json " + (dir / "f.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;  // kim may fail: a finding, not an error
  const nlohmann::json j = read_json(dir / "f.json");
  ASSERT_EQ(j["reproducers"].size(), 1u) << r.output;
  const nlohmann::json& rep = j["reproducers"][0];
  EXPECT_EQ(rep["run"], "kim-float");
  EXPECT_EQ(rep["replayed"], true);
  EXPECT_LT(rep["triangles"].get<int>(), rep["original_triangles"].get<int>());
  // The printed command, run as printed (its first word is the program), shows the open chain.
  std::string command = rep["command"].get<std::string>();
  ASSERT_EQ(command.rfind("shadowcert certify ", 0), 0u) << command;
  const fs::path certified = dir / "certify.json";
  const RunResult replay = run_cli(command.substr(std::string("shadowcert ").size()) + " --json " + certified.string());
  ASSERT_EQ(replay.exit_code, 0) << replay.output;
  EXPECT_EQ(read_json(certified)["methods"]["kim"]["closed"], false);
}

TEST(CliFuzz, BadOptions_ExitTwo) {
  EXPECT_EQ(run_cli("fuzz --gl-methods cs --cases 1").exit_code, 2);  // GL options need --gl
  EXPECT_EQ(run_cli("fuzz --gl-size 32x24 --cases 1").exit_code, 2);
  EXPECT_EQ(run_cli("fuzz --gl --gl-methods cs,bogus --cases 1").exit_code, 2);
  EXPECT_NE(run_cli("fuzz --gl --gl-methods bogus --cases 1").output.find("bogus"), std::string::npos);
  EXPECT_EQ(run_cli("fuzz --gl --gl-size 0x24 --cases 1").exit_code, 2);
  EXPECT_EQ(run_cli("fuzz --cases 0").exit_code, 2);
  EXPECT_EQ(run_cli("fuzz --triangles 0").exit_code, 2);
  EXPECT_EQ(run_cli("fuzz --methods refedge-half --cases 1").exit_code, 2);
  EXPECT_EQ(run_cli("fuzz --bogus").exit_code, 2);
}

// fuzz --gl (docs/campaign.md, "The GL methods"): cases 0 to 11 of seed 1 at 30 triangles pass
// every robust GL method on llvmpipe; every pixel of every case is judged once per method.
TEST(CliFuzz, TinyGlCampaign_ExitsZeroJsonHasEveryGlMethod) {
  const fs::path dir = temp_dir("cli_test") / "fuzz_gl";
  const fs::path json = dir / "gl.json";
  const RunResult r = run_cli("fuzz --gl --seed 1 --cases 12 --triangles 30 --gl-size 32x24 --out " +
                              (dir / "out").string() + " --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("gl-pertri"), std::string::npos) << r.output;  // the GL table
  const nlohmann::json j = read_json(json);
  ASSERT_TRUE(j["gl"].is_object()) << j.dump(2);
  EXPECT_EQ(j["gl"]["cases"], 12);
  EXPECT_EQ(j["gl"]["size"], nlohmann::json::array({32, 24}));
  EXPECT_GT(j["gl"]["cases_per_second"].get<double>(), 0.0);
  EXPECT_FALSE(j["gl"]["renderer"].get<std::string>().empty());
  for (const char* run : {"gl-cpu", "gl-cs", "gl-gs", "gl-ts", "gl-pertri"}) {
    SCOPED_TRACE(run);
    ASSERT_TRUE(j["methods"].contains(run));
    const nlohmann::json& m = j["methods"][run];
    EXPECT_EQ(m["must_not_fail"], true);
    EXPECT_EQ(m["failures"], 0);
    EXPECT_EQ(m["closure_failures"], 0);
    EXPECT_EQ(m["hard_errors"], 0);
    EXPECT_EQ(m["hard_error_pixels"], 0);
    EXPECT_EQ(m["hard_error_pixels"].get<std::uint64_t>() + m["ambiguous_pixels"].get<std::uint64_t>() +
                  m["agree_pixels"].get<std::uint64_t>(),
              12u * 32u * 24u);
    EXPECT_GT(m["agree_pixels"].get<std::uint64_t>(), 0u);
    EXPECT_GT(m["volume_triangles"].get<std::uint64_t>(), 0u);
  }
  EXPECT_TRUE(j["methods"].contains("exact"));  // the exact part ran as without --gl
  EXPECT_EQ(j["must_not_fail_failed"], false);
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Case 19 of seed 1 (30 triangles): the light exactly on a triangle's plane (on_plane). Exactly
// it casts nothing; cs evaluates its light side in float, gets a nonzero sign and shadows a
// half-space: hard errors (docs/campaign.md, "What the GL campaign found"). If this test starts
// failing because cs passes, that finding was fixed: pin another failing case.
// --gl-scenes hard (campaign/hard_scene.h): hard-soup scenes of 3 to 5 parts and 1 to 3 lights;
// every light of every scene compared, so the pixels add up to lights x pixels.
TEST(CliFuzz, HardGlScenes_ExitZeroJsonCountsPartsAndEveryLightsPixels) {
  const fs::path dir = temp_dir("cli_test") / "fuzz_gl_hard";
  const fs::path json = dir / "gl.json";
  const RunResult r = run_cli("fuzz --gl --gl-scenes hard --seed 3 --cases 3 --methods exact --gl-methods cs,pertri "
                              "--gl-size 48x36 --out " + (dir / "out").string() + " --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("hard-soup scenes"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  ASSERT_TRUE(j["gl"].is_object()) << j.dump(2);
  EXPECT_EQ(j["gl"]["scenes"], "hard");
  std::uint64_t parts = 0;
  for (const auto& [name, n] : j["gl"]["parts"].items()) parts += n.get<std::uint64_t>();
  EXPECT_GE(parts, 9u);  // 3 to 5 parts a scene
  EXPECT_LE(parts, 15u);
  EXPECT_TRUE(j["gl"].contains("light_on_plane"));
  EXPECT_TRUE(j["gl"].contains("edge_on"));
  for (const char* run : {"gl-cs", "gl-pertri"}) {
    SCOPED_TRACE(run);
    const nlohmann::json& m = j["methods"][run];
    EXPECT_EQ(m["failures"], 0);
    EXPECT_TRUE(m["failures_by_part"].contains("stl_torus"));
    const std::uint64_t pixels = m["hard_error_pixels"].get<std::uint64_t>() +
                                 m["ambiguous_pixels"].get<std::uint64_t>() + m["agree_pixels"].get<std::uint64_t>();
    EXPECT_EQ(pixels % (48u * 36u), 0u);
    EXPECT_GE(pixels, 3u * 48u * 36u);
    EXPECT_LE(pixels, 9u * 48u * 36u);
  }
  EXPECT_EQ(run_cli("fuzz --gl --gl-scenes walls --cases 1").exit_code, 2);
  EXPECT_EQ(run_cli("fuzz --gl-scenes hard --cases 1").exit_code, 2);  // needs --gl
}

TEST(CliFuzz, GlFailure_ShrunkToASceneThatDiffReplays) {
  const fs::path dir = temp_dir("cli_test") / "gl_campaign_failure";
  const fs::path json = dir / "gl.json";
  // Float signs: the light within rounding of a plane still fails them (exact signs do not).
  const RunResult r = run_cli("fuzz --gl --sign float --seed 2 --cases 20 --triangles 30 --methods exact --gl-methods cs "
                              "--max-reproducers 1 --out " + (dir / "out").string() + " --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 1) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["must_not_fail_failed"], true);
  EXPECT_EQ(j["methods"]["gl-cs"]["failures"], 1);
  ASSERT_EQ(j["reproducers"].size(), 1u) << r.output;
  const nlohmann::json& rep = j["reproducers"][0];
  EXPECT_EQ(rep["run"], "gl-cs");
  EXPECT_EQ(rep["case"], 15);
  EXPECT_EQ(rep["failure"], "hard_errors");
  EXPECT_EQ(rep["replayed"], true);
  EXPECT_LT(rep["triangles"].get<int>(), rep["original_triangles"].get<int>());
  // The printed command, run as printed, fails the same way.
  const std::string command = rep["command"].get<std::string>();
  ASSERT_EQ(command.rfind("shadowcert diff ", 0), 0u) << command;
  const fs::path diffed = dir / "diff.json";
  const RunResult replay = run_cli(command.substr(std::string("shadowcert ").size()) + " --json " + diffed.string());
  EXPECT_EQ(replay.exit_code, 1) << replay.output;
  const nlohmann::json d = read_json(diffed);
  EXPECT_GT(d["methods"]["cs"]["hard_errors"].get<int>(), 0);
  EXPECT_EQ(d["methods"]["cs"]["closed"], true);
}

// The same cases with the default exact signs: none fails (docs/gpu.md "Exact signs").
TEST(CliFuzz, CasesThatFailFloatSigns_PassWithExactSigns) {
  const fs::path json = temp_dir("cli_test") / "gl_campaign_exact.json";
  const RunResult r = run_cli("fuzz --gl --seed 2 --cases 20 --triangles 30 --methods exact --gl-methods cs,pertri "
                              "--max-reproducers 0 --out " + (temp_dir("cli_test") / "unused").string() + " --json " +
                              json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["gl"]["sign"], "exact");
  EXPECT_EQ(j["methods"]["gl-cs"]["failures"], 0);
  EXPECT_EQ(j["methods"]["gl-pertri"]["failures"], 0);
}

TEST(CliFuzz, RegressionReproducer_CertifyReplaysItsRecordedCommand) {
  // Every reproducer's command is relative to its folder (tests/regressions/README.md).
  const fs::path folder = fs::path(kSource) / "tests" / "regressions";
  const nlohmann::json rep = read_json(folder / "refedge-double-light-on-triangle-s1-c105.json");
  std::istringstream words(rep["command"].get<std::string>());
  std::string word, command;
  words >> word;  // "shadowcert": run_cli supplies the program
  while (words >> word) {
    const bool file = word.ends_with(".off") || word.ends_with(".points");
    command += ' ';
    command += file ? (folder / word).string() : word;
  }
  const fs::path certified = temp_dir("cli_test") / "regression.json";
  const RunResult r = run_cli(command + " --json " + certified.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(certified);
  EXPECT_EQ(j["methods"]["refedge"]["closed"], true);
  EXPECT_EQ(j["methods"]["refedge"]["count_checks"], 2);
  EXPECT_EQ(j["methods"]["refedge"]["count_failures"], 2);  // the documented light-on-triangle error
}

// ---- diff (docs/diff.md): the exact image against every GL method ---------------------------

namespace {

const std::string kHardScenes = kSource + "/data/scenes/hard/";

}  // namespace

TEST(CliDiff, DefaultScene_EveryMethodInJsonImagesAndOfflineReport) {
  const fs::path dir = temp_dir("cli_test") / "diff_default";
  const fs::path json = temp_dir("cli_test") / "diff_default.json";
  const fs::path report = temp_dir("cli_test") / "diff_default.html";
  const RunResult r = run_cli("diff " + kDefaultScene + " --size 64x48 --out " + dir.string() + " --json " +
                              json.string() + " --report " + report.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_GT(j["exact_seconds"].get<double>(), 0.0);
  EXPECT_EQ(j["passed"], true);
  EXPECT_EQ(j["size"], nlohmann::json::array({64, 48}));
  for (const char* m : {"cpu", "cs", "gs", "ts", "pertri", "shadowmap"}) {
    SCOPED_TRACE(m);
    ASSERT_TRUE(j["methods"].contains(m));
    const nlohmann::json& method = j["methods"][m];
    for (const char* key : {"hard_errors", "ambiguous", "agree", "closed", "gl_ms"}) EXPECT_TRUE(method.contains(key)) << key;
    EXPECT_EQ(method["hard_errors"].get<int>() + method["ambiguous"].get<int>() + method["agree"].get<int>(), 64 * 48);
    if (std::string(m) == "shadowmap") {
      EXPECT_TRUE(method["closed"].is_null());
      EXPECT_EQ(method["robust"], false);
    } else {
      EXPECT_EQ(method["hard_errors"], 0);
      EXPECT_EQ(method["closed"], true);
    }
    EXPECT_TRUE(fs::exists(dir / (std::string(m) + "_overlay.png")));
    EXPECT_TRUE(fs::exists(dir / (std::string(m) + "_mask.png")));
  }
  for (const char* file : {"exact_mask.png", "exact_counts.png", "exact_ambiguous.png", "summary.json"})
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  EXPECT_EQ(read_json(dir / "summary.json"), j);
  // One page, every image inlined, nothing fetched from elsewhere.
  const std::string html = read_text(report);
  std::size_t images = 0;
  for (std::size_t at = html.find("src=\"data:image/png;base64,"); at != std::string::npos;
       at = html.find("src=\"data:image/png;base64,", at + 1))
    ++images;
  EXPECT_EQ(images, 3u + 6u * 3u);  // exact mask, counts, ambiguity; per method overlay and both masks
  EXPECT_EQ(html.find("http"), std::string::npos);
  EXPECT_EQ(html.find("src=\"/"), std::string::npos);
}

TEST(CliDiff, MethodsOption_ComparesOnlyThose) {
  const fs::path json = temp_dir("cli_test") / "diff_methods.json";
  const RunResult r = run_cli("diff " + kDefaultScene + " --size 48x36 --methods gs,shadowmap --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["methods"].size(), 2u);
  EXPECT_TRUE(j["methods"].contains("gs"));
  EXPECT_TRUE(j["methods"].contains("shadowmap"));
}

// `--methods all` is what docs/cli.md says it is (regression: diff rejected the `all` its docs
// offered): the registry's six, and joined with other names each method once.
TEST(CliDiff, MethodsAll_TheSixChainAndMapMethods) {
  const fs::path json = temp_dir("cli_test") / "diff_methods_all.json";
  const RunResult r = run_cli("diff " + kDefaultScene + " --size 32x24 --methods discrete,all,cpu --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["methods"].size(), 7u);
  for (const char* m : {"discrete", "cpu", "cs", "gs", "ts", "pertri", "shadowmap"}) EXPECT_TRUE(j["methods"].contains(m)) << m;
}

// z-pass counts the faces between the eye and P: with the eye inside a shadow volume every
// pixel behind it is off by the eye's own count. cpu is a robust method, so the run fails.
TEST(CliDiff, RobustMethodWithHardErrors_ExitsOne) {
  const fs::path json = temp_dir("cli_test") / "diff_zpass.json";
  const RunResult r = run_cli("diff " + kHardScenes + "camera_inside_volume.json --size 48x36 --methods cpu --zpass --json " +
                              json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_GT(j["methods"]["cpu"]["hard_errors"].get<int>(), 0);
  EXPECT_EQ(j["methods"]["cpu"]["failed"], true);
  EXPECT_EQ(j["passed"], false);
  EXPECT_NE(r.output.find("FAILED"), std::string::npos);
}

// The shadow map's errors are its speed-against-error figures, never a failure: a 16^2 map's
// staircases on default.json (26 hard errors at 96x72; the capped frustum of a light inside the
// bounds, which this test used to err with, is a cube map now, without one).
TEST(CliDiff, ShadowMapHardErrors_ExitZero) {
  const fs::path json = temp_dir("cli_test") / "diff_shadowmap.json";
  const RunResult r = run_cli("diff " + kDefaultScene + " --size 96x72 --methods shadowmap --shadowmap-size 16 --json " +
                              json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GT(read_json(json)["methods"]["shadowmap"]["hard_errors"].get<int>(), 0);
}

TEST(CliDiff, BadOptions_ExitTwo) {
  EXPECT_EQ(run_cli("diff " + kDefaultScene + " --methods cpu,bogus").exit_code, 2);
  EXPECT_NE(run_cli("diff " + kDefaultScene + " --methods bogus").output.find("bogus"), std::string::npos);
  EXPECT_EQ(run_cli("diff " + kDefaultScene + " --zpass --zfail").exit_code, 2);
  EXPECT_EQ(run_cli("diff " + kDefaultScene + " --size 0x10").exit_code, 2);
  EXPECT_EQ(run_cli("diff " + kDefaultScene + " --shadowmap-size 0").exit_code, 2);
  EXPECT_EQ(run_cli("diff").exit_code, 2);
  EXPECT_EQ(run_cli("diff " + kSource + "/no/such/scene.json").exit_code, 2);
}

// ---- --stencil auto|zpass|zfail (docs/gpu.md#proven-z-pass) ------------------------------------

TEST(CliStencil, RenderAuto_PlainSceneProvenZPassInTextAndJson) {
  const fs::path json = temp_dir("cli_test") / "render_auto.json";
  const RunResult r = run_cli("render " + kDefaultScene + " --size 48x36 --stencil auto --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cpu/auto"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("light 0: zpass (proven"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["stencil"], "auto");
  ASSERT_EQ(j["stencil_per_light"].size(), 1u);
  const nlohmann::json& l = j["stencil_per_light"][0];
  EXPECT_EQ(l["light"], 0);
  EXPECT_EQ(l["stencil"], "zpass");
  EXPECT_EQ(l["reason"], "proven");
  EXPECT_EQ(l["eye_count"], 0);
  EXPECT_GE(l["proof_seconds"].get<double>(), 0.0);
  EXPECT_TRUE(j["stage_seconds"].contains("zpass_proof"));
}

TEST(CliStencil, DiffAuto_CameraInsideVolumePicksZFailAndPasses) {
  const fs::path json = temp_dir("cli_test") / "diff_auto.json";
  const RunResult r = run_cli("diff " + kHardScenes + "camera_inside_volume.json --size 48x36 --methods cpu,cs "
                              "--stencil auto --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("light 1: zfail (camera in volume: n(eye) = 2)"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["stencil"], "auto");
  EXPECT_EQ(j["passed"], true);
  ASSERT_EQ(j["stencil_per_light"].size(), 2u);
  for (const nlohmann::json& l : j["stencil_per_light"]) {
    EXPECT_EQ(l["stencil"], "zfail");
    EXPECT_EQ(l["reason"], "camera_in_volume");
    EXPECT_EQ(l["eye_count"], 2);
  }
}

TEST(CliStencil, AliasesAndRequestedMethods_SayRequested) {
  for (const char* option : {"--zpass", "--stencil zpass", "--stencil zpass --zpass"}) {
    SCOPED_TRACE(option);
    const fs::path json = temp_dir("cli_test") / "render_requested.json";
    const RunResult r = run_cli("render " + kDefaultScene + " --size 32x24 " + option + " --json " + json.string());
    SHADOWCERT_SKIP_WITHOUT_GL(r);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = read_json(json);
    EXPECT_EQ(j["stencil"], "zpass");
    EXPECT_EQ(j["stencil_per_light"][0]["stencil"], "zpass");
    EXPECT_EQ(j["stencil_per_light"][0]["reason"], "requested");
    EXPECT_FALSE(j["stencil_per_light"][0].contains("eye_count"));
  }
}

TEST(CliStencil, BadOrConflictingStencilOptions_ExitTwo) {
  for (const std::string& command : {std::string("render"), std::string("diff")}) {
    SCOPED_TRACE(command);
    const RunResult bogus = run_cli(command + " " + kDefaultScene + " --stencil bogus");
    EXPECT_EQ(bogus.exit_code, 2);
    EXPECT_NE(bogus.output.find("--stencil"), std::string::npos) << bogus.output;
    EXPECT_NE(bogus.output.find("bogus"), std::string::npos) << bogus.output;
    const RunResult conflict = run_cli(command + " " + kDefaultScene + " --stencil zfail --zpass");
    EXPECT_EQ(conflict.exit_code, 2);
    EXPECT_NE(conflict.output.find("contradicts --stencil zfail"), std::string::npos) << conflict.output;
    EXPECT_EQ(run_cli(command + " " + kDefaultScene + " --stencil auto --zfail").exit_code, 2);
    EXPECT_EQ(run_cli(command + " " + kDefaultScene + " --zpass --zfail").exit_code, 2);
  }
  const RunResult shadowmap = run_cli("render " + kDefaultScene + " --method shadowmap --stencil auto");
  EXPECT_EQ(shadowmap.exit_code, 2);
  EXPECT_NE(shadowmap.output.find("--method shadowmap does not read it"), std::string::npos) << shadowmap.output;
}

// An option of another method is refused, naming the methods that read it (the method registry,
// pipeline/method_registry.h), before any file is read.
TEST(CliRender, OptionOfAnotherMethod_ExitTwoNamingItsMethods) {
  const RunResult angle = run_cli("render " + kDefaultScene + " --method cpu --light-angle 1");
  EXPECT_EQ(angle.exit_code, 2);
  EXPECT_NE(angle.output.find("--light-angle: is read by pcss only; --method cpu does not read it"), std::string::npos)
      << angle.output;
  const RunResult width = run_cli("render " + kDefaultScene + " --method pcss --smoothie-width 0.1");
  EXPECT_EQ(width.exit_code, 2);
  EXPECT_NE(width.output.find("is read by smoothie only"), std::string::npos) << width.output;
  const RunResult capture = run_cli("render " + kDefaultScene + " --method pcf --capture /tmp/x.vol");
  EXPECT_EQ(capture.exit_code, 2);
  EXPECT_NE(capture.output.find("is read by cpu, cs, gs, ts, pertri, discrete, accurate, smooth, smooth-gpu only"),
            std::string::npos)
      << capture.output;
  const RunResult unknown = run_cli("render " + kDefaultScene + " --method bogus");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.output.find("bogus"), std::string::npos) << unknown.output;
}

// ---- smooth silhouettes: discrete, accurate, smooth (docs/smooth-silhouettes.md) ---------------

// default.json has a non-manifold fan and an open box with a fin: they fall back to the robust
// chain, named with their reports; discrete is held to 0 hard errors, accurate and smooth report
// theirs without failing.
TEST(CliSilhouette, DiffDefaultScene_NonManifoldMeshesFallBackWithTheirReports) {
  const fs::path json = temp_dir("cli_test") / "diff_silhouette.json";
  const RunResult r = run_cli("diff " + kDefaultScene + " --size 96x72 --methods discrete,accurate,smooth,smooth-gpu --json " +
                              json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["methods"]["discrete"]["hard_errors"], 0);
  EXPECT_EQ(j["methods"]["discrete"]["robust"], true);
  EXPECT_EQ(j["methods"]["smooth"]["robust"], false);
  EXPECT_EQ(j["methods"]["smooth-gpu"]["robust"], false);
  for (const char* method : {"discrete", "accurate", "smooth", "smooth-gpu"}) {
    EXPECT_EQ(j["methods"][method]["closed"], true) << method;
    bool fan_fell_back = false, floor_smooth = false;
    for (const nlohmann::json& c : j["methods"][method]["casters"]) {
      if (c["mesh"] == "fan")
        fan_fell_back = c["cast_by"] == "robust chain" &&
                        c["qualification"].get<std::string>().find("non-manifold edge") != std::string::npos;
      if (c["mesh"] == "floor") floor_smooth = c["cast_by"] == method;
    }
    EXPECT_TRUE(fan_fell_back) << method;
    EXPECT_TRUE(floor_smooth) << method;
  }
  EXPECT_NE(r.output.find("fan (16 triangles) cast by the robust chain: not an oriented 2-manifold"), std::string::npos)
      << r.output;
}

TEST(CliSilhouette, RenderSmoothSphere_OneLoopAndAShadow) {
  const fs::path json = temp_dir("cli_test") / "render_smooth.json";
  const RunResult r = run_cli("render " + kSource + "/data/scenes/smooth_sphere.json --method smooth --epsilon 0.003 "
                              "--size 160x120 --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_GT(j["shadowed_pixels"].get<int>(), 200);
  bool sphere = false;
  for (const nlohmann::json& c : j["casters"])
    if (c["mesh"] == "sphere") sphere = c["cast_by"] == "smooth" && c["loops"] == 1;
  EXPECT_TRUE(sphere) << j.dump();
}

// A scene whose sphere records its ellipsoid: diff also compares the silhouette runs with the
// analytic shadow (docs/smooth-silhouettes.md#per-pixel-error-against-the-analytic-shadow),
// reports it in text and JSON and keeps the exit code; other runs and other scenes get none.
TEST(CliSilhouette, DiffSmoothSphere_ReportsTheAnalyticErrorAndKeepsTheExitCode) {
  const fs::path json = temp_dir("cli_test") / "diff_analytic.json";
  const RunResult r = run_cli("diff " + kSource + "/data/scenes/smooth_sphere.json --size 160x120 --methods "
                              "cpu,discrete,smooth --json " + json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("analytic shadow of sphere as ellipsoid"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  ASSERT_TRUE(j.contains("analytic")) << j.dump();
  EXPECT_EQ(j["analytic"]["casters"], nlohmann::json::array({"sphere"}));
  EXPECT_GT(j["analytic"]["pixels"][0]["shadowed"].get<int>(), 100);
  EXPECT_FALSE(j["methods"]["cpu"].contains("analytic"));
  const nlohmann::json& discrete = j["methods"]["discrete"]["analytic"];
  const nlohmann::json& smooth = j["methods"]["smooth"]["analytic"];
  EXPECT_LT(smooth["receiver_disagree"].get<int>(), discrete["receiver_disagree"].get<int>());
  EXPECT_LT(smooth["caster_disagree"].get<int>(), discrete["caster_disagree"].get<int>());
  EXPECT_TRUE(j["methods"]["smooth"]["per_light"][0].contains("analytic"));
  // default.json has no analytic caster.
  const fs::path plain = temp_dir("cli_test") / "diff_no_analytic.json";
  ASSERT_EQ(run_cli("diff " + kDefaultScene + " --size 64x48 --methods smooth --json " + plain.string()).exit_code, 0);
  EXPECT_FALSE(read_json(plain).contains("analytic"));
}

TEST(CliSilhouette, BadEpsilonOrCreaseAngle_ExitTwo) {
  const std::string scene = kSource + "/data/scenes/smooth_sphere.json";
  EXPECT_EQ(run_cli("render " + scene + " --method smooth --epsilon 0").exit_code, 2);
  EXPECT_EQ(run_cli("render " + scene + " --method smooth --crease-angle 200").exit_code, 2);
  EXPECT_EQ(run_cli("diff " + scene + " --methods smooth --epsilon -1").exit_code, 2);
}

// certify --method discrete|accurate|smooth: every light's volume certified closed, each mesh's
// caster report in the JSON.
TEST(CliSilhouette, CertifySmooth_EveryLightClosedWithTheCasters) {
  for (const char* method : {"discrete", "accurate", "smooth"}) {
    const fs::path json = temp_dir("cli_test") / (std::string("certify_") + method + ".json");
    const RunResult r = run_cli("certify " + kSource + "/data/scenes/closed_casters.json --method " + method +
                                " --json " + json.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const nlohmann::json j = read_json(json);
    EXPECT_EQ(j["closed"], true) << method;
    ASSERT_FALSE(j["lights"].empty());
    for (const nlohmann::json& l : j["lights"]) EXPECT_EQ(l["unbalanced_edges"], 0);
    EXPECT_EQ(j["casters"].size(), 4u);
  }
  EXPECT_EQ(run_cli("certify " + kDefaultScene + " --method smooth --epsilon 0").exit_code, 2);
}

// certify --method smooth-gpu: the GPU builds the smooth casters' part of every light's volume,
// read back and certified closed with the rest; render draws it.
TEST(CliSilhouette, CertifyAndRenderSmoothGpu_ClosedAndAShadow) {
  const fs::path json = temp_dir("cli_test") / "certify_smooth_gpu.json";
  const RunResult r = run_cli("certify " + kSource + "/data/scenes/closed_casters.json --method smooth-gpu --json " +
                              json.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["closed"], true);
  bool built_on_gpu = false;
  for (const nlohmann::json& c : j["casters"]) built_on_gpu = built_on_gpu || c["cast_by"] == "smooth-gpu";
  EXPECT_TRUE(built_on_gpu) << j.dump();
  const fs::path render_json = temp_dir("cli_test") / "render_smooth_gpu.json";
  const RunResult render = run_cli("render " + kSource + "/data/scenes/smooth_sphere.json --method smooth-gpu "
                                   "--size 160x120 --json " + render_json.string());
  ASSERT_EQ(render.exit_code, 0) << render.output;
  EXPECT_GT(read_json(render_json)["shadowed_pixels"].get<int>(), 200);
}

// shadowcert soft: the exact soft reference's figures in JSON, its light as PNG and PFM, and
// the hard shadow for R = 0 (docs/smoothies.md#the-exact-soft-reference).
TEST(CliSoft, SphereOverFloor_JsonRegionsAndLightFiles) {
  const fs::path dir = temp_dir("cli_test");
  const fs::path json = dir / "soft.json", png = dir / "soft_light.png";
  const RunResult r = run_cli("soft " + kSource + "/data/scenes/sphere_over_floor.json --size 64x48 --radius 0.5 "
                              "--samples 16 --json " + json.string() + " --out " + png.string() + " --regions " +
                              (dir / "soft_regions.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["samples"], 16);
  EXPECT_EQ(j["sample_lights"].size(), 16u);
  EXPECT_EQ(j["radius"], 0.5);
  const nlohmann::json& px = j["pixels"];
  EXPECT_EQ(px["no_hit"].get<int>() + px["undefined"].get<int>() + px["umbra"].get<int>() +
                px["penumbra"].get<int>() + px["lit"].get<int>(),
            64 * 48);
  EXPECT_GT(px["penumbra"].get<int>(), 0);
  EXPECT_TRUE(fs::exists(png));
  EXPECT_TRUE(fs::exists(dir / "soft_regions.png"));
  // The float copy beside the PNG: a little-endian gray PFM, one float per pixel.
  const fs::path pfm = dir / "soft_light.pfm";
  ASSERT_TRUE(fs::exists(pfm));
  std::ifstream in(pfm, std::ios::binary);
  std::string magic, scale;
  int width = 0, height = 0;
  in >> magic >> width >> height >> scale;
  EXPECT_EQ(magic, "Pf");
  EXPECT_EQ(width, 64);
  EXPECT_EQ(height, 48);
  EXPECT_EQ(scale, "-1.0");
  EXPECT_EQ(fs::file_size(pfm), std::string("Pf\n64 48\n-1.0\n").size() + 64u * 48u * 4u);

  const fs::path hard = dir / "soft_hard.json";
  const RunResult h = run_cli("soft " + kSource + "/data/scenes/sphere_over_floor.json --size 64x48 --radius 0 --json " +
                              hard.string());
  ASSERT_EQ(h.exit_code, 0) << h.output;
  EXPECT_EQ(read_json(hard)["samples"], 1);
  EXPECT_EQ(read_json(hard)["pixels"]["penumbra"], 0);
}

TEST(CliSoft, BadOptions_ExitTwo) {
  const std::string scene = kSource + "/data/scenes/sphere_over_floor.json --size 16x12";
  EXPECT_EQ(run_cli("soft " + scene + " --samples 10").exit_code, 2);
  EXPECT_EQ(run_cli("soft " + scene + " --radius -1").exit_code, 2);
  EXPECT_EQ(run_cli("soft " + scene + " --light 1").exit_code, 2);
  EXPECT_EQ(run_cli("soft " + scene + " --contact-pixels -2").exit_code, 2);
  EXPECT_EQ(run_cli("soft " + kSource + "/data/scenes/missing.json").exit_code, 2);
}

// `shadowcert track` (docs/smoothies.md, "Silhouette tracking"): the bifurcation case of
// tests/contour/silhouette_tracker_test.cpp, a torus of 8 x 8 segments lit from its own plane.
TEST(CliTrack, Torus_JsonHasSummariesAndFramesPerVariant) {
  const fs::path dir = temp_dir("cli_test");
  const fs::path scene = dir / "track_torus.json";
  std::ofstream(scene) << R"({"meshes": [{"generator": "torus", "params": {"minor_radius": 0.3, "major_segments": 8,
                              "minor_segments": 8}}]})";
  const fs::path json = dir / "track_torus_out.json";
  const RunResult r = run_cli("track " + scene.string() + " --orbit-radius 3 --orbit-height 0 --frames 36 " +
                              "--variant one-way,continue,periodic:4 --per-frame --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("one-way per frame"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["frames"], 36);
  EXPECT_EQ(j["path"]["kind"], "orbit");
  EXPECT_EQ(j["path"]["radius"], 3.0);
  EXPECT_EQ(j["lights"].size(), 36u);
  ASSERT_EQ(j["meshes"].size(), 1u);
  EXPECT_EQ(j["meshes"][0]["tracked"], true);
  EXPECT_EQ(j["meshes"][0]["qualification"], "qualifies");
  ASSERT_EQ(j["variants"].size(), 3u);
  EXPECT_EQ(j["variants"][0]["variant"], "one-way");
  EXPECT_EQ(j["variants"][2]["variant"], "periodic:4");
  for (const auto& v : j["variants"]) {
    ASSERT_EQ(v["frames"].size(), 36u);
    for (const char* key : {"frames", "mean_miss_rate", "max_miss_rate", "frames_with_misses", "missed", "false_positives",
                            "oldest_miss", "mean_edges_checked", "mean_found", "mean_exact", "mean_ms"})
      EXPECT_TRUE(v["summary"].contains(key)) << key;
    for (const char* key : {"frame", "edges_checked", "faces_evaluated", "ms", "full_search", "found", "exact", "missed",
                            "false_positives", "miss_rate", "oldest_miss"})
      EXPECT_TRUE(v["frames"][1].contains(key)) << key;
    EXPECT_EQ(v["frames"][0]["full_search"], true);
  }
  EXPECT_GT(j["variants"][0]["summary"]["missed"].get<int>(), 0);
  EXPECT_GT(j["variants"][0]["frames"][1]["missed"].get<int>(), 0);
  EXPECT_EQ(j["variants"][1]["summary"]["missed"], 0);
  EXPECT_LT(j["variants"][2]["summary"]["oldest_miss"].get<int>(), 4);
  EXPECT_EQ(j["exact"]["frames"].size(), 36u);
}

// Soups are not tracked: named with the reason, their silhouette the exact full search's.
TEST(CliTrack, DefaultScene_SoupsNamedWithTheirReason) {
  const fs::path json = temp_dir("cli_test") / "track_default.json";
  const RunResult r = run_cli("track " + kDefaultScene + " --frames 12 --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("mesh fan: 16 triangles, 33 edges: not tracked (not an oriented 2-manifold: 1 non-manifold edge"),
            std::string::npos)
      << r.output;
  const nlohmann::json j = read_json(json);
  ASSERT_EQ(j["meshes"].size(), 4u);
  EXPECT_EQ(j["meshes"][1]["tracked"], false);
  EXPECT_NE(j["meshes"][1]["qualification"].get<std::string>().find("non-manifold edge"), std::string::npos);
  EXPECT_GT(j["exact"]["mean_untracked_edges"].get<double>(), 0.0);
  EXPECT_EQ(j["variants"].size(), 4u);  // all: full, one-way, continue, periodic:10
  // A soup alone: nothing to track, the exact full search still runs.
  const RunResult soup = run_cli("track " + kSource + "/data/scenes/hard/bow_ties.obj --frames 4");
  ASSERT_EQ(soup.exit_code, 0) << soup.output;
  EXPECT_NE(soup.output.find("no mesh qualifies for tracking"), std::string::npos) << soup.output;
}

TEST(CliTrack, PathFile_OneFramePerLightOrRepeated) {
  const fs::path dir = temp_dir("cli_test");
  const fs::path path = dir / "track_path.txt";
  std::ofstream(path) << "# three lights\n4 2 0 1\n0 2 4 1\n0.3 1 0.2 0\n";
  const fs::path json = dir / "track_path.json";
  ASSERT_EQ(run_cli("track " + kCube + " --path " + path.string() + " --json " + json.string()).exit_code, 0);
  EXPECT_EQ(read_json(json)["frames"], 3);
  EXPECT_EQ(read_json(json)["path"]["kind"], "file");
  EXPECT_EQ(read_json(json)["lights"][2][3], 0.0);
  ASSERT_EQ(run_cli("track " + kCube + " --path " + path.string() + " --frames 7 --json " + json.string()).exit_code, 0);
  EXPECT_EQ(read_json(json)["frames"], 7);
  EXPECT_EQ(read_json(json)["lights"][3], read_json(json)["lights"][0]);
}

TEST(CliTrack, BadInput_ExitsTwoNamingTheOptionOrFileAndLine) {
  const fs::path dir = temp_dir("cli_test");
  const auto fails = [](const std::string& arguments, const std::string& expected) {
    const RunResult r = run_cli("track " + arguments);
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << arguments << "\n" << r.output;
  };
  fails(kCube + " --variant bogus", "--variant: unknown variant 'bogus'");
  fails(kCube + " --variant one-way,periodic:0", "periodic:T needs a whole number T >= 1, got '0'");
  fails(kCube + " --frames 0", "--frames: must be at least 1");
  fails(kCube + " --frames -3", "--frames: must be at least 1");
  fails(kCube + " --orbit-radius -1", "--orbit-radius: must be positive and finite");
  const fs::path path = dir / "track_bad_path.txt";
  std::ofstream(path) << "1 2 3 1\n\n1 2 3 2\n";
  fails(kCube + " --path " + path.string(), path.string() + ":3: w must be 1");
  fails(kCube + " --path " + path.string() + " --orbit-radius 2", "excludes");
  fails(kCube + " --path " + (dir / "no_such_path.txt").string(), "cannot open light path file");
  const fs::path nothing = dir / "track_nothing_casts.json";
  std::ofstream(nothing) << R"({"meshes": [{"generator": "floor", "casts": false}]})";
  fails(nothing.string(), "no casting triangle to track");
}

// The soft shadow-map methods and the light image (docs/smoothies.md): render --method smoothie,
// --pcf K, --pcss, --light-image FILE.png (+ FILE.pfm), their usage errors, diff --methods.
namespace {

// A little-endian gray PFM's floats, rows as stored; empty when the header is not ours.
std::vector<float> read_pfm_values(const fs::path& file, int& width, int& height) {
  std::ifstream in(file, std::ios::binary);
  std::string magic, scale;
  in >> magic >> width >> height >> scale;
  if (magic != "Pf" || scale != "-1.0") return {};
  in.get();
  std::vector<float> values(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(float)));
  return in ? values : std::vector<float>{};
}

}  // namespace

TEST(CliSmoothie, RenderSmoothie_JsonAndLightImagePngAndPfm) {
  const fs::path dir = temp_dir("cli_test");
  const fs::path json = dir / "smoothie.json", png = dir / "smoothie_light.png";
  const RunResult r = run_cli("render " + kDefaultScene + " --size 128x96 --method smoothie --smoothie-width 0.3 "
                              "--smoothie-space light --light-image " + png.string() + " --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("smoothies (first light)"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["method"], "smoothie");
  EXPECT_EQ(j["smoothie"]["width"], 0.3);
  EXPECT_EQ(j["smoothie"]["space"], "light");
  ASSERT_EQ(j["smoothie"]["per_light"].size(), 1u);
  EXPECT_GT(j["smoothie"]["per_light"][0]["smoothies"].get<int>(), 50);
  EXPECT_EQ(j["light_image"]["pfm"], (dir / "smoothie_light.pfm").string());
  EXPECT_TRUE(fs::exists(png));
  int width = 0, height = 0;
  const std::vector<float> light = read_pfm_values(dir / "smoothie_light.pfm", width, height);
  ASSERT_EQ(width, 128);
  ASSERT_EQ(height, 96);
  ASSERT_EQ(light.size(), 128u * 96u);
  std::size_t uncovered = 0, partial = 0;
  for (float a : light) {
    EXPECT_TRUE(a == -1.0f || (a >= 0.0f && a <= 1.0f)) << a;
    uncovered += a < 0.0f ? 1 : 0;
    partial += a > 0.0f && a < 1.0f ? 1 : 0;
  }
  EXPECT_GT(uncovered, 0u);
  EXPECT_GT(partial, 20u) << "a penumbra";
}

TEST(CliSmoothie, PcfAndPcssFlags_PickTheirMethods) {
  const fs::path dir = temp_dir("cli_test");
  const RunResult pcf = run_cli("render " + kDefaultScene + " --size 64x48 --pcf 5 --json " + (dir / "pcf.json").string());
  ASSERT_EQ(pcf.exit_code, 0) << pcf.output;
  EXPECT_EQ(read_json(dir / "pcf.json")["method"], "pcf");
  EXPECT_EQ(read_json(dir / "pcf.json")["pcf_kernel"], 5);
  const RunResult pcss = run_cli("render " + kDefaultScene + " --size 64x48 --pcss --light-radius 0.25 --json " +
                                 (dir / "pcss.json").string());
  ASSERT_EQ(pcss.exit_code, 0) << pcss.output;
  EXPECT_EQ(read_json(dir / "pcss.json")["method"], "pcss");
  EXPECT_EQ(read_json(dir / "pcss.json")["light_radius"], 0.25);
  EXPECT_EQ(run_cli("render " + kDefaultScene + " --size 32x24 --method pcss").exit_code, 0);  // the default R
}

// A stencil method's light image is its lit mask: 1 on the lit receiver pixels, 0 on the shadowed.
TEST(CliSmoothie, StencilMethodLightImage_IsTheLitMask) {
  const fs::path dir = temp_dir("cli_test");
  const fs::path json = dir / "cs.json";
  const RunResult r = run_cli("render " + kDefaultScene + " --size 96x72 --method cs --light-image " +
                              (dir / "cs_light.png").string() + " --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  int width = 0, height = 0;
  const std::vector<float> light = read_pfm_values(dir / "cs_light.pfm", width, height);
  ASSERT_EQ(light.size(), 96u * 72u);
  std::size_t lit = 0, shadowed = 0;
  for (float a : light) {
    EXPECT_TRUE(a == -1.0f || a == 0.0f || a == 1.0f) << a;
    lit += a == 1.0f ? 1 : 0;
    shadowed += a == 0.0f ? 1 : 0;
  }
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(lit, j["lit_pixels"].get<std::size_t>());
  EXPECT_EQ(shadowed, j["shadowed_pixels"].get<std::size_t>());
}

TEST(CliSmoothie, BadOptions_ExitTwoNamingTheOption) {
  const std::string render = "render " + kDefaultScene + " --size 16x12 ";
  const auto expect_usage = [&](const std::string& arguments, const std::string& option) {
    const RunResult r = run_cli(render + arguments);
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(option), std::string::npos) << arguments << "\n" << r.output;
  };
  for (const char* width : {"0", "-1", "nan", "inf"})
    expect_usage(std::string("--method smoothie --smoothie-width ") + width, "--smoothie-width");
  expect_usage("--method pcf --smoothie-width 0.1", "--smoothie-width");
  expect_usage("--method smoothie --smoothie-space image", "--smoothie-space");
  expect_usage("--method cs --smoothie-space light", "--smoothie-space");
  for (const char* k : {"0", "2", "17"}) expect_usage(std::string("--pcf ") + k, "--pcf");
  expect_usage("--pcf 3 --method cs", "--pcf");
  expect_usage("--pcf 3 --pcss", "--pcf");
  expect_usage("--pcss --method smoothie", "--pcss");
  expect_usage("--pcss --light-radius -1", "--light-radius");
  expect_usage("--method cs --light-radius 1", "--light-radius");
  expect_usage("--method smoothie --capture out.vol", "--capture");
  expect_usage("--method pcf --stencil zpass", "--stencil");
  expect_usage("--method smoothie --shadowmap-size 0", "--shadowmap-size");
  const std::string diff = "diff " + kDefaultScene + " --size 16x12 --methods smoothie ";
  EXPECT_EQ(run_cli(diff + "--smoothie-width -2").exit_code, 2);
  EXPECT_EQ(run_cli(diff + "--pcf 4").exit_code, 2);
  EXPECT_EQ(run_cli(diff + "--light-radius 0").exit_code, 2);
}

// diff takes the soft methods as baselines: reported, never a failure.
TEST(CliSmoothie, DiffSoftMethods_ReportedAsBaselines) {
  const fs::path json = temp_dir("cli_test") / "diff_soft.json";
  const RunResult r = run_cli("diff " + kDefaultScene + " --size 48x36 --methods pcf,pcss,smoothie --pcf 3 --json " +
                              json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  for (const char* m : {"pcf", "pcss", "smoothie"}) {
    ASSERT_TRUE(j["methods"].contains(m)) << m;
    EXPECT_EQ(j["methods"][m]["robust"], false) << m;
    EXPECT_EQ(j["methods"][m]["failed"], false) << m;
    EXPECT_TRUE(j["methods"][m]["closed"].is_null()) << m;
  }
  EXPECT_EQ(j["methods"]["pcf"]["pcf_kernel"], 3);
}

// A point light inside the scene's bounds: one map frustum cannot hold the scene; every
// shadow-map method draws it with a cube map and says so (text and JSON); the directional light
// keeps its one map (tests/cli/lamp_in_room_test.cpp: a light at the bounds' very centre).
TEST(CliSmoothie, LightInsideTheBounds_Reported) {
  const fs::path json = temp_dir("cli_test") / "cube.json";
  const RunResult r = run_cli("render " + kHardScenes + "light_inside_closed_caster.json --size 32x24 --method smoothie "
                              "--json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("light 0: inside or next to the scene's bounds: a cube map"), std::string::npos) << r.output;
  EXPECT_EQ(read_json(json)["cube_lights"], nlohmann::json::array({0}));
}
