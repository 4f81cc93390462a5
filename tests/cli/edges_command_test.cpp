// `shadowcert edges` as users run it (docs/cli.md, docs/edge-maps.md): every filter and style
// with and without shadows on data/scenes/edges_creases.json writes its images and JSON; the
// edge pixels are the same with shadows as without (the edge map never sees them); thresholds
// and the crease angle mean what they say; bad options exit 2 naming the option, a scene the
// camera does not see exits 2 saying so. edges renders: without an EGL device it exits 2
// naming EGL, and these tests skip.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;

using namespace shadowcert::cli_test;

const std::string kScene = std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/edges_creases.json";

struct EdgesRun {
  RunResult run;
  nlohmann::json report;
  fs::path out, edge_map;
};

// `edges SCENE ARGS --size 160x120` with --out, --edge-map and --json under a name of its own.
EdgesRun edges(const std::string& name, const std::string& arguments, const std::string& scene = kScene) {
  const fs::path dir = temp_dir("edges_test");
  EdgesRun r;
  r.out = dir / (name + ".png");
  r.edge_map = dir / (name + "_map.png");
  const fs::path json = dir / (name + ".json");
  r.run = run_cli("edges " + scene + " --size 160x120 " + arguments + " --out " + r.out.string() + " --edge-map " +
                  r.edge_map.string() + " --json " + json.string());
  if (r.run.exit_code == 0) r.report = read_json(json);
  return r;
}

TEST(CliEdges, EveryFilterAndStyle_WithAndWithoutShadows_SameEdgePixels) {
  for (const std::string filter : {"diagonal", "c1", "sobel"}) {
    nlohmann::json without;
    for (const std::string style : {"edges", "gooch", "toon"}) {
      for (const std::string shadows : {"", "cs", "shadowmap"}) {
        if (!shadows.empty() && style != "toon") continue;  // shadows: one style is enough here
        SCOPED_TRACE(filter + ", " + style + (shadows.empty() ? "" : ", shadows " + shadows));
        const EdgesRun r = edges(filter + "_" + style + "_" + shadows,
                                 "--filter " + filter + " --style " + style +
                                     (shadows.empty() ? "" : " --shadows " + shadows));
        SHADOWCERT_SKIP_WITHOUT_GL(r.run);
        ASSERT_EQ(r.run.exit_code, 0) << r.run.output;
        EXPECT_TRUE(fs::file_size(r.out) > 0 && fs::file_size(r.edge_map) > 0);
        const nlohmann::json& j = r.report;
        EXPECT_EQ(j["filter"], filter);
        EXPECT_EQ(j["style"], style);
        EXPECT_EQ(j["size"], nlohmann::json::array({160, 120}));
        EXPECT_EQ(j["crease_angle"], 30.0);
        EXPECT_GT(j["thresholds"]["profile"].get<double>(), 0.0);
        EXPECT_GT(j["thresholds"]["inner"].get<double>(), 0.0);
        EXPECT_LT(j["depth_range"]["near"].get<double>(), j["depth_range"]["far"].get<double>());
        const nlohmann::json& e = j["edge_pixels"];
        EXPECT_GT(e["profile"].get<int>(), 0);
        EXPECT_GT(e["inner"].get<int>(), 0);
        EXPECT_GT(e["covered"].get<int>(), e["profile"].get<int>());
        for (const char* pass : {"g_buffer", "edge_filter", "composite", "frame"})
          EXPECT_GE(j["pass_ms"][pass].get<double>(), 0.0) << pass;
        if (shadows.empty()) {
          EXPECT_TRUE(j["shadows"].is_null());
          if (without.is_null()) without = e;
          EXPECT_EQ(e, without) << "the style changes nothing of the edge map";
        } else {
          EXPECT_EQ(j["shadows"], shadows);
          EXPECT_GT(j["shadowed_pixels"].get<int>(), 0);
          EXPECT_EQ(e, without) << "edge pixels with shadows as without";
        }
      }
    }
  }
}

