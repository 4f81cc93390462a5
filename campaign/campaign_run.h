#pragma once
// A method run of the random-soup campaign (docs/campaign.md): one multiplicity method of
// exact/edge_multiplicity.h in one precision, named "exact", "kim-float", "refedge-double"...
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "exact/edge_multiplicity.h"
#include "scene/edge_table.h"

namespace shadowcert {

struct CampaignRun {
  MultiplicityMethod method = MultiplicityMethod::exact;
  Precision precision = Precision::float64;  // ignored by exact
  // When set, replaces edge_multiplicities(method, ..., precision): tests plant faults through
  // it. The answer is still judged as `method` in `precision` (its must-not-fail status and
  // the bound of exact/float_sign_bound.h).
  std::function<EdgeMultiplicities(const Soup& canonical, const EdgeTable& table, const Light& light)> multiplicities;
  std::string label;  // the name when not empty (a planted fault names itself)
};

// "exact", or "<method>-float" / "<method>-double"; the label when set.
[[nodiscard]] std::string campaign_run_name(const CampaignRun& run);

// exact, peciva and refedge are consistent per triangle (docs/definitions.md#counts): closed chains and right
// counts always. kim is not: its failures are findings, counted and reported.
[[nodiscard]] bool must_not_fail(const CampaignRun& run);

// The seven runs: exact, then kim, peciva, refedge, each in float and double.
[[nodiscard]] std::vector<CampaignRun> all_campaign_runs();

// A comma-separated list of "exact", "all", a method name (both precisions) or a run name
// ("refedge-float"); duplicates are dropped, the order is that of all_campaign_runs(). Throws
// std::invalid_argument("parse_campaign_runs: ...") naming an unknown entry, or on an empty list.
[[nodiscard]] std::vector<CampaignRun> parse_campaign_runs(std::string_view list);

[[nodiscard]] std::string_view precision_name(Precision precision);  // "float" or "double"

}  // namespace shadowcert
