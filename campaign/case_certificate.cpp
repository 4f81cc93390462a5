// certify_campaign_case (campaign/case_certificate.h): the exact pipeline once per case, one chain
// per distinct multiplicity answer, one set of samples and one occluder counter for all runs.
#include "campaign/case_certificate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "exact/chain_crossings.h"
#include "exact/closure_certificate.h"
#include "exact/count_certificate.h"
#include "exact/count_sampling.h"
#include "exact/face_crossing.h"
#include "exact/float_sign_bound.h"
#include "exact/light_orientation.h"
#include "exact/light_orientation_filter.h"
#include "exact/orient_unchecked.h"
#include "exact/shadow_volume_chain.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/split_mix_random.h"

namespace shadowcert {
namespace {


// Where straddle points land: this many ulps of the triangle's largest coordinate off its
// plane, to either side. Not a tolerance (no verdict depends on it; every count and crossing
// is exact wherever the points land): the barycentric point itself is off the plane by up to
// about 6 rounding errors of that magnitude (a + r (b - a) + s (c - a), three coordinates),
// and 16 ulps along the sign pattern of the normal put the two points on opposite sides in
// practice, as close to the triangle as that allows, where V(t) is thinnest.
constexpr double kStraddleUlps = 16.0;

// Streams of a case's sampling seed (scene/split_mix_random.h), one per purpose.
constexpr std::uint64_t kTargetStream = 21;
constexpr std::uint64_t kStraddleStream = 22;
constexpr std::uint64_t kBoxStream = 23;

void require_valid_light(const Light& light) { require_defined(light, "certify_campaign_case"); }

// One ulp of x (> 0), or the smallest normal for 0.
double grain(double x) {
  if (x == 0.0) return std::numeric_limits<double>::min();
  return std::nextafter(x, std::numeric_limits<double>::infinity()) - x;
}

struct Sample {
  Vec3 point{};
  std::uint32_t count = 0;  // n(point), defined
};

struct SamplePair {
  Sample from;
  Sample to;
};

// Draws samples with defined counts, re-drawing while a sample's budget lasts.
class SampleDrawer {
 public:
  SampleDrawer(const Soup& canonical, const OccluderCounter& counter, const CampaignSampling& sampling,
               CaseVerdict& verdict)
      : soup_(canonical),
        counter_(counter),
        sampling_(sampling),
        verdict_(verdict),
        box_(detail::sampling_box(canonical)) {}

  [[nodiscard]] const Box& box() const { return box_; }

  // Points on either side of triangle t's plane (t with three distinct indices).
  std::optional<SamplePair> straddle(std::uint32_t t, SplitMixRandom& rng) {
    for (std::uint32_t attempt = 0;; ++attempt) {
      if (std::optional<SamplePair> pair = try_straddle(soup_.triangles[t], rng)) return pair;
      if (!spend(attempt)) return std::nullopt;
    }
  }

  std::optional<Sample> in_box(SplitMixRandom& rng) {
    for (std::uint32_t attempt = 0;; ++attempt) {
      Vec3 p{};
      for (int d = 0; d < 3; ++d)
        p[d] = std::clamp(box_.lo[d] + rng.unit() * (box_.hi[d] - box_.lo[d]), box_.lo[d], box_.hi[d]);
      if (const std::optional<std::uint32_t> n = counter_.count(p)) return Sample{p, *n};
      if (!spend(attempt)) return std::nullopt;
    }
  }

 private:
  bool spend(std::uint32_t attempt) {
    if (attempt >= sampling_.max_redraws) {
      ++verdict_.lost;
      return false;
    }
    ++verdict_.redrawn;
    return true;
  }

