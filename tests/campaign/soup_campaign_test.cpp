// campaign/soup_campaign.h: a bounded campaign with fixed seeds finds no failure of a method that
// must not fail and counts kim's; results do not depend on the thread count; planted faults are
// found on (nearly) every case and shrunk to a soup of a triangle or two that still fails.
#include "campaign/soup_campaign.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <iostream>
#include <utility>
#include <vector>

#include "campaign_test_support.h"

namespace {

using namespace shadowcert;
using namespace shadowcert::test_support;

// The CI campaign: seeds x cases of 100 triangles, every family, light placement and frame.
// About 3 s on one core of the development machine.
constexpr std::uint64_t kCases = 1000;

TEST(SoupCampaign, FixedSeeds_NoFailureOfExactPecivaRefedge_KimFailuresCounted) {
  for (const std::uint64_t seed : {1ULL, 2ULL, 3ULL}) {
    std::cout << "seed " << seed << "\n";
    CampaignOptions options;
    options.seed = seed;
    options.cases = kCases;
    const CampaignResult result = run_campaign(options);
    ASSERT_EQ(result.cases, kCases);
    for (std::size_t r = 0; r < options.runs.size(); ++r) {
      const CampaignRunTally& t = result.runs[r];
      const std::string name = campaign_run_name(options.runs[r]);
      EXPECT_GT(t.checks, 5 * kCases) << name;  // every case compared pairs
      EXPECT_EQ(t.decided_sign_error_cases, 0u) << name;
      if (must_not_fail(options.runs[r])) {
        EXPECT_EQ(t.failures, 0u) << name;
        EXPECT_EQ(t.closure_failures, 0u) << name;
        EXPECT_EQ(t.count_failures, 0u) << name;
      }
    }
    // Kim (per-edge evaluation, no consistency) loses closure on some soups in both precisions,
    // float more often: findings, counted, never shrunk unless asked.
    const CampaignRunTally& kim_float = result.runs[1];
    const CampaignRunTally& kim_double = result.runs[2];
    EXPECT_GT(kim_float.closure_failures, kCases / 20);
    EXPECT_GT(kim_double.closure_failures, 0u);
    EXPECT_GT(kim_float.closure_failures, kim_double.closure_failures);
    EXPECT_TRUE(result.failures.empty());
    EXPECT_TRUE(result.shrunk.empty());
    // The exact run agrees with n(B) - n(A) at every pair; rounding makes the float runs differ
    // somewhere (thin volumes, lights on triangles).
    EXPECT_EQ(result.runs[0].exact_mismatch_cases, 0u);
    EXPECT_GT(result.runs[5].exact_mismatch_cases, 0u);  // refedge-float
  }
}

TEST(SoupCampaign, OneThreadOrMany_SameResult) {
  CampaignOptions options;
  options.seed = 77;
  options.cases = 300;
  options.triangles = 40;
  const CampaignResult many = run_campaign(options);
  CampaignResult one;
  {
    const tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = run_campaign(options);
  }
  ASSERT_EQ(one.runs.size(), many.runs.size());
  EXPECT_EQ(one.samples, many.samples);
  EXPECT_EQ(one.cases_by_family, many.cases_by_family);
  for (std::size_t r = 0; r < one.runs.size(); ++r) {
    EXPECT_EQ(one.runs[r].failures, many.runs[r].failures);
    EXPECT_EQ(one.runs[r].checks, many.runs[r].checks);
    EXPECT_EQ(one.runs[r].exact_mismatch_cases, many.runs[r].exact_mismatch_cases);
    EXPECT_EQ(one.runs[r].sign_disagreement_cases, many.runs[r].sign_disagreement_cases);
  }
}

TEST(SoupCampaign, PlantedConsistentFlip_FoundAndShrunkToATriangleThatStillFails) {
  CampaignOptions options;
  options.seed = 5;
  options.cases = 40;
  options.runs = {CampaignRun{}, planted_run(PlantedFault::consistent_flip)};
  options.max_shrunk_per_run = 3;
  const CampaignResult result = run_campaign(options);
  EXPECT_EQ(result.runs[0].failures, 0u);
  EXPECT_GT(result.runs[1].failures, options.cases * 3 / 4);  // all but cases where nothing casts or t is undecided
  EXPECT_EQ(result.runs[1].closure_failures, 0u);
  ASSERT_EQ(result.shrunk.size(), 3u);
  for (const ShrunkFailure& s : result.shrunk) {
    SCOPED_TRACE("case " + std::to_string(s.failure.index));
    EXPECT_EQ(s.failure.run, 1u);
    EXPECT_EQ(s.failure.kind, CampaignFailureKind::counts);
    EXPECT_LE(s.soup.triangles.size(), 2u);
    EXPECT_TRUE(s.minimal);
    EXPECT_TRUE(s.verdict.failed());  // still fails, the same way
    EXPECT_TRUE(s.verdict.closed);
    EXPECT_GE(s.verdict.exact_mismatches, 1u);
    // And the same again from the shrunk soup itself.
    const RunVerdict again = certify_campaign_case(s.soup, s.original.light, options.runs,
                                               campaign_sampling_for_case(options.sampling, options.seed, s.failure.index))
                                 .runs[1];
    EXPECT_TRUE(again.failed());
  }
}

TEST(SoupCampaign, PlantedCapOnlyFlip_ClosureFailuresShrunkToOneTriangle) {
  CampaignOptions options;
  options.seed = 6;
  options.cases = 30;
  options.runs = {planted_run(PlantedFault::cap_only_flip)};
  options.max_shrunk_per_run = 2;
  const CampaignResult result = run_campaign(options);
  EXPECT_GT(result.runs[0].closure_failures, options.cases * 3 / 4);
  ASSERT_EQ(result.shrunk.size(), 2u);
  for (const ShrunkFailure& s : result.shrunk) {
    EXPECT_EQ(s.failure.kind, CampaignFailureKind::closure);
    EXPECT_EQ(s.soup.triangles.size(), 1u);
    EXPECT_EQ(s.soup.vertices.size(), 3u);
    EXPECT_FALSE(s.verdict.closed);
  }
}

TEST(SoupCampaign, ShrinkFindings_KimClosureFailureShrunkSmallAndStillOpen) {
  CampaignOptions options;
  options.seed = 1;
  options.cases = 200;
  options.runs = parse_campaign_runs("exact,kim-float");
  options.shrink_findings = true;
  options.max_shrunk_per_run = 2;
  const CampaignResult result = run_campaign(options);
  ASSERT_FALSE(result.failures.empty());
  ASSERT_EQ(result.shrunk.size(), 2u);
  for (const ShrunkFailure& s : result.shrunk) {
    EXPECT_EQ(s.failure.run, 1u);
    EXPECT_FALSE(s.verdict.closed);
    EXPECT_LE(s.soup.triangles.size(), 6u);
    EXPECT_LT(s.soup.triangles.size(), s.original.soup.triangles.size());
  }
}

TEST(SoupCampaign, CaseSamplingSeeds_DifferPerCaseAndSeed) {
  const CampaignSampling base;
  EXPECT_NE(campaign_sampling_for_case(base, 1, 0).seed, campaign_sampling_for_case(base, 1, 1).seed);
  EXPECT_NE(campaign_sampling_for_case(base, 1, 0).seed, campaign_sampling_for_case(base, 2, 0).seed);
  EXPECT_EQ(campaign_sampling_for_case(base, 1, 5).seed, campaign_sampling_for_case(base, 1, 5).seed);
}

// Shards (campaign/case_shard.h, docs/batch-runs.md): the shards of a campaign hold every case
// once, and their tallies add up to the whole run's, failures and their order included.
TEST(SoupCampaign, FourShards_CoverEveryCaseOnceAndAddUpToTheWholeRun) {
  CampaignOptions whole;
  whole.seed = 11;
  whole.cases = 203;  // not a multiple of 4: the shards differ by one case
  whole.triangles = 30;
  whole.shrink_findings = true;  // kim's failures listed too, so that there are some
  whole.max_shrunk_per_run = 0;
  const CampaignResult expected = run_campaign(whole);
  ASSERT_FALSE(expected.failures.empty()) << "no kim failure: pick another seed";

  CampaignResult sum;
  sum.runs.resize(whole.runs.size());
  std::vector<int> held(whole.cases, 0);
  for (std::uint64_t k = 0; k < 4; ++k) {
    CampaignOptions shard = whole;
    shard.shard = {k, 4};
    for (std::uint64_t j = 0; j < shard_case_count(whole.cases, shard.shard); ++j)
      ++held[shard_case_index(shard.shard, j)];
    const CampaignResult part = run_campaign(shard);
    EXPECT_EQ(part.cases, shard_case_count(whole.cases, shard.shard));
    sum.cases += part.cases;
    sum.samples += part.samples;
    for (std::size_t i = 0; i < sum.cases_by_family.size(); ++i) sum.cases_by_family[i] += part.cases_by_family[i];
    for (std::size_t i = 0; i < sum.cases_by_placement.size(); ++i)
      sum.cases_by_placement[i] += part.cases_by_placement[i];
    for (std::size_t r = 0; r < whole.runs.size(); ++r) {
      sum.runs[r].failures += part.runs[r].failures;
      sum.runs[r].checks += part.runs[r].checks;
      sum.runs[r].exact_mismatch_cases += part.runs[r].exact_mismatch_cases;
      sum.runs[r].sign_disagreement_cases += part.runs[r].sign_disagreement_cases;
    }
    for (const CampaignFailure& f : part.failures) {
      EXPECT_EQ(f.index % 4, k);  // only its own cases
      sum.failures.push_back(f);
    }
  }
  EXPECT_EQ(held, std::vector<int>(whole.cases, 1));
  EXPECT_EQ(sum.cases, expected.cases);
  EXPECT_EQ(sum.samples, expected.samples);
  EXPECT_EQ(sum.cases_by_family, expected.cases_by_family);
  EXPECT_EQ(sum.cases_by_placement, expected.cases_by_placement);
  for (std::size_t r = 0; r < whole.runs.size(); ++r) {
    SCOPED_TRACE(campaign_run_name(whole.runs[r]));
    EXPECT_EQ(sum.runs[r].failures, expected.runs[r].failures);
    EXPECT_EQ(sum.runs[r].checks, expected.runs[r].checks);
    EXPECT_EQ(sum.runs[r].exact_mismatch_cases, expected.runs[r].exact_mismatch_cases);
    EXPECT_EQ(sum.runs[r].sign_disagreement_cases, expected.runs[r].sign_disagreement_cases);
  }
  const auto key = [](const CampaignFailure& f) { return std::pair(f.index, f.run); };
  std::vector<std::pair<std::uint64_t, std::size_t>> got, want;
  for (const CampaignFailure& f : sum.failures) got.push_back(key(f));
  for (const CampaignFailure& f : expected.failures) want.push_back(key(f));
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, want);
}

TEST(SoupCampaign, ShardCounts_SplitTheCasesEvenly) {
  EXPECT_EQ(shard_case_count(10, {0, 3}), 4u);  // 0 3 6 9
  EXPECT_EQ(shard_case_count(10, {2, 3}), 3u);  // 2 5 8
  EXPECT_EQ(shard_case_count(2, {4, 5}), 0u);   // more shards than cases
  EXPECT_EQ(shard_case_count(7, {0, 1}), 7u);
  EXPECT_EQ(shard_case_index({2, 3}, 2), 8u);
}

TEST(SoupCampaign, BadOptions_Throw) {
  CampaignOptions options;
  options.runs.clear();
  EXPECT_THROW((void)run_campaign(options), std::invalid_argument);
  options = {};
  options.triangles = 0;
  EXPECT_THROW((void)run_campaign(options), std::invalid_argument);
  options = {};
  options.shard = {3, 3};  // index beyond the count
  EXPECT_THROW((void)run_campaign(options), std::invalid_argument);
  options.shard = {0, 0};
  EXPECT_THROW((void)run_campaign(options), std::invalid_argument);
}

}  // namespace
