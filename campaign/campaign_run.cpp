#include "campaign/campaign_run.h"

#include <stdexcept>

namespace shadowcert {

std::string campaign_run_name(const CampaignRun& run) {
  if (!run.label.empty()) return run.label;
  if (run.method == MultiplicityMethod::exact) return "exact";
  return std::string(method_name(run.method)) + "-" + std::string(precision_name(run.precision));
}

bool must_not_fail(const CampaignRun& run) { return run.method != MultiplicityMethod::kim; }

std::vector<CampaignRun> all_campaign_runs() {
  std::vector<CampaignRun> runs{{MultiplicityMethod::exact, Precision::float64, {}, {}}};
  for (MultiplicityMethod m : {MultiplicityMethod::kim, MultiplicityMethod::peciva, MultiplicityMethod::refedge})
    for (Precision p : {Precision::float32, Precision::float64}) runs.push_back({m, p, {}, {}});
  return runs;
}

std::vector<CampaignRun> parse_campaign_runs(std::string_view list) {
  const std::vector<CampaignRun> every = all_campaign_runs();
  std::vector<bool> chosen(every.size(), false);
  std::size_t start = 0;
  bool any = false;
  while (start <= list.size()) {
    const std::size_t comma = list.find(',', start);
    const std::string_view entry = list.substr(start, comma == std::string_view::npos ? list.npos : comma - start);
    start = comma == std::string_view::npos ? list.size() + 1 : comma + 1;
    if (entry.empty()) continue;
    bool matched = false;
    for (std::size_t i = 0; i < every.size(); ++i) {
      if (entry == "all" || entry == campaign_run_name(every[i]) || entry == method_name(every[i].method)) {
        chosen[i] = true;
        matched = true;
      }
    }
    if (!matched)
      throw std::invalid_argument("parse_campaign_runs: unknown run '" + std::string(entry) +
                                  "' (exact, kim, peciva, refedge, all, or a run such as refedge-float)");
    any = true;
  }
  if (!any) throw std::invalid_argument("parse_campaign_runs: no run given");
  std::vector<CampaignRun> runs;
  for (std::size_t i = 0; i < every.size(); ++i)
    if (chosen[i]) runs.push_back(every[i]);
  return runs;
}

std::string_view precision_name(Precision precision) {
  switch (precision) {
    case Precision::float32:
      return "float";
    case Precision::float64:
      return "double";
  }
  throw std::invalid_argument("precision_name: unknown precision");
}

}  // namespace shadowcert
