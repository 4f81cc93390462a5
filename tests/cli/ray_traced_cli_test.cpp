// The ray-traced peers rt and rt-robust through the CLI (docs/ray-tracing.md, docs/cli.md):
// render writes the image, mask and JSON without GL and refuses a GL option by name; diff reports
// their hard, ambiguous and agreeing pixels (and --soft error) beside the GL methods and never
// fails on them; bench runs them with their time and error; fuzz --gl-methods refuses them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using namespace shadowcert::cli_test;

const std::string kSource = SHADOWCERT_SOURCE_DIR;
const std::string kDefaultScene = kSource + "/data/scenes/default.json";
// The hard scene where rt has been seen wrong (the eye 2,000 scene sizes from a 1e-6 scene).
const std::string kTinyScale = kSource + "/data/scenes/hard/scale_1e-6.json";

TEST(CliRenderRayTraced, RtRobust_WritesImageMaskLightImageAndJsonWithoutGl) {
  const fs::path dir = empty_temp_dir("ray_traced_cli_test", "render");
  const RunResult r = run_cli("render " + kDefaultScene + " --method rt-robust --size 64x48 --out " +
                              (dir / "rt.png").string() + " --mask " + (dir / "mask.png").string() + " --light-image " +
                              (dir / "light.png").string() + " --json " + (dir / "rt.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Embree robust mode"), std::string::npos) << r.output;
  for (const char* file : {"rt.png", "mask.png", "light.png", "light.pfm", "rt.json"})
    EXPECT_TRUE(fs::is_regular_file(dir / file)) << file;
  const nlohmann::json j = read_json(dir / "rt.json");
  EXPECT_EQ(j["method"], "rt-robust");
  EXPECT_EQ(j["size"], (nlohmann::json{64, 48}));
  EXPECT_GT(j["lit_pixels"].get<int>(), 0);
  EXPECT_GT(j["shadowed_pixels"].get<int>(), 0);  // default.json's casters shadow the floor
  EXPECT_GE(j["stage_seconds"]["build"].get<double>(), 0.0);
  EXPECT_EQ(j["rays"], 64 * 48);
}

TEST(CliRenderRayTraced, GlOption_ExitTwoNamingIt) {
  for (const char* option : {"--counts x.png", "--stencil zpass", "--capture x.vol", "--pcf 3", "--timing"}) {
    const RunResult r = run_cli("render " + kDefaultScene + " --method rt --size 16x12 " + option);
    EXPECT_EQ(r.exit_code, 2) << option << ": " << r.output;
    EXPECT_NE(r.output.find(std::string(option).substr(0, std::string(option).find(' '))), std::string::npos)
        << r.output;
  }
}

