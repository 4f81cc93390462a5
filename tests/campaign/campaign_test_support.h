#pragma once
// Planted faults for the campaign tests: method runs whose chain is wrong on purpose, so that the
// campaign's certificates and shrinker can be seen to catch and minimise a failure.
// Header-only, test code only.
#include <cstdint>

#include "exact/edge_multiplicity.h"
#include "campaign/campaign_run.h"
#include "scene/edge_table.h"

namespace shadowcert::test_support {

enum class PlantedFault { consistent_flip, cap_only_flip };

// refedge in double, except that the first triangle (canonical order) with a nonzero sign has
// it reversed: consistent_flip reverses its caps and its three edge entries (a closed chain,
// -dV(t) instead of dV(t): wrong counts behind t), cap_only_flip only its caps (an open chain).
inline CampaignRun planted_run(PlantedFault fault) {
  CampaignRun run{MultiplicityMethod::refedge,
              Precision::float64,
              {},
              fault == PlantedFault::consistent_flip ? "planted-consistent-flip" : "planted-cap-flip"};
  run.multiplicities = [fault](const Soup& canonical, const EdgeTable& table, const Light& light) {
    EdgeMultiplicities m =
        edge_multiplicities(MultiplicityMethod::refedge, canonical, table, light, Precision::float64);
    std::uint32_t t = 0;
    while (t < m.triangle_sign.size() && m.triangle_sign[t] == Sign::zero) ++t;
    if (t == m.triangle_sign.size()) return m;  // nothing casts: nothing to flip
    m.triangle_sign[t] = -m.triangle_sign[t];
    if (fault == PlantedFault::cap_only_flip) return m;
    const std::vector<Sign> entries =
        edge_entry_signs(MultiplicityMethod::refedge, canonical, table, light, Precision::float64);
    for (std::size_t e = 0; e < table.size(); ++e)
      for (std::uint32_t i = table.first_opposite[e]; i < table.first_opposite[e + 1]; ++i)
        if (table.opposite_triangle[i] == t) m.multiplicity[e] += 2 * to_int(entries[i]);  // m = -sum: -s -> +s
    return m;
  };
  return run;
}

}  // namespace shadowcert::test_support