  std::optional<SamplePair> try_straddle(const Triangle& t, SplitMixRandom& rng) const {
    const Vec3 &a = soup_.vertices[t[0]], &b = soup_.vertices[t[1]], &c = soup_.vertices[t[2]];
    double r = rng.unit(), s = rng.unit();
    if (r + s > 1.0) {  // fold the unit square onto the triangle: uniform barycentrics
      r = 1.0 - r;
      s = 1.0 - s;
    }
    Vec3 p{}, normal{};
    double reach = 0.0;
    for (int i = 0; i < 3; ++i) {
      p[i] = a[i] + r * (b[i] - a[i]) + s * (c[i] - a[i]);
      reach = std::max({reach, std::fabs(a[i]), std::fabs(b[i]), std::fabs(c[i]), std::fabs(p[i])});
    }
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      normal[i] = (b[j] - a[j]) * (c[k] - a[k]) - (b[k] - a[k]) * (c[j] - a[j]);
    }
    const double step = kStraddleUlps * grain(reach);
    SamplePair pair;
    for (int i = 0; i < 3; ++i) {
      const double along = normal[i] > 0.0 ? step : (normal[i] < 0.0 ? -step : 0.0);
      pair.from.point[i] = p[i] + along;
      pair.to.point[i] = p[i] - along;
    }
    const std::optional<std::uint32_t> n_from = counter_.count(pair.from.point);
    if (!n_from) return std::nullopt;
    const std::optional<std::uint32_t> n_to = counter_.count(pair.to.point);
    if (!n_to) return std::nullopt;
    pair.from.count = *n_from;
    pair.to.count = *n_to;
    return pair;
  }

  const Soup& soup_;
  const OccluderCounter& counter_;
  const CampaignSampling& sampling_;
  CaseVerdict& verdict_;
  Box box_;
};

bool distinct_indices(const Triangle& t) { return t[0] != t[1] && t[1] != t[2] && t[2] != t[0]; }

// One distinct answer (multiplicities and cap signs) and everything that depends only on it.
struct DistinctChain {
  std::size_t first_run = 0;
  ShadowVolumeChain chain;
  std::vector<std::uint32_t> side_edge_id;  // the table edge of each of chain.side_edges
  ClosureCertificate closure;
  // Triangles (canonical indices) whose cap sign differs from the exact one, and, among those
  // with an exact sign, c(t) = s_method * s_exact (0 or -1) for the claimed count.
  std::vector<std::uint32_t> disagreeing;
  std::vector<std::uint32_t> claimed_triangles;
  std::vector<int> claimed_weight;  // 1 - c(t): what [P in V(t)] subtracts from n(P)
  // Triangles that contain the (point) light, exact sign 0, given a nonzero sign: their faces
  // all lie in their plane, so pairs that do not cross it are still compared.
  std::vector<std::uint32_t> holding_light;
};

bool same_answer(const EdgeMultiplicities& a, const EdgeMultiplicities& b) {
  return a.triangle_sign == b.triangle_sign && a.multiplicity == b.multiplicity;
}

// True iff the point light lies on the closed triangle abc (which spans a plane through it).
// Q is any point off the plane (a rounded a + unit axis: only its exact side matters); L lies
// in the closed triangle iff, for each edge pq with opposite vertex r, L is on r's side of the
// plane (Q, p, q) or on it.
bool triangle_holds_light(const Vec3& a, const Vec3& b, const Vec3& c, const Light& light) {
  if (light.directional()) return false;  // a point at infinity lies on no finite triangle
  const HomogeneousPoint pa = finite_point(a), pb = finite_point(b), pc = finite_point(c), l = light.position;
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 q = a;
    q[axis] += q[axis] == 0.0 ? 1.0 : std::fabs(q[axis]);
    const HomogeneousPoint pq = finite_point(q);
    if (orient(pa, pb, pc, pq) == Sign::zero) continue;
    for (const auto& [p, r, o] : {std::array{pa, pb, pc}, std::array{pb, pc, pa}, std::array{pc, pa, pb}}) {
      const Sign inner = orient(pq, p, r, o), side = orient(pq, p, r, l);
      if (side != Sign::zero && side != inner) return false;
    }
    return true;
  }
  return false;  // no area: no face of any volume
}

