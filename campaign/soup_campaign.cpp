#include "campaign/soup_campaign.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "campaign/soup_shrinker.h"
#include "scene/split_mix_random.h"

namespace shadowcert {
namespace {

// Cases per task at least: large enough to amortise scheduling, small enough to balance the
// cores near the end.
constexpr std::size_t kCasesPerTask = 16;

struct Partial {
  std::vector<CampaignRunTally> runs;
  std::vector<std::uint64_t> cases_by_family = std::vector<std::uint64_t>(kSoupFamilies, 0);
  std::vector<std::uint64_t> cases_by_placement = std::vector<std::uint64_t>(kLightPlacements, 0);
  std::uint64_t cases = 0, samples = 0, redrawn = 0, lost = 0;
  std::vector<CampaignFailure> failures;
};

void add(std::vector<std::uint64_t>& to, const std::vector<std::uint64_t>& from) {
  for (std::size_t i = 0; i < to.size(); ++i) to[i] += from[i];
}

void tally(CampaignRunTally& t, const RunVerdict& v, const CampaignCaseKind& kind) {
  t.failures += v.failed();
  t.closure_failures += v.closure_failed();
  t.count_failures += v.count_failed();
  t.decided_sign_error_cases += v.decided_sign_errors > 0;
  t.sign_disagreement_cases += v.sign_disagreements > 0;
  t.light_on_triangle_cases += v.light_on_triangle > 0;
  t.exact_mismatch_cases += v.exact_mismatches > 0;
  t.checks += v.checks;
  t.skipped += v.skipped;
  t.inconclusive += v.inconclusive;
  if (v.failed()) {
    ++t.failures_by_family[static_cast<std::size_t>(kind.family)];
    ++t.failures_by_placement[static_cast<std::size_t>(kind.light)];
  }
}

void merge(CampaignRunTally& to, const CampaignRunTally& from) {
  to.failures += from.failures;
  to.closure_failures += from.closure_failures;
  to.count_failures += from.count_failures;
  to.decided_sign_error_cases += from.decided_sign_error_cases;
  to.sign_disagreement_cases += from.sign_disagreement_cases;
  to.light_on_triangle_cases += from.light_on_triangle_cases;
  to.exact_mismatch_cases += from.exact_mismatch_cases;
  to.checks += from.checks;
  to.skipped += from.skipped;
  to.inconclusive += from.inconclusive;
  add(to.failures_by_family, from.failures_by_family);
  add(to.failures_by_placement, from.failures_by_placement);
}

void run_case(const CampaignOptions& options, std::uint64_t index, Partial& p) {
  const CampaignCase c = campaign_case(options.seed, index, options.triangles);
  const CaseVerdict v =
      certify_campaign_case(c.soup, c.light, options.runs, campaign_sampling_for_case(options.sampling, options.seed, index));
  ++p.cases;
  ++p.cases_by_family[static_cast<std::size_t>(c.kind.family)];
  ++p.cases_by_placement[static_cast<std::size_t>(c.kind.light)];
  p.samples += v.samples;
  p.redrawn += v.redrawn;
  p.lost += v.lost;
  for (std::size_t r = 0; r < options.runs.size(); ++r) {
    const RunVerdict& rv = v.runs[r];
    tally(p.runs[r], rv, c.kind);
    if (rv.failed() && (must_not_fail(options.runs[r]) || options.shrink_findings))
      p.failures.push_back({index, r, failure_kind(rv)});
  }
}

bool before(const CampaignFailure& a, const CampaignFailure& b) {
  return a.index != b.index ? a.index < b.index : a.run < b.run;
}

}  // namespace

CampaignSampling campaign_sampling_for_case(const CampaignSampling& sampling, std::uint64_t seed, std::uint64_t index) {
  CampaignSampling s = sampling;
  s.seed = split_mix(split_mix(seed) ^ index);
  return s;
}

CampaignFailureKind failure_kind(const RunVerdict& verdict) {
  return verdict.closure_failed() ? CampaignFailureKind::closure : CampaignFailureKind::counts;
}

CampaignResult run_campaign(const CampaignOptions& options) {
  if (options.runs.empty()) throw std::invalid_argument("run_campaign: no method run");
  if (options.triangles == 0) throw std::invalid_argument("run_campaign: a case needs at least one triangle");
  if (!valid_case_shard(options.shard))
    throw std::invalid_argument("run_campaign: a shard needs count >= 1 and index < count");
  const auto start = std::chrono::steady_clock::now();
  tbb::combinable<Partial> partials([&options] {
    Partial p;
    p.runs.resize(options.runs.size());
    return p;
  });
  // j runs over the shard's cases; each is certified under its campaign index.
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, shard_case_count(options.cases, options.shard), kCasesPerTask),
                    [&](const tbb::blocked_range<std::uint64_t>& range) {
                      Partial& p = partials.local();
                      for (std::uint64_t j = range.begin(); j < range.end(); ++j) {
                        run_case(options, shard_case_index(options.shard, j), p);
                        if (options.progress != nullptr) options.progress->fetch_add(1, std::memory_order_relaxed);
                      }
                    });
  CampaignResult result;
  result.runs.resize(options.runs.size());
  partials.combine_each([&result](const Partial& p) {
    result.cases += p.cases;
    for (std::size_t r = 0; r < p.runs.size(); ++r) merge(result.runs[r], p.runs[r]);
    add(result.cases_by_family, p.cases_by_family);
    add(result.cases_by_placement, p.cases_by_placement);
    result.samples += p.samples;
    result.redrawn += p.redrawn;
    result.lost += p.lost;
    result.failures.insert(result.failures.end(), p.failures.begin(), p.failures.end());
  });
  std::sort(result.failures.begin(), result.failures.end(), before);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // The first failures of each run, shrunk in parallel.
  const auto shrink_start = std::chrono::steady_clock::now();
  std::vector<CampaignFailure> chosen;
  std::vector<std::size_t> per_run(options.runs.size(), 0);
  for (const CampaignFailure& f : result.failures)
    if (per_run[f.run]++ < options.max_shrunk_per_run) chosen.push_back(f);
  result.shrunk.resize(chosen.size());
  tbb::parallel_for(std::size_t{0}, chosen.size(),
                    [&](std::size_t k) { result.shrunk[k] = shrink_failure(options, chosen[k]); });
  result.shrink_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - shrink_start).count();
  return result;
}

