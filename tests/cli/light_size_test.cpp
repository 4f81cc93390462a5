// The area light's size in the units of its kind (docs/smoothies.md#light-sizes): a point light's
// disk radius in world units (--light-radius), a directional light's angular radius in degrees
// (--light-angle). The directional default was a tangent of 1% of the scene's diagonal, so a
// 1000-unit scene got an 84 degree sun; it is now an angle, the same whatever the scale, and the
// soft reference's answer survives scaling. And the soft reference's noise: each pixel's light
// is a K-sample estimate, whose 95% half-width (Hoeffding, sqrt(ln 40 / (2K))) soft and diff
// --soft report beside the errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"

namespace {

namespace fs = std::filesystem;
using namespace shadowcert::cli_test;

// The default angular radius, atan(0.01) in degrees (gpu/shadow_map_renderer.h).
const double kDefaultAngle = std::atan(0.01) * 180.0 / 3.14159265358979323846;

// A box over a floor under a sun, every length times `scale` (the sun's direction is not a length).
fs::path sun_scene(double scale) {
  const fs::path file = temp_dir("light_size_test") / ("sun_x" + std::to_string(static_cast<int>(scale)) + ".json");
  const nlohmann::json s{
      {"meshes",
       {{{"name", "floor"}, {"generator", "floor"}, {"params", {{"half_size", 4}}}, {"transform", {{"scale", scale}}}},
        {{"name", "box"},
         {"generator", "box"},
         {"params", {{"min", {-0.5, 0.25, -0.5}}, {"max", {0.5, 2.25, 0.5}}}},
         {"transform", {{"scale", scale}}}}}},
      {"lights", {{1.0, 0.8, 0.5, 0.0}}},  // low: a long shadow, its penumbra widening away from the box
      {"camera",
       {{"eye", {1.0 * scale, 4.0 * scale, 4.0 * scale}},
        {"target", {-1.5 * scale, 0.0, -0.8 * scale}},
        {"up", {0, 1, 0}},
        {"fov_y_deg", 50},
        {"size", {96, 72}}}}};
  std::ofstream(file) << s.dump(2);
  return file;
}

TEST(CliLightSize, DirectionalDefault_TheSameSunWhateverTheScale) {
  const fs::path dir = temp_dir("light_size_test");
  nlohmann::json soft[2], wide[2], diff[2];
  const double scales[2] = {1.0, 1000.0};
  for (int i = 0; i < 2; ++i) {
    const std::string scene = sun_scene(scales[i]).string(), n = std::to_string(i);
    const RunResult s = run_cli("soft " + scene + " --samples 16 --json " + (dir / ("soft_" + n + ".json")).string());
    ASSERT_EQ(s.exit_code, 0) << s.output;
    soft[i] = read_json(dir / ("soft_" + n + ".json"));
    // A wider sun (3 degrees) for penumbrae of a few pixels: the same shadow at both scales.
    const RunResult w = run_cli("soft " + scene + " --samples 16 --light-angle 3 --json " +
                                (dir / ("wide_" + n + ".json")).string());
    ASSERT_EQ(w.exit_code, 0) << w.output;
    wide[i] = read_json(dir / ("wide_" + n + ".json"));
    const RunResult d = run_cli("diff " + scene + " --methods pcss --soft --samples 16 --light-angle 3 --json " +
                                (dir / ("diff_" + n + ".json")).string());
    SHADOWCERT_SKIP_WITHOUT_GL(d);
    ASSERT_EQ(d.exit_code, 0) << d.output;
    diff[i] = read_json(dir / ("diff_" + n + ".json"));
  }
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(soft[i]["angle_degrees"].get<double>(), kDefaultAngle, 1e-12) << scales[i];
    EXPECT_EQ(soft[i]["light_shape"], "sun");
  }
  // The sun's sample directions do not depend on the scene's size at all, bit for bit (the old
  // default, a tangent of 1% of the diagonal, grew with it: 6.6 degrees here, 89.5 at 1000x).
  EXPECT_EQ(soft[0]["sample_lights"], soft[1]["sample_lights"]);
  EXPECT_EQ(soft[0]["pixels"], soft[1]["pixels"]);
  // So the soft shadow is the same, scaled: the regions, the light per pixel and pcss's error
  // against it (what differs is the 1000x scene's rounding, a pixel here and there).
  ASSERT_GT(wide[0]["pixels"]["penumbra"].get<int>(), 50);
  EXPECT_NEAR(wide[0]["pixels"]["penumbra"].get<double>(), wide[1]["pixels"]["penumbra"].get<double>(), 3.0);
  EXPECT_NEAR(wide[0]["mean_light"].get<double>(), wide[1]["mean_light"].get<double>(), 0.002);
  const auto pcss_error = [](const nlohmann::json& j) {
    return j["methods"]["pcss"]["per_light"][0]["soft"]["mean_error"].get<double>();
  };
  EXPECT_GT(pcss_error(diff[0]), 0.0);
  EXPECT_NEAR(pcss_error(diff[0]), pcss_error(diff[1]), 0.005);
}