// True iff the closed segment AB meets the plane of a triangle of `triangles` (the faces of a
// triangle holding the light all lie in its plane).
bool meets_a_plane(const std::vector<std::uint32_t>& triangles, const Soup& canonical, const Vec3& a, const Vec3& b) {
  for (std::uint32_t t : triangles) {
    const Triangle& tri = canonical.triangles[t];
    const HomogeneousPoint p = finite_point(canonical.vertices[tri[0]]), q = finite_point(canonical.vertices[tri[1]]),
                           r = finite_point(canonical.vertices[tri[2]]);
    const Sign sa = orient(p, q, r, finite_point(a)), sb = orient(p, q, r, finite_point(b));
    if (sa == Sign::zero || sb == Sign::zero || sa != sb) return true;
  }
  return false;
}

// The sample points of a case and the pairs compared: targeted straddles, random straddles,
// then the box points in order of x (consecutive box points make medium-length segments).
struct Samples {
  std::vector<Sample> points;
  std::vector<std::array<std::uint32_t, 2>> pairs;  // indices into points: from, to

  void add_pair(const SamplePair& p) {
    const auto first = static_cast<std::uint32_t>(points.size());
    points.push_back(p.from);
    points.push_back(p.to);
    pairs.push_back({first, first + 1});
  }
};

Samples draw_samples(const Soup& canonical, const std::vector<std::uint32_t>& targets, SampleDrawer& drawer,
                     const CampaignSampling& sampling) {
  Samples samples;
  SplitMixRandom target_rng{sampling.seed, kTargetStream};
  if (targets.size() <= sampling.targeted_pairs) {  // every target, once
    for (std::uint32_t t : targets)
      if (std::optional<SamplePair> p = drawer.straddle(t, target_rng)) samples.add_pair(*p);
  } else {  // a random choice among them
    for (std::uint32_t k = 0; k < sampling.targeted_pairs; ++k)
      if (std::optional<SamplePair> p = drawer.straddle(targets[target_rng() % targets.size()], target_rng))
        samples.add_pair(*p);
  }
  std::vector<std::uint32_t> candidates;
  for (std::uint32_t t = 0; t < canonical.triangles.size(); ++t)
    if (distinct_indices(canonical.triangles[t])) candidates.push_back(t);
  if (!candidates.empty()) {
    SplitMixRandom rng{sampling.seed, kStraddleStream};
    for (std::uint32_t k = 0; k < sampling.straddle_pairs; ++k)
      if (std::optional<SamplePair> p = drawer.straddle(candidates[rng() % candidates.size()], rng))
        samples.add_pair(*p);
  }
  SplitMixRandom rng{sampling.seed, kBoxStream};
  std::vector<Sample> box;
  for (std::uint32_t k = 0; k < sampling.in_box; ++k)
    if (std::optional<Sample> s = drawer.in_box(rng)) box.push_back(*s);
  std::sort(box.begin(), box.end(), [](const Sample& a, const Sample& b) { return a.point < b.point; });
  for (std::size_t k = 0; k < box.size(); ++k) {
    samples.points.push_back(box[k]);
    if (k > 0) {
      const auto to = static_cast<std::uint32_t>(samples.points.size() - 1);
      samples.pairs.push_back({to - 1, to});
    }
  }
  return samples;
}

// orient(a, b, c, x) for finite a, b, c and x finite or a direction (docs/definitions.md#orientation): the inline
// semi-static stage of exact/light_orientation_filter.h (CGAL's certified Orientation_3
// filter, D(a, b, c, L) with x in the light's place), then the full predicate where it cannot
// certify. Same signs as orient, at a fraction of the cost for these many small queries.
Sign orient_with_last(const Vec3& a, const Vec3& b, const Vec3& c, const HomogeneousPoint& x) {
  if (const std::optional<Sign> quick = detail::semi_static_light_orientation(a, b, c, x)) return *quick;
  return detail::orient_unchecked(finite_point(a), finite_point(b), finite_point(c), x);
}

