// campaign/reproducer.h: reproducers read back bit for bit, name the command that replays
// them, and replay what `certify` computes: an open kim chain, and a count failure at the
// recorded pair. Bad files are InputErrors naming the file.
#include "campaign/reproducer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/input_error.h"
#include "campaign/case_certificate.h"
#include "support/hard_case_scenes.h"

namespace {

using namespace shadowcert;
using namespace shadowcert::test_support;
namespace fs = std::filesystem;

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("shadowcert_fuzz_reproducer_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// Doubles that print long or oddly: they must all come back bitwise.
Soup awkward_soup() {
  return soup_of({{0.1, -0.0, 1e-300},
                  {std::nextafter(1.0, 2.0), 1e6 + 0.1, -std::numeric_limits<double>::denorm_min()},
                  {-123456.789012345678, 2.5e-17, 3.0 / 7.0},
                  {1.0, 2.0, 3.0}},
                 {{0, 1, 2}, {1, 3, 2}, {0, 0, 3}});
}

TEST(CampaignReproducer, WriteThenRead_SameSoupLightRunAndPointsBitForBit) {
  CampaignReproducer r;
  r.soup = awkward_soup();
  r.light = Light{{std::nextafter(0.3, 1.0), -1.0 / 3.0, 1e-310, 1.0}};
  r.method = MultiplicityMethod::peciva;
  r.precision = Precision::float32;
  r.failure = "counts";
  r.points = {{0.1 + 1e-17, 1.0 / 3.0, -2.0 / 7.0}, {5e-324, -0.0, 7.0}};
  r.status = "fixed";
  r.seed = 12;
  r.case_index = 345;
  r.family = "mesh";
  r.placement = "off_plane";
  r.original_triangles = 100;
  const fs::path json = write_reproducer(temp_dir(), "awkward", r);
  const CampaignReproducer back = read_reproducer(json);
  EXPECT_EQ(back.soup.vertices, r.soup.vertices);
  EXPECT_EQ(back.soup.triangles, r.soup.triangles);
  EXPECT_EQ(back.light.position, r.light.position);
  EXPECT_EQ(back.method, r.method);
  EXPECT_EQ(back.precision, r.precision);
  EXPECT_EQ(back.failure, "counts");
  EXPECT_EQ(back.points, r.points);
  EXPECT_EQ(back.status, "fixed");
  EXPECT_EQ(back.seed, 12u);
  EXPECT_EQ(back.case_index, 345u);
  EXPECT_EQ(back.family, "mesh");
  EXPECT_EQ(back.placement, "off_plane");
  EXPECT_EQ(back.original_triangles, 100u);
  EXPECT_TRUE(fs::exists(json.parent_path() / "awkward.off"));
  EXPECT_TRUE(fs::exists(json.parent_path() / "awkward.points"));
}

TEST(CampaignReproducer, CertifyCommand_SeventeenDigitLightMethodPrecisionAndPoints) {
  CampaignReproducer r;
  r.light = Light{{0.1, -2.0, 1e-300, 0.0}};
  r.method = MultiplicityMethod::kim;
  r.precision = Precision::float64;
  EXPECT_EQ(certify_command(r, "x.off", "x.points"),
            "shadowcert certify x.off --light=0.10000000000000001,-2,1e-300,0 --method kim "
            "--precision double");
  r.failure = "counts";
  EXPECT_EQ(certify_command(r, "x.off", "x.points"),
            "shadowcert certify x.off --light=0.10000000000000001,-2,1e-300,0 --method kim "
            "--precision double --samples 0 --points x.points");
}

TEST(CampaignReproducer, KimOnThePinnedTiltedPlane_ReplaysOpen) {
  const HardCaseScene scene = pinned_tilted_plane();
  CampaignReproducer r;
  r.soup = scene.soup;
  r.light = scene.light;
  r.method = MultiplicityMethod::kim;
  r.precision = Precision::float32;
  r.status = "finding";
  const ReproducerReplay replay =
      replay_reproducer(read_reproducer(write_reproducer(temp_dir(), "pinned", r)));
  EXPECT_FALSE(replay.closed);
  EXPECT_TRUE(replay.reproduces);
  r.method = MultiplicityMethod::refedge;
  EXPECT_FALSE(replay_reproducer(r).reproduces);  // refedge float is closed there
}

// A count failure found by the case certificate replays through certify_counts at its pair:
// refedge in float on the 1e6-offset hard case, where float rounding merges vertices.
TEST(CampaignReproducer, FloatCountMismatch_ReplaysAtTheRecordedPair) {
  const std::vector<HardCaseScene> scenes = hard_case_scenes();
  const auto scene = std::find_if(scenes.begin(), scenes.end(), [](const HardCaseScene& s) {
    return s.name == "offset 1e6 with 1e-3 features, point light";
  });
  ASSERT_NE(scene, scenes.end());
  const CampaignRun refedge{MultiplicityMethod::refedge, Precision::float32, {}, {}};
  CampaignSampling sampling;
  sampling.straddle_pairs = 64;
  sampling.seed = 3;
  const RunVerdict v = certify_campaign_case(scene->soup, scene->light, {refedge}, sampling).runs[0];
  ASSERT_TRUE(v.first_exact_mismatch.has_value());
  CampaignReproducer r;
  r.soup = scene->soup;
  r.light = scene->light;
  r.method = MultiplicityMethod::refedge;
  r.precision = Precision::float32;
  r.failure = "counts";
  r.points = {v.first_exact_mismatch->from, v.first_exact_mismatch->to};
  const ReproducerReplay replay =
      replay_reproducer(read_reproducer(write_reproducer(temp_dir(), "offset", r)));
  EXPECT_TRUE(replay.closed);
  EXPECT_EQ(replay.count_checks, 2u);  // the pair, both ways
  EXPECT_EQ(replay.count_failures, 2u);
  EXPECT_TRUE(replay.reproduces);
  r.method = MultiplicityMethod::exact;
  EXPECT_FALSE(replay_reproducer(r).reproduces);  // the exact chain counts right there
}

TEST(CampaignReproducer, BadFiles_InputErrorNamingTheFile) {
  const fs::path dir = temp_dir();
  CampaignReproducer r;
  r.soup = awkward_soup();
  const fs::path json = write_reproducer(dir, "good", r);
  auto rewrite = [&](const std::string& from, const std::string& to) {
    std::ifstream in(json);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    const fs::path bad = dir / "bad.json";
    std::ofstream(bad) << text;
    return bad;
  };
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"\"method\": \"exact\"", "\"method\": \"fast\""},
           {"\"precision\": \"double\"", "\"precision\": \"half\""},
           {"\"failure\": \"closure\"", "\"failure\": \"speed\""},
           {"\"status\": \"open\"", "\"status\": \"maybe\""},
           {"\"mesh\": \"good.off\"", "\"mesh\": \"missing.off\""},
           {"\"failure\": \"closure\"", "\"failure\": \"counts\""},  // counts without points
           {"\"seed\"", "\"sead\""}}) {
    const fs::path bad = rewrite(from, to);
    try {
      (void)read_reproducer(bad);
      ADD_FAILURE() << "no error for " << to;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(to == "\"mesh\": \"missing.off\"" ? "missing.off" : "bad.json"),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW((void)read_reproducer(dir / "absent.json"), InputError);
}

}  // namespace