ShrunkFailure shrink_failure(const CampaignOptions& options, const CampaignFailure& failure) {
  if (failure.run >= options.runs.size()) throw std::invalid_argument("shrink_failure: run out of range");
  ShrunkFailure out;
  out.failure = failure;
  out.original = campaign_case(options.seed, failure.index, options.triangles);
  const CampaignSampling sampling = campaign_sampling_for_case(options.sampling, options.seed, failure.index);
  const Light light = out.original.light;
  // The same runs and sampling as the campaign (targeted samples depend on every run's signs).
  auto verdict_of = [&](const Soup& soup) {
    return certify_campaign_case(soup, light, options.runs, sampling).runs[failure.run];
  };
  // A count failure that `certify` can show (an exact mismatch at a pair, replayed with
  // --points) must stay one.
  const bool keep_mismatch =
      failure.kind == CampaignFailureKind::counts && verdict_of(out.original.soup).exact_mismatches > 0;
  const ShrinkResult shrunk = shrink_soup(out.original.soup, [&](const Soup& soup) {
    const RunVerdict v = verdict_of(soup);
    return v.failed() && failure_kind(v) == failure.kind && (!keep_mismatch || v.exact_mismatches > 0);
  });
  out.soup = shrunk.soup;
  out.tests = shrunk.tests;
  out.minimal = shrunk.minimal;
  out.verdict = verdict_of(out.soup);
  return out;
}

}  // namespace shadowcert
