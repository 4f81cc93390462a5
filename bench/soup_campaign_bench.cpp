// Throughput of the random-soup campaign (docs/campaign.md): soups of 100 triangles per second with
// every method run (exact, kim, peciva and refedge in float and double), target at least 2,000
// per second on 2 cores. Also the two halves of one case on one thread: generating it
// (campaign/random_soup.h) and certifying it (campaign/case_certificate.h).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cstdint>

#include "campaign/soup_campaign.h"
#include "campaign/case_certificate.h"
#include "campaign/random_soup.h"

namespace {

using namespace shadowcert;

constexpr std::uint64_t kCasesPerIteration = 2000;
constexpr std::uint32_t kTriangles = 100;

// Cases run in parallel over range(0) threads; a new seed per iteration, so no case repeats.
void BM_Campaign(benchmark::State& state) {
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  CampaignOptions options;
  options.cases = kCasesPerIteration;
  options.triangles = kTriangles;
  std::uint64_t failures = 0;
  for (auto _ : state) {
    ++options.seed;
    const CampaignResult result = run_campaign(options);
    for (std::size_t r = 0; r < options.runs.size(); ++r)
      if (must_not_fail(options.runs[r])) failures += result.runs[r].failures;
  }
  state.counters["soups_per_second"] =
      benchmark::Counter(static_cast<double>(kCasesPerIteration), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["must_not_fail_failures"] = static_cast<double>(failures);
}
BENCHMARK(BM_Campaign)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_GenerateCase(benchmark::State& state) {
  std::uint64_t index = 0;
  for (auto _ : state) benchmark::DoNotOptimize(campaign_case(1, index++, kTriangles));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GenerateCase)->Unit(benchmark::kMicrosecond);

void BM_CertifyCase(benchmark::State& state) {
  const std::vector<CampaignRun> runs = all_campaign_runs();
  std::vector<CampaignCase> cases;
  for (std::uint64_t i = 0; i < 512; ++i) cases.push_back(campaign_case(1, i, kTriangles));
  std::size_t k = 0;
  for (auto _ : state) {
    const CampaignCase& c = cases[k++ % cases.size()];
    benchmark::DoNotOptimize(certify_campaign_case(c.soup, c.light, runs, campaign_sampling_for_case({}, 1, k)));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CertifyCase)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
