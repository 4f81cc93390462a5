#pragma once
// The JSON of a method's figures against a truth, one layout for `diff --json` and bench.json
// (docs/cli.md, docs/bench.md#benchjson): against the exact soft reference
// (pipeline/soft_shadow_comparison.h) and against the analytic shadow
// (pipeline/analytic_comparison.h).
#include <nlohmann/json.hpp>

#include "pipeline/analytic_comparison.h"
#include "pipeline/soft_shadow_comparison.h"

namespace shadowcert::cli {

// Every field of `errors` under its own name: counts, mean and max errors, the regions', leaks
// at contact and acne.
[[nodiscard]] nlohmann::json soft_errors_json(const SoftShadowErrors& errors);

// The pixels on the receiver and on the caster: agree, disagree, ambiguous (and the caster's band).
[[nodiscard]] nlohmann::json analytic_counts_json(const AnalyticCounts& counts);

}  // namespace shadowcert::cli