TEST(CliEdges, ThresholdAndCreaseAngle_MeanWhatTheySay) {
  const EdgesRun none = edges("none", "--threshold 1 --crease-angle 180");
  SHADOWCERT_SKIP_WITHOUT_GL(none.run);
  ASSERT_EQ(none.run.exit_code, 0) << none.run.output;
  EXPECT_EQ(none.report["edge_pixels"]["profile"], 0) << "no intensity exceeds 1";
  EXPECT_EQ(none.report["edge_pixels"]["inner"], 0) << "no crease is sharper than 180 degrees";
  const EdgesRun loose = edges("loose", "--threshold 0.01 --crease-angle 10");
  ASSERT_EQ(loose.run.exit_code, 0) << loose.run.output;
  const EdgesRun normal = edges("normal", "");
  ASSERT_EQ(normal.run.exit_code, 0) << normal.run.output;
  EXPECT_GT(loose.report["edge_pixels"]["profile"].get<int>(), normal.report["edge_pixels"]["profile"].get<int>());
  EXPECT_GE(loose.report["edge_pixels"]["inner"].get<int>(), normal.report["edge_pixels"]["inner"].get<int>());
  EXPECT_EQ(loose.report["thresholds"]["profile"], 0.01);
}

TEST(CliEdges, Timing_PassesAndFrameInJson) {
  const EdgesRun r = edges("timing", "--timing --frames 3");
  SHADOWCERT_SKIP_WITHOUT_GL(r.run);
  ASSERT_EQ(r.run.exit_code, 0) << r.run.output;
  const nlohmann::json& t = r.report["timing"];
  EXPECT_EQ(t["frames"], 3);
  for (const char* stage : {"g_buffer", "edge_filter", "composite", "frame"}) {
    EXPECT_GE(t["gpu_ms"][stage]["min"].get<double>(), 0.0) << stage;
    EXPECT_LE(t["gpu_ms"][stage]["min"].get<double>(), t["gpu_ms"][stage]["max"].get<double>()) << stage;
  }
  EXPECT_NE(r.run.output.find("edge_filter"), std::string::npos) << r.run.output;  // the printed table
}

TEST(CliEdges, BadOptions_ExitTwoNamingTheOption) {
  for (const auto& [arguments, option] : std::vector<std::pair<std::string, std::string>>{
           {"--filter laplace", "--filter"},
           {"--style hatching", "--style"},
           {"--threshold 1.5", "--threshold"},
           {"--threshold -0.1", "--threshold"},
           {"--threshold nan", "--threshold"},
           {"--crease-angle 200", "--crease-angle"},
           {"--shadows bogus", "--shadows"},
           {"--frames 3", "--frames"},
           {"--size 0x10", "--size"}}) {
    const RunResult r = run_cli("edges " + kScene + " " + arguments);
    EXPECT_EQ(r.exit_code, 2) << arguments << ": " << r.output;
    EXPECT_NE(r.output.find(option), std::string::npos) << arguments << ": " << r.output;
  }
  const RunResult missing = run_cli("edges /nonexistent/scene.json");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("/nonexistent/scene.json"), std::string::npos) << missing.output;
}

TEST(CliEdges, CameraSeesNothing_ExitsTwoSayingSo) {
  const fs::path scene = temp_dir("edges_test") / "looking_away.json";
  std::ofstream(scene) << R"({"meshes": [{"generator": "floor", "params": {"half_size": 2}}],
    "camera": {"eye": [0, 1, 10], "target": [0, 1, 20], "size": [64, 48]}})";
  const RunResult r = run_cli("edges " + scene.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("sees nothing"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("looking_away.json"), std::string::npos) << r.output;
}

// A mesh file is framed over a floor (io/scene_input.h's load_image_scene). Regression: three
// meshes of ../shared/data (beast.obj, thingi10k_908460.stl, an OpenSCAD export), far from the
// origin or far from unit size, were drawn with the default camera, which saw none of them.
TEST(CliEdges, MeshFarFromTheOrigin_FramedAndEdged) {
  const fs::path mesh = temp_dir("edges_test") / "far_tetrahedron.off";
  std::ofstream(mesh) << "OFF\n4 4 0\n5000 5000 5000\n6000 5000 5000\n5000 6000 5000\n5000 5000 6000\n"
                         "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const EdgesRun r = edges("far_mesh", "--style gooch --shadows cs", mesh.string());
  SHADOWCERT_SKIP_WITHOUT_GL(r.run);
  ASSERT_EQ(r.run.exit_code, 0) << r.run.output;
  // The floor covers most of the image; the tetrahedron's outline is a profile edge.
  EXPECT_GT(r.report["edge_pixels"]["covered"].get<int>(), 160 * 120 / 4);
  EXPECT_GT(r.report["edge_pixels"]["profile"].get<int>(), 50);
  EXPECT_GT(r.report["edge_pixels"]["inner"].get<int>(), 0);
}

}  // namespace
