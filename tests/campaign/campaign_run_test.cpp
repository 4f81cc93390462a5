// exact/fuzz_run.h: run names, the must-not-fail split and the --methods list syntax.
#include "exact/fuzz_run.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using namespace shadowcert;

std::vector<std::string> names(const std::vector<FuzzRun>& runs) {
  std::vector<std::string> out;
  for (const FuzzRun& r : runs) out.push_back(fuzz_run_name(r));
  return out;
}

TEST(FuzzRun, AllRuns_ExactThenEachFloatMethodInBothPrecisions) {
  EXPECT_EQ(names(all_fuzz_runs()), (std::vector<std::string>{"exact", "kim-float", "kim-double", "peciva-float",
                                                              "peciva-double", "refedge-float", "refedge-double"}));
}

TEST(FuzzRun, MustNotFail_EveryMethodButKim) {
  for (const FuzzRun& r : all_fuzz_runs())
    EXPECT_EQ(must_not_fail(r), r.method != MultiplicityMethod::kim) << fuzz_run_name(r);
}

TEST(FuzzRun, ParseList_MethodsRunsAllAndDuplicates) {
  EXPECT_EQ(names(parse_fuzz_runs("all")), names(all_fuzz_runs()));
  EXPECT_EQ(names(parse_fuzz_runs("refedge")), (std::vector<std::string>{"refedge-float", "refedge-double"}));
  EXPECT_EQ(names(parse_fuzz_runs("peciva-double,exact")), (std::vector<std::string>{"exact", "peciva-double"}));
  EXPECT_EQ(names(parse_fuzz_runs("kim,kim-float,,kim")), (std::vector<std::string>{"kim-float", "kim-double"}));
}

TEST(FuzzRun, ParseList_UnknownOrEmpty_ThrowsNamingTheEntry) {
  try {
    (void)parse_fuzz_runs("exact,refedge-half");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("refedge-half"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)parse_fuzz_runs(""), std::invalid_argument);
  EXPECT_THROW((void)parse_fuzz_runs(",,"), std::invalid_argument);
}

TEST(FuzzRun, Label_OverridesTheName) {
  FuzzRun planted{MultiplicityMethod::refedge, Precision::float64, {}, "planted"};
  EXPECT_EQ(fuzz_run_name(planted), "planted");
  EXPECT_TRUE(must_not_fail(planted));
}

}  // namespace
