#pragma once
// The certificate of one campaign case (docs/campaign.md): a soup and a light, certified for a list
// of method runs (campaign/campaign_run.h) with the exact module's own pieces (docs/definitions.md#certificates):
// canonical soup, edge table, multiplicities, chain, closure certificate, and occluder counts
// at a few sample points chosen where a wrong chain shows.
//
// Right counts. A float method's chain is Σ_t c(t) dV(t) with c = s_method * s_exact
// (docs/certificates.md, "Float methods and counts right"): where a rounded sign differs from
// the exact one, the chain is, correctly, another chain. So a run's counts are right when
//   (a) at every sample pair (A, B), the crossings of AB with its chain equal the change of
//       its *claimed* count Σ_t c(t) [P in V(t)] (for exact, and for every run whose signs are
//       all exact, that is n(B) - n(A)), and
//   (b) every triangle whose sign differs from the exact one is *undecided* at the run's
//       precision (exact/float_sign_bound.h): a sign its own arithmetic decides must be exact.
// A pair where the crossings differ from the exact n(B) - n(A) although (a) and (b) hold is an
// *exact mismatch*: the visible effect of a legitimate rounding, reported, never a failure.
//   (c) One configuration escapes the claim: a point light lying ON a triangle (at a vertex,
//       on an edge, inside it). D = 0 there (undecided at every precision) but a float method
//       may round it to +-1; that triangle's chain then lies in its plane with nothing to
//       cancel its cap near the light (a half-space's boundary, or side faces degenerate at
//       the light), so its crossings are no count at all. Such triangles are reported
//       (light_on_triangle), pairs meeting their planes are not held to the claim
//       (inconclusive), every other pair still is. docs/campaign.md, "a light exactly on a
//       triangle", has the investigation.
//
// Samples. A flipped or missing triangle t changes the winding number inside V(t), whose
// thinnest part is just behind t; so most samples come in *straddle pairs*: a uniform point
// of a triangle moved 16 ulps to either side of its plane, one pair per triangle, first
// across every triangle whose sign a run got different from the exact one (the informative
// ones), then across random triangles. A few points in the sampling box, checked
// consecutively in lexicographic order, add longer segments that cross side faces. Any sample whose count is undefined
// (on a boundary) is re-drawn (docs/definitions.md#count-certificate); a pair whose segment touches a face of one chain is skipped for that
// chain. Every draw comes from streams of `seed`: a case's certificate is a pure function of (soup, light, runs,
// sampling).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "campaign/campaign_run.h"

namespace shadowcert {

struct CampaignSampling {
  std::uint32_t targeted_pairs = 4;  // straddle pairs across triangles whose sign some run changed
  std::uint32_t straddle_pairs = 4;  // straddle pairs across random triangles
  std::uint32_t in_box = 3;          // points in the sampling box (in_box - 1 pairs)
  std::uint32_t max_redraws = 8;     // per sample
  std::uint64_t seed = 1;
};

// One compared pair: the crossings of from -> to and what they should be.
struct CheckedPair {
  Vec3 from{};
  Vec3 to{};
  std::int64_t exact_change = 0;    // n(to) - n(from)
  std::int64_t claimed_change = 0;  // the run's claimed count's change
  std::int64_t crossed = 0;         // signed crossings with the run's chain
};

inline constexpr std::uint32_t kNoTriangle = 0xffffffffu;

struct RunVerdict {
  bool closed = false;
  std::uint64_t unbalanced_edges = 0;
  std::uint64_t checks = 0;                         // pairs compared
  std::uint64_t skipped = 0;                        // pairs whose segment touched a face of this chain
  std::uint64_t count_failures = 0;                 // pairs where crossed != claimed_change, (a)
  std::uint64_t exact_mismatches = 0;               // pairs where crossed != exact_change
  std::uint32_t sign_disagreements = 0;             // soup triangles whose cap sign differs from the exact one
  std::uint32_t decided_sign_errors = 0;            // of them, decided at the run's precision, (b)
  std::uint32_t light_on_triangle = 0;              // of them, triangles that contain the light (c)
  std::uint64_t inconclusive = 0;                   // pairs not compared with the claim because of (c)
  std::uint32_t first_decided_error = kNoTriangle;  // a canonical triangle index of (b)
  std::optional<CheckedPair> first_count_failure;
  std::optional<CheckedPair> first_exact_mismatch;
  bool shared = false;  // multiplicities and signs identical to an earlier run's: verdict shared

  [[nodiscard]] bool closure_failed() const { return !closed; }
  [[nodiscard]] bool count_failed() const { return count_failures > 0 || decided_sign_errors > 0; }
  [[nodiscard]] bool failed() const { return closure_failed() || count_failed(); }
};

struct CaseVerdict {
  std::vector<RunVerdict> runs;  // one per run, in the order given
  std::uint64_t samples = 0;     // sample points with a defined count
  std::uint64_t redrawn = 0;     // re-draws spent
  std::uint64_t lost = 0;        // samples given up after max_redraws
};

// Throws std::invalid_argument("certify_campaign_case: ...") on an invalid light (non-finite, w not
// 0 or 1, zero direction) or an index out of range; a soup may be empty.
[[nodiscard]] CaseVerdict certify_campaign_case(const Soup& soup, const Light& light, const std::vector<CampaignRun>& runs,
                                            const CampaignSampling& sampling);

}  // namespace shadowcert
