#include "cli/comparison_json.h"

namespace shadowcert::cli {

nlohmann::json soft_errors_json(const SoftShadowErrors& e) {
  return {{"compared", e.compared},
          {"reference_only", e.reference_only},
          {"method_only", e.method_only},
          {"mean_error", e.mean_error},
          {"max_error", e.max_error},
          {"mean_signed_error", e.mean_signed_error},
          {"umbra", e.umbra},
          {"umbra_mean_error", e.umbra_mean_error},
          {"penumbra", e.penumbra},
          {"penumbra_mean_error", e.penumbra_mean_error},
          {"outside_penumbra", e.outside_penumbra},
          {"outside_penumbra_mean_error", e.outside_penumbra_mean_error},
          {"contact", e.contact},
          {"leaks", e.leaks},
          {"lit_facing", e.lit_facing},
          {"acne", e.acne},
          {"turned_away", e.turned_away},
          {"turned_away_mean_error", e.turned_away_mean_error},
          {"reference_ci95", e.reference_ci95},
          {"reference_noise", e.reference_noise}};
}

nlohmann::json analytic_counts_json(const AnalyticCounts& a) {
  return {{"receiver_agree", a.receiver_agree},         {"receiver_disagree", a.receiver_disagree},
          {"receiver_ambiguous", a.receiver_ambiguous}, {"caster_agree", a.caster_agree},
          {"caster_disagree", a.caster_disagree},       {"caster_band", a.caster_band},
          {"caster_ambiguous", a.caster_ambiguous}};
}

}  // namespace shadowcert::cli