// The plane side of every face any distinct chain has, at every sample point. A pair whose two
// points lie strictly on the same side of a face's plane cannot meet that face (the face tests
// of exact/face_crossing.h answer `apart` at once there), so only the faces left, usually one
// or two, go to the every-face crossing count detail::chain_crossings_of_segment, in a reduced
// chain: the same face tests and sign rules as every certificate, minus the work the signs
// computed once per point already did.
class PlaneSides {
 public:
  PlaneSides(const Soup& canonical, const EdgeTable& table, const Light& light, const std::vector<bool>& caps,
             const std::vector<bool>& sides, const std::vector<Sample>& points)
      : points_(points.size()),
        cap_(canonical.triangles.size() * points.size(), Sign::zero),
        side_(table.size() * points.size(), Sign::zero) {
    const HomogeneousPoint& l = light.position;
    for (std::size_t t = 0; t < caps.size(); ++t) {
      if (!caps[t]) continue;
      const Triangle& tri = canonical.triangles[t];
      const Vec3 &a = canonical.vertices[tri[0]], &b = canonical.vertices[tri[1]], &c = canonical.vertices[tri[2]];
      for (std::size_t i = 0; i < points.size(); ++i)  // orient(a, b, c, P)
        cap_[t * points_ + i] = orient_with_last(a, b, c, finite_point(points[i].point));
    }
    const Vec3 l_xyz{l[0], l[1], l[2]};
    for (std::size_t e = 0; e < sides.size(); ++e) {
      if (!sides[e]) continue;
      const Vec3 &u = canonical.vertices[table.edges[e][0]], &v = canonical.vertices[table.edges[e][1]];
      for (std::size_t i = 0; i < points.size(); ++i) {
        const HomogeneousPoint p = finite_point(points[i].point);
        // orient(L, u, v, P): directly for a point light; for a directional one, by two
        // transpositions and one more, -orient(u, v, P, L), whose last point is the direction.
        side_[e * points_ + i] =
            l[3] != 0.0 ? orient_with_last(l_xyz, u, v, p) : -orient_with_last(u, v, points[i].point, l);
      }
    }
  }

  // True iff points i and j lie strictly on one side of the plane of cap t / of side edge e.
  [[nodiscard]] bool cap_apart(std::size_t t, std::size_t i, std::size_t j) const {
    return apart(cap_[t * points_ + i], cap_[t * points_ + j]);
  }
  [[nodiscard]] bool side_apart(std::size_t e, std::size_t i, std::size_t j) const {
    return apart(side_[e * points_ + i], side_[e * points_ + j]);
  }
  [[nodiscard]] Sign cap_side(std::size_t t, std::size_t i) const { return cap_[t * points_ + i]; }

 private:
  static bool apart(Sign a, Sign b) { return a == b && a != Sign::zero; }
  std::size_t points_;
  std::vector<Sign> cap_;
  std::vector<Sign> side_;
};

// The claimed count minus n(P) at point i (campaign/case_certificate.h): - Σ (1 - c(t)) [P in V(t)]
// over the triangles whose sign differs; nullopt when P -> light touches one of them. P on the
// light's side of t's plane (a sign already known) is never in V(t).
std::optional<std::int64_t> claimed_offset(const DistinctChain& d, const Soup& canonical, const HomogeneousPoint& light,
                                           const std::vector<Sign>& exact_sign, const PlaneSides& sides,
                                           const Samples& samples, std::size_t i) {
  std::int64_t offset = 0;
  for (std::size_t k = 0; k < d.claimed_triangles.size(); ++k) {
    const std::uint32_t t = d.claimed_triangles[k];
    if (sides.cap_side(t, i) == exact_sign[t]) continue;
    const Triangle& tri = canonical.triangles[t];
    const auto& v = canonical.vertices;
    switch (detail::segment_meets_triangle(finite_point(samples.points[i].point), light, exact_sign[t], v[tri[0]],
                                           v[tri[1]], v[tri[2]])
                .meeting) {
      case detail::Meeting::apart:
        break;
      case detail::Meeting::crosses:
        offset -= d.claimed_weight[k];
        break;
      case detail::Meeting::touches:
        return std::nullopt;
    }
  }
  return offset;
}

