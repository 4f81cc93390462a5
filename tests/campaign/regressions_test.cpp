// Every shrunk reproducer the random-soup campaign ever wrote, kept under tests/regressions/ (format:
// tests/regressions/README.md), replayed through what `certify` computes:
//   status "finding": a method allowed to fail (kim) still fails exactly as recorded;
//   status "fixed":   a method that must not fail failed there once; it must pass now;
//   status "open":    a known failure of a method that must not fail: this test fails until
//                     it is fixed (and the status set to "fixed").
// On every reproducer's soup and light, exact, peciva and refedge (float and double) must also
// pass the campaign's own case certificate.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "campaign/case_certificate.h"
#include "campaign/reproducer.h"
#include "campaign/campaign_run.h"

namespace {

using namespace shadowcert;
namespace fs = std::filesystem;

std::vector<fs::path> reproducers() {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(fs::path(SHADOWCERT_SOURCE_DIR) / "tests" / "regressions"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(CampaignRegressions, EveryReproducer_ReplaysAsItsStatusSays) {
  const std::vector<fs::path> files = reproducers();
  if (files.empty()) GTEST_SKIP() << "no reproducer in tests/regressions/ yet";
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    const CampaignReproducer r = read_reproducer(file);
    const ReproducerReplay replay = replay_reproducer(r);
    if (r.status == "finding") {
      EXPECT_TRUE(replay.reproduces) << r.failure << " no longer fails: update the pinned finding";
    } else if (r.status == "fixed") {
      EXPECT_FALSE(replay.reproduces) << "a fixed " << r.failure << " failure is back";
    } else {
      ADD_FAILURE() << "open failure of " << method_name(r.method) << ": " << r.failure;
    }
  }
}

TEST(CampaignRegressions, EveryReproducer_ConsistentMethodsPassTheCaseCertificate) {
  const std::vector<fs::path> files = reproducers();
  if (files.empty()) GTEST_SKIP() << "no reproducer in tests/regressions/ yet";
  std::vector<CampaignRun> runs;
  for (const CampaignRun& run : all_campaign_runs())
    if (must_not_fail(run)) runs.push_back(run);
  for (const fs::path& file : files) {
    const CampaignReproducer r = read_reproducer(file);
    CampaignSampling sampling;
    sampling.straddle_pairs = 16;
    sampling.seed = r.case_index;
    const CaseVerdict v = certify_campaign_case(r.soup, r.light, runs, sampling);
    for (std::size_t k = 0; k < runs.size(); ++k)
      EXPECT_FALSE(v.runs[k].failed()) << file.filename().string() << ": " << campaign_run_name(runs[k]);
  }
}

}  // namespace