TEST(CliDiffRayTraced, RtBesideCpu_FiguresImagesAndNeverAFailure) {
  const fs::path dir = empty_temp_dir("ray_traced_cli_test", "diff");
  const RunResult r = run_cli("diff " + kTinyScale + " --size 96x72 --methods cpu,rt,rt-robust --out " + dir.string() +
                              " --report " + (dir / "report.html").string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;  // cpu holds; rt's hard errors (if any) never fail the run
  const nlohmann::json j = read_json(dir / "summary.json");
  const long lights = j["lights"].get<long>();
  const std::string suffix = lights > 1 ? "_light0" : "";
  for (const char* name : {"rt", "rt-robust"}) {
    SCOPED_TRACE(name);
    const nlohmann::json& m = j["methods"][name];
    EXPECT_EQ(m["robust"], false);
    EXPECT_EQ(m["failed"], false);
    EXPECT_EQ(m["ray_traced"], true);
    EXPECT_EQ(m["hard_errors"].get<long>() + m["ambiguous"].get<long>() + m["agree"].get<long>(), lights * 96 * 72);
    EXPECT_EQ(m["ambiguous"], j["methods"]["cpu"]["ambiguous"]) << "the same exact image judges both";
    EXPECT_TRUE(fs::is_regular_file(dir / (std::string(name) + "_overlay" + suffix + ".png")));
    EXPECT_TRUE(fs::is_regular_file(dir / (std::string(name) + "_mask" + suffix + ".png")));
    EXPECT_NE(r.output.find(std::string("  ") + name + " "), std::string::npos) << r.output;
  }
  EXPECT_EQ(j["methods"]["rt"]["mode"], "fast");
  EXPECT_EQ(j["methods"]["rt-robust"]["mode"], "robust");
  EXPECT_NE(read_text(dir / "report.html").find("rt-robust overlay" + std::string(lights > 1 ? ", light 0" : "")), std::string::npos);
}

TEST(CliDiffRayTraced, RtAloneWithSoft_NoGlContextAndItsSoftError) {
  const fs::path json = temp_dir("ray_traced_cli_test") / "diff_soft.json";
  const RunResult r =
      run_cli("diff " + kDefaultScene + " --size 64x48 --methods rt --soft --samples 16 --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;  // no GL needed: this runs on a machine without EGL
  EXPECT_NE(r.output.find("no GL context"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  ASSERT_EQ(j["methods"].size(), 1u);
  const nlohmann::json& soft = j["methods"]["rt"]["per_light"][0]["soft"];
  ASSERT_TRUE(soft.is_object()) << j["methods"]["rt"].dump();
  // rt traces the reference's own 16 sample points: it can differ only where a float shadow ray
  // decides otherwise than the exact verdict, a few pixels at most on default.json.
  EXPECT_LT(soft["mean_error"].get<double>(), 0.01);
  EXPECT_EQ(j["soft_reference"]["samples"], 16);
}

TEST(CliBenchRayTraced, HardSceneAndDefault_RunsWithTimeAndError) {
  const fs::path dir = empty_temp_dir("ray_traced_cli_test", "bench");
  const RunResult r = run_cli("bench " + kDefaultScene + " " + kTinyScale +
                              " --size 48x36 --frames 2 --methods rt,rt-robust,shadowmap/512 --threads 1 --no-plots --out " +
                              dir.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(dir / "bench.json");
  ASSERT_EQ(j["scenes"].size(), 2u);
  for (const nlohmann::json& scene : j["scenes"]) {
    ASSERT_EQ(scene["runs"].size(), 3u);
    for (const nlohmann::json& run : scene["runs"]) {
      if (run["family"] != "ray_traced") continue;
      SCOPED_TRACE(run["id"].get<std::string>());
      EXPECT_EQ(run["failed"], false);
      EXPECT_EQ(run["robust"], false);
      EXPECT_TRUE(run["error"]["hard_errors"].is_number());
      EXPECT_TRUE(run["error"]["closed"].is_null());
      EXPECT_TRUE(run["error"]["soft"].is_object()) << "a shadow-map run asked for the soft reference";
      EXPECT_GT(run["time"]["frame_ms"]["median"].get<double>(), 0.0);
      EXPECT_EQ(run["parameter"]["mode"], run["id"] == "rt" ? "fast" : "robust");
    }
  }
  EXPECT_NE(read_text(dir / "bench.md").find("| rt-robust |"), std::string::npos);
  EXPECT_EQ(j["environment"]["host"]["threads"], 1);  // --threads 1: the exact image's and Embree's
}

// The report's scaling table: one row per scene in order of triangles, the exact image's seconds
// beside each ray tracer's build plus rays, and the ratio of the two as bench.json has them.
TEST(CliBenchRayTraced, Report_ExactAgainstEmbreeByTriangles) {
  const fs::path dir = empty_temp_dir("ray_traced_cli_test", "bench_scaling");
  const std::string lamp = kSource + "/data/scenes/lamp_in_room.json";  // more triangles than default.json
  const RunResult r = run_cli("bench " + lamp + " " + kDefaultScene +
                              " --size 48x36 --frames 1 --methods rt-robust,rt --no-plots --out " + dir.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(dir / "bench.json");
  const std::string md = read_text(dir / "bench.md");
  const std::size_t table = md.find("## The exact image against Embree, by triangles");
  ASSERT_NE(table, std::string::npos) << md;
  ASSERT_EQ(j["scenes"].size(), 2u);
  std::vector<std::pair<double, std::size_t>> at;  // (triangles, the row's place in the table)
  for (const nlohmann::json& scene : j["scenes"]) {
    const double exact = scene["exact_image_seconds"].get<double>();
    EXPECT_LT(exact, scene["exact_seconds"].get<double>());  // that one has the float-rounded twin too
    std::string row = "| " + scene["suite"].get<std::string>() + "/" + scene["name"].get<std::string>() + " |";
    const std::size_t place = md.find(row, table);
    ASSERT_NE(place, std::string::npos) << row << "\n" << md.substr(table);
    at.emplace_back(scene["triangles"].get<double>(), place);
    for (const nlohmann::json& run : scene["runs"]) {
      const double seconds = (run["time"]["build_ms"].get<double>() + run["time"]["frame_ms"]["median"].get<double>()) / 1000.0;
      ASSERT_GT(seconds, 0.0);
      char ratio[64];
      std::snprintf(ratio, sizeof ratio, "| %.1f |", exact / seconds);
      const std::size_t end = md.find('\n', place);
      EXPECT_NE(md.substr(place, end - place).find(ratio), std::string::npos)
          << run["id"] << ": " << ratio << " in " << md.substr(place, end - place);
    }
  }
  std::sort(at.begin(), at.end());
  EXPECT_LT(at[0].second, at[1].second) << "rows in order of triangles";
  EXPECT_LT(at[0].first, at[1].first);
}

// --threads: the exact image's and Embree's threads, in diff's JSON; a GL render refuses it, and
// a number no machine has is an error naming the option.
TEST(CliDiffRayTraced, Threads_RecordedAndCheckedByName) {
  const fs::path json = temp_dir("ray_traced_cli_test") / "diff_threads.json";
  RunResult r = run_cli("diff " + kDefaultScene + " --size 32x24 --methods rt --threads 1 --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_json(json)["threads"], 1);
  r = run_cli("diff " + kDefaultScene + " --size 32x24 --methods rt --threads 100000");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--threads"), std::string::npos) << r.output;
  r = run_cli("render " + kDefaultScene + " --method cpu --size 32x24 --threads 2");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--threads"), std::string::npos) << r.output;
  r = run_cli("render " + kDefaultScene + " --method rt --size 32x24 --threads 1 --out " +
              (temp_dir("ray_traced_cli_test") / "rt_threads.png").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

TEST(CliFuzzRayTraced, GlMethodsRt_ExitTwoSayingItIsNoGlMethod) {
  const RunResult r = run_cli("fuzz --gl --gl-methods rt --cases 1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("not a GL method"), std::string::npos) << r.output;
}

}  // namespace
