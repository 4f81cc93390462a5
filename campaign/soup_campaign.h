#pragma once
// The random-soup campaign (docs/campaign.md): cases 0 .. N-1 of campaign/random_soup.h (or one
// shard of them, campaign/case_shard.h), each certified for
// every method run by campaign/case_certificate.h, in parallel over all cores (TBB). Every
// case depends only on (seed, index), so the result is the same whatever the thread count and
// schedule. Failing cases are then shrunk (campaign/soup_shrinker.h) to small soups that still
// fail the same way.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "campaign/case_certificate.h"
#include "campaign/campaign_run.h"
#include "campaign/case_shard.h"
#include "campaign/random_soup.h"

namespace shadowcert {

struct CampaignOptions {
  std::uint64_t seed = 1;
  std::uint64_t cases = 1000;     // the whole campaign's: cases 0 .. cases-1
  CaseShard shard;                // only these of them (default: all)
  std::uint32_t triangles = 100;  // per case, >= 1
  std::vector<CampaignRun> runs = all_campaign_runs();
  CampaignSampling sampling;                           // its seed is replaced per case (campaign_sampling_for_case)
  std::size_t max_shrunk_per_run = 4;              // failing cases shrunk per run: the first ones by index
  bool shrink_findings = false;                    // also shrink failures of runs allowed to fail (kim)
  std::atomic<std::uint64_t>* progress = nullptr;  // when set, incremented as cases complete
};

// What a failure is, for shrinking: the shrunk soup must fail the same way.
enum class CampaignFailureKind : std::uint8_t { closure, counts };

struct CampaignRunTally {
  std::uint64_t failures = 0;          // cases with a closure or count failure (RunVerdict::failed)
  std::uint64_t closure_failures = 0;  // cases whose chain is not closed
  std::uint64_t count_failures = 0;    // cases with a count failure (claim or decided sign)
  std::uint64_t decided_sign_error_cases = 0;
  std::uint64_t sign_disagreement_cases = 0;  // cases where some cap sign differs from the exact one
  std::uint64_t light_on_triangle_cases = 0;  // of them, a nonzero sign on a triangle holding the light
  std::uint64_t exact_mismatch_cases = 0;     // cases where some pair's crossings differ from n(B) - n(A)
  std::uint64_t checks = 0, skipped = 0, inconclusive = 0;
  std::vector<std::uint64_t> failures_by_family = std::vector<std::uint64_t>(kSoupFamilies, 0);
  std::vector<std::uint64_t> failures_by_placement = std::vector<std::uint64_t>(kLightPlacements, 0);
};

struct CampaignFailure {
  std::uint64_t index = 0;  // the case
  std::size_t run = 0;      // index into the options' runs
  CampaignFailureKind kind = CampaignFailureKind::closure;
};

struct ShrunkFailure {
  CampaignFailure failure;
  CampaignCase original;      // the case as generated
  Soup soup;              // the shrunk soup (same light)
  RunVerdict verdict;     // the failing run's verdict on the shrunk soup
  std::size_t tests = 0;  // shrinking cost, in case certificates
  bool minimal = false;
};

struct CampaignResult {
  std::uint64_t cases = 0;  // cases certified: the shard's
  double seconds = 0.0;  // the cases alone, shrinking excluded
  double shrink_seconds = 0.0;
  std::vector<CampaignRunTally> runs;  // one per run of the options
  std::vector<std::uint64_t> cases_by_family = std::vector<std::uint64_t>(kSoupFamilies, 0);
  std::vector<std::uint64_t> cases_by_placement = std::vector<std::uint64_t>(kLightPlacements, 0);
  std::uint64_t samples = 0, redrawn = 0, lost = 0;
  std::vector<CampaignFailure> failures;  // every failure of a must-not-fail run, then allowed ones
                                      // when shrink_findings; sorted by (index, run)
  std::vector<ShrunkFailure> shrunk;  // at most max_shrunk_per_run per run
};

// The sampling of case `index` of a campaign: `sampling` with a seed derived from both.
[[nodiscard]] CampaignSampling campaign_sampling_for_case(const CampaignSampling& sampling, std::uint64_t seed,
                                                  std::uint64_t index);

// The kind of failure of a failed verdict: closure when the chain is open, counts otherwise.
[[nodiscard]] CampaignFailureKind failure_kind(const RunVerdict& verdict);

// Throws std::invalid_argument("run_campaign: ...") on no runs, zero triangles or a bad shard.
[[nodiscard]] CampaignResult run_campaign(const CampaignOptions& options);

// Shrinks one failure of a campaign with these options (the same runs and sampling).
[[nodiscard]] ShrunkFailure shrink_failure(const CampaignOptions& options, const CampaignFailure& failure);

}  // namespace shadowcert
