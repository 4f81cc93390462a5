// campaign/campaign_run.h: run names, the must-not-fail split and the --methods list syntax.
#include "campaign/campaign_run.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using namespace shadowcert;

std::vector<std::string> names(const std::vector<CampaignRun>& runs) {
  std::vector<std::string> out;
  for (const CampaignRun& r : runs) out.push_back(campaign_run_name(r));
  return out;
}

TEST(CampaignRun, AllRuns_ExactThenEachFloatMethodInBothPrecisions) {
  EXPECT_EQ(names(all_campaign_runs()), (std::vector<std::string>{"exact", "kim-float", "kim-double", "peciva-float",
                                                              "peciva-double", "refedge-float", "refedge-double"}));
}

TEST(CampaignRun, MustNotFail_EveryMethodButKim) {
  for (const CampaignRun& r : all_campaign_runs())
    EXPECT_EQ(must_not_fail(r), r.method != MultiplicityMethod::kim) << campaign_run_name(r);
}

TEST(CampaignRun, ParseList_MethodsRunsAllAndDuplicates) {
  EXPECT_EQ(names(parse_campaign_runs("all")), names(all_campaign_runs()));
  EXPECT_EQ(names(parse_campaign_runs("refedge")), (std::vector<std::string>{"refedge-float", "refedge-double"}));
  EXPECT_EQ(names(parse_campaign_runs("peciva-double,exact")), (std::vector<std::string>{"exact", "peciva-double"}));
  EXPECT_EQ(names(parse_campaign_runs("kim,kim-float,,kim")), (std::vector<std::string>{"kim-float", "kim-double"}));
}

TEST(CampaignRun, ParseList_UnknownOrEmpty_ThrowsNamingTheEntry) {
  try {
    (void)parse_campaign_runs("exact,refedge-half");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("refedge-half"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)parse_campaign_runs(""), std::invalid_argument);
  EXPECT_THROW((void)parse_campaign_runs(",,"), std::invalid_argument);
}

TEST(CampaignRun, Label_OverridesTheName) {
  CampaignRun planted{MultiplicityMethod::refedge, Precision::float64, {}, "planted"};
  EXPECT_EQ(campaign_run_name(planted), "planted");
  EXPECT_TRUE(must_not_fail(planted));
}

}  // namespace
