// The `shadowcert` command as users run it: exit codes (0 ok, 1 a check failed, 2 usage,
// input or environment), messages on stderr naming the file and line, and the JSON keys
// the issues promise.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
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

fs::path temp_dir() {
  fs::path dir = fs::temp_directory_path() / ("shadowcert_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

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
  const fs::path json = temp_dir() / "cube.json";
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
  const fs::path json = temp_dir() / "default.json";
  const RunResult r = run_cli("inspect " + kDefaultScene + " --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_GT(j["nonmanifold_edges"].get<int>(), 0);
  EXPECT_EQ(j["closed"], false);
  ASSERT_TRUE(j.contains("meshes"));
  EXPECT_GE(j["meshes"].size(), 2u);
}

TEST(CliInspect, BadFile_ExitsTwoNamingFileAndLine) {
  const fs::path bad = temp_dir() / "bad.obj";
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
  const fs::path scene = temp_dir() / "scene.json";
  std::ofstream(scene) << R"({"meshes": [{"generator": "box", "colour": 1}]})";
  const RunResult r = run_cli("inspect " + scene.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("colour"), std::string::npos) << r.output;
}

TEST(CliCertify, DefaultScene_JsonHasEveryMethodAndExactIsCertified) {
  const fs::path json = temp_dir() / "certify.json";
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
  const fs::path dir = temp_dir();
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
  const fs::path points = temp_dir() / "points.txt";
  std::ofstream(points) << "# comment\n1 2 3\n4 five 6\n";
  const RunResult r = run_cli("certify " + kCube + " --points " + points.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find(points.string() + ":3"), std::string::npos) << r.output;
}

TEST(CliCertify, UserPoints_AreChecked) {
  const fs::path dir = temp_dir();
  std::ofstream(dir / "p.txt") << "5 5 4\n-3 0.3 0.2\n";
  const RunResult r = run_cli("certify " + kCube + " --method exact --samples 0 --light 10,0.5,0.5,1 --points " +
                              (dir / "p.txt").string() + " --json " + (dir / "u.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(dir / "u.json");
  EXPECT_EQ(j["methods"]["exact"]["count_checks"], 2);
  EXPECT_EQ(j["methods"]["exact"]["count_failures"], 0);
}

namespace {

// render needs EGL (here Mesa's llvmpipe); without it render exits 2 naming EGL, and the
// capture tests skip rather than fail on machines with no GL at all.
bool render_unavailable(const RunResult& r) {
  return r.exit_code == 2 && r.output.find("EGL") != std::string::npos;
}

void capture_and_certify(const std::string& method) {
  const fs::path volume = temp_dir() / ("capture_" + method + ".vol");
  const RunResult render =
      run_cli("render " + kDefaultScene + " --method " + method + " --size 64x48 --capture " + volume.string());
  if (render_unavailable(render)) GTEST_SKIP() << render.output;
  ASSERT_EQ(render.exit_code, 0) << render.output;
  const fs::path json = temp_dir() / ("capture_" + method + ".json");
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
  const fs::path volume = temp_dir() / "capture_fault.vol";
  const RunResult render = run_cli("render " + kDefaultScene + " --method cs --size 64x48 --capture " + volume.string());
  if (render_unavailable(render)) GTEST_SKIP() << render.output;
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
  const fs::path json = temp_dir() / "capture_fault.json";
  const RunResult r = run_cli("certify --volume " + volume.string() + " --json " + json.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("unbalanced edges"), std::string::npos) << r.output;
  const nlohmann::json j = read_json(json);
  EXPECT_EQ(j["closed"], false);
  EXPECT_EQ(j["unbalanced_edges"], 3);
}

TEST(CliCapture, BadVolumeFile_ExitsTwoNamingLine) {
  const fs::path volume = temp_dir() / "bad.vol";
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
