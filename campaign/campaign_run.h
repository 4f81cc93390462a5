#pragma once
// A method run of the fuzz campaign (docs/fuzzing.md): one multiplicity method of
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

struct FuzzRun {
  MultiplicityMethod method = MultiplicityMethod::exact;
  Precision precision = Precision::float64;  // ignored by exact
  // When set, replaces edge_multiplicities(method, ..., precision): tests plant faults through
  // it. The answer is still judged as `method` in `precision` (its must-not-fail status and
  // the bound of exact/float_sign_bound.h).
  std::function<EdgeMultiplicities(const Soup& canonical, const EdgeTable& table, const Light& light)> multiplicities;
  std::string label;  // the name when not empty (a planted fault names itself)
};

// "exact", or "<method>-float" / "<method>-double"; the label when set.
[[nodiscard]] std::string fuzz_run_name(const FuzzRun& run);

// exact, peciva and refedge are consistent per triangle (DESIGN.md §3): closed chains and right
// counts always. kim is not: its failures are findings, counted and reported.
[[nodiscard]] bool must_not_fail(const FuzzRun& run);

// The seven runs: exact, then kim, peciva, refedge, each in float and double.
[[nodiscard]] std::vector<FuzzRun> all_fuzz_runs();

// A comma-separated list of "exact", "all", a method name (both precisions) or a run name
// ("refedge-float"); duplicates are dropped, the order is that of all_fuzz_runs(). Throws
// std::invalid_argument("parse_fuzz_runs: ...") naming an unknown entry, or on an empty list.
[[nodiscard]] std::vector<FuzzRun> parse_fuzz_runs(std::string_view list);

[[nodiscard]] std::string_view precision_name(Precision precision);  // "float" or "double"

}  // namespace shadowcert