TEST(CliLightSize, LightAngleOutOfRange_ExitsTwoNamingTheOption) {
  const std::string scene = sun_scene(1.0).string();
  const auto expect_usage = [](const std::string& arguments) {
    const RunResult r = run_cli(arguments);
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find("--light-angle"), std::string::npos) << arguments << "\n" << r.output;
  };
  for (const char* angle : {"0", "90", "-1", "nan", "inf"}) {
    expect_usage("render " + scene + " --pcss --light-angle " + angle);
    expect_usage("diff " + scene + " --methods pcss --light-angle " + angle);
    expect_usage("bench " + scene + " --methods pcss --light-angle " + angle);
  }
  expect_usage("render " + scene + " --method cs --light-angle 1");  // pcss's option only
  for (const char* angle : {"90", "-1", "nan"}) expect_usage("soft " + scene + " --light-angle " + angle);
}

TEST(CliLightSize, LightAngleGiven_UsedByPcssAndTheReference) {
  const fs::path dir = temp_dir("light_size_test");
  const std::string scene = sun_scene(1.0).string();
  const RunResult r = run_cli("render " + scene + " --pcss --light-angle 2.5 --json " + (dir / "pcss.json").string());
  SHADOWCERT_SKIP_WITHOUT_GL(r);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_json(dir / "pcss.json")["light_angle_degrees"], 2.5);
  const RunResult d = run_cli("diff " + scene + " --methods pcss --soft --samples 4 --light-angle 2.5 --json " +
                              (dir / "diff_angle.json").string());
  ASSERT_EQ(d.exit_code, 0) << d.output;
  EXPECT_EQ(read_json(dir / "diff_angle.json")["soft_reference"]["angle_degrees"], 2.5);
  const RunResult b = run_cli("bench " + scene + " --methods pcss --size 32x24 --frames 1 --no-plots --light-angle 2.5 "
                              "--out " + (dir / "bench_angle").string());
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_EQ(read_json(dir / "bench_angle" / "bench.json")["scenes"][0]["soft_reference"]["angle_degrees"], 2.5);
  // 0 is the hard shadow: one sample, the sun itself, no noise.
  const RunResult h = run_cli("soft " + scene + " --light-angle 0 --json " + (dir / "hard.json").string());
  ASSERT_EQ(h.exit_code, 0) << h.output;
  EXPECT_EQ(read_json(dir / "hard.json")["samples"], 1);
  EXPECT_EQ(read_json(dir / "hard.json")["ci95"], 0.0);
  EXPECT_EQ(read_json(dir / "hard.json")["pixels"]["penumbra"], 0);
}

// The reported half-width is Hoeffding's for the K samples: sqrt(ln(2 / 0.05) / (2K)).
TEST(CliLightSize, SoftReferenceHalfWidth_HoeffdingsForK) {
  const fs::path dir = temp_dir("light_size_test");
  const std::string scene = std::string(SHADOWCERT_SOURCE_DIR) + "/data/scenes/soft_contact.json --size 64x48";
  const double expected = std::sqrt(std::log(40.0) / (2.0 * 16.0));  // 0.3395
  const RunResult s = run_cli("soft " + scene + " --samples 16 --json " + (dir / "ci_soft.json").string());
  ASSERT_EQ(s.exit_code, 0) << s.output;
  EXPECT_NEAR(read_json(dir / "ci_soft.json")["ci95"].get<double>(), expected, 1e-12);
  const RunResult d = run_cli("diff " + scene + " --methods cpu,pcss --soft --samples 16 --json " +
                              (dir / "ci_diff.json").string());
  SHADOWCERT_SKIP_WITHOUT_GL(d);
  ASSERT_EQ(d.exit_code, 0) << d.output;
  EXPECT_NE(d.output.find("ref noise"), std::string::npos) << d.output;
  const nlohmann::json j = read_json(dir / "ci_diff.json");
  EXPECT_NEAR(j["soft_reference"]["ci95"].get<double>(), expected, 1e-12);
  for (const char* m : {"cpu", "pcss"}) {
    const nlohmann::json& e = j["methods"][m]["per_light"][0]["soft"];
    // A pixel with an undefined sample has fewer: its half-width is wider, never narrower.
    EXPECT_GE(e["reference_ci95"].get<double>(), expected - 1e-12) << m;
    // The mean spread over the compared pixels: some penumbra, at most 1 / (2 sqrt K) anywhere.
    EXPECT_GT(e["reference_noise"].get<double>(), 0.0) << m;
    EXPECT_LE(e["reference_noise"].get<double>(), 0.5 / std::sqrt(16.0)) << m;
  }
}

}  // namespace