// Crossings of pair (i, j) with chain d: the faces the plane signs cannot rule out, counted by
// detail::chain_crossings_of_segment; nullopt on a touch.
std::optional<std::int64_t> pair_crossings(const DistinctChain& d, const Soup& canonical, const Light& light,
                                           const PlaneSides& sides, const Samples& samples, std::size_t i,
                                           std::size_t j) {
  ShadowVolumeChain reduced;
  reduced.finite_vertices = d.chain.finite_vertices;
  reduced.directional = d.chain.directional;
  for (std::size_t k = 0; k < d.chain.cap_triangles.size(); ++k) {
    if (sides.cap_apart(d.chain.cap_triangles[k], i, j)) continue;
    reduced.cap_triangles.push_back(d.chain.cap_triangles[k]);
    reduced.cap_sign.push_back(d.chain.cap_sign[k]);
  }
  for (std::size_t k = 0; k < d.chain.side_edges.size(); ++k) {
    if (sides.side_apart(d.side_edge_id[k], i, j)) continue;
    reduced.side_edges.push_back(d.chain.side_edges[k]);
    reduced.side_multiplicity.push_back(d.chain.side_multiplicity[k]);
  }
  if (reduced.cap_triangles.empty() && reduced.side_edges.empty()) return 0;
  return detail::chain_crossings_of_segment({canonical, light, reduced}, samples.points[i].point,
                                            samples.points[j].point);
}

// Compares every pair with one distinct chain; fills the verdict fields that depend on the
// chain alone.
void check_pairs(const DistinctChain& d, const Soup& canonical, const Light& light, const std::vector<Sign>& exact_sign,
                 const PlaneSides& sides, const Samples& samples, RunVerdict& verdict) {
  const HomogeneousPoint l = light.position;
  for (const auto& [i, j] : samples.pairs) {
    const Sample &from = samples.points[i], &to = samples.points[j];
    const std::optional<std::int64_t> crossed = pair_crossings(d, canonical, light, sides, samples, i, j);
    const std::optional<std::int64_t> offset_from = claimed_offset(d, canonical, l, exact_sign, sides, samples, i);
    const std::optional<std::int64_t> offset_to = claimed_offset(d, canonical, l, exact_sign, sides, samples, j);
    if (!crossed || !offset_from || !offset_to) {
      ++verdict.skipped;
      continue;
    }
    CheckedPair checked;
    checked.from = from.point;
    checked.to = to.point;
    checked.exact_change = std::int64_t{to.count} - std::int64_t{from.count};
    checked.claimed_change = checked.exact_change + *offset_to - *offset_from;
    checked.crossed = *crossed;
    ++verdict.checks;
    if (checked.crossed != checked.exact_change) {
      ++verdict.exact_mismatches;
      if (!verdict.first_exact_mismatch) verdict.first_exact_mismatch = checked;
    }
    if (meets_a_plane(d.holding_light, canonical, checked.from, checked.to)) {
      ++verdict.inconclusive;  // the chain of a triangle holding the light: no claim there
      continue;
    }
    if (checked.crossed != checked.claimed_change) {
      ++verdict.count_failures;
      if (!verdict.first_count_failure) verdict.first_count_failure = checked;
    }
  }
}

}  // namespace

CaseVerdict certify_campaign_case(const Soup& soup, const Light& light, const std::vector<CampaignRun>& runs,
                              const CampaignSampling& sampling) {
  require_valid_light(light);
  require_finite_vertices(soup, "certify_campaign_case");
  require_indices_in_range(soup, "certify_campaign_case");
  const Soup canonical = canonical_soup(soup).soup;
  const EdgeTable table = build_edge_table(canonical);
  const EdgeMultiplicities exact = exact_multiplicities(canonical, table, light);

  // Every run's answer; a run whose multiplicities AND cap signs equal an earlier run's has the
  // identical chain (assemble_chain is a pure function of them), hence the identical closure
  // certificate and identical crossings at every sample: its verdict is shared, only the
  // precision-dependent check (b) is redone. No chain that differs is ever skipped.
  std::vector<DistinctChain> distinct;
  std::vector<std::size_t> chain_of_run(runs.size());
  std::vector<EdgeMultiplicities> answers;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const CampaignRun& run = runs[r];
    EdgeMultiplicities m = run.multiplicities ? run.multiplicities(canonical, table, light)
                           : run.method == MultiplicityMethod::exact
                               ? exact
                               : edge_multiplicities(run.method, canonical, table, light, run.precision);
    std::size_t found = distinct.size();
    for (std::size_t k = 0; k < distinct.size(); ++k)
      if (same_answer(answers[distinct[k].first_run], m)) found = k;
    chain_of_run[r] = found;
    answers.push_back(std::move(m));
    if (found < distinct.size()) continue;
    DistinctChain d;
    d.first_run = r;
    const EdgeMultiplicities& answer = answers.back();
    d.chain = assemble_chain(canonical, table, answer, light);
    for (std::uint32_t e = 0; e < table.size(); ++e)
      if (answer.multiplicity[e] != 0) d.side_edge_id.push_back(e);  // assemble_chain's order
    d.closure = certify_closure(d.chain);
    for (std::uint32_t t = 0; t < canonical.triangles.size(); ++t) {
      const Sign s = answer.triangle_sign[t], e = exact.triangle_sign[t];
      if (s == e) continue;
      d.disagreeing.push_back(t);
      if (e == Sign::zero) {  // the light in t's plane: V(t) is flat, it winds nowhere...
        const Triangle& tri = canonical.triangles[t];
        if (s != Sign::zero && triangle_holds_light(canonical.vertices[tri[0]], canonical.vertices[tri[1]],
                                                    canonical.vertices[tri[2]], light))
          d.holding_light.push_back(t);  // ...unless the light lies on t (header)
        continue;
      }
      d.claimed_triangles.push_back(t);
      d.claimed_weight.push_back(1 - to_int(s * e));
    }
    distinct.push_back(std::move(d));
  }

  CaseVerdict verdict;
  verdict.runs.resize(runs.size());
  std::vector<std::uint32_t> targets;
  for (const DistinctChain& d : distinct) {
    targets.insert(targets.end(), d.claimed_triangles.begin(), d.claimed_triangles.end());
    targets.insert(targets.end(), d.holding_light.begin(), d.holding_light.end());
  }
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());

  const OccluderCounter counter(canonical, light);
  SampleDrawer drawer(canonical, counter, sampling, verdict);
  const Samples samples = draw_samples(canonical, targets, drawer, sampling);
  verdict.samples = samples.points.size();
  std::vector<bool> caps(canonical.triangles.size(), false), sides(table.size(), false);
  for (const DistinctChain& d : distinct) {
    for (std::uint32_t t : d.chain.cap_triangles) caps[t] = true;
    for (std::uint32_t t : d.claimed_triangles) caps[t] = true;  // claimed_offset reads their sides
    for (std::uint32_t e : d.side_edge_id) sides[e] = true;
  }
  const PlaneSides plane_sides(canonical, table, light, caps, sides, samples.points);

  std::vector<RunVerdict> chain_verdicts(distinct.size());
  for (std::size_t k = 0; k < distinct.size(); ++k) {
    RunVerdict& v = chain_verdicts[k];
    v.closed = distinct[k].closure.closed;
    v.unbalanced_edges = distinct[k].closure.unbalanced.size();
    v.sign_disagreements = static_cast<std::uint32_t>(distinct[k].disagreeing.size());
    v.light_on_triangle = static_cast<std::uint32_t>(distinct[k].holding_light.size());
    check_pairs(distinct[k], canonical, light, exact.triangle_sign, plane_sides, samples, v);
  }
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const DistinctChain& d = distinct[chain_of_run[r]];
    RunVerdict& v = verdict.runs[r];
    v = chain_verdicts[chain_of_run[r]];
    v.shared = d.first_run != r;
    // (b): a sign that differs from the exact one must be undecided at the run's precision.
    for (std::uint32_t t : d.disagreeing) {
      const Triangle& tri = canonical.triangles[t];
      const auto& p = canonical.vertices;
      if (!float_sign_is_decided(p[tri[0]], p[tri[1]], p[tri[2]], light, runs[r].precision)) continue;
      if (v.decided_sign_errors++ == 0) v.first_decided_error = t;
    }
  }
  return verdict;
}

}  // namespace shadowcert
