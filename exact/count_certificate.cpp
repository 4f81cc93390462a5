// certify_counts (exact/count_certificate.h, docs/definitions.md#count-certificate): sample points with exact direct
// counts, checked in Morton order, each against its predecessor: the signed crossings of the
// short segment between them must equal the difference of their direct counts.
#include "exact/count_certificate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "core/portable_math.h"
#include "exact/chain_crossings.h"
#include "exact/count_sampling.h"

namespace shadowcert {
namespace {


enum class SampleKind : std::uint8_t { in_box, near_triangle, user };

// Stream kinds of detail::sample_stream: every random draw has its own reproducible stream.
constexpr std::uint64_t kInBoxStream = 1;
constexpr std::uint64_t kNearTriangleStream = 2;
constexpr std::uint64_t kRedrawStream = 3;
constexpr std::uint64_t kReferenceStream = 4;
constexpr std::size_t kBlock = 1024;  // samples per stream in the drawing phase
constexpr std::size_t kReportedFailures = 16;

// A point with its direct count n (docs/definitions.md#counts), defined: the point is on no boundary.
struct Sample {
  Vec3 point{};
  std::uint32_t count = 0;
  SampleKind kind = SampleKind::in_box;
  std::uint32_t redraws = 0;  // re-draws this sample has used so far
};

// Draws random samples with a defined count, re-drawing (docs/definitions.md#count-certificate: never guessing)
// while the per-sample budget lasts.
class Sampler {
 public:
  Sampler(const Soup& soup, const OccluderCounter& counter, const Box& box, const CountSampling& sampling)
      : soup_(soup), counter_(counter), box_(box), max_redraws_(sampling.max_redraws) {}

  [[nodiscard]] const Box& box() const { return box_; }

  // nullopt when the budget ran out; `redraws` counts the re-draws used, across calls.
  [[nodiscard]] std::optional<Sample> draw(SampleKind kind, std::mt19937_64& rng, std::uint32_t& redraws) const {
    for (;;) {
      const Vec3 p = kind == SampleKind::near_triangle ? detail::draw_near_triangle(soup_, rng)
                                                        : detail::draw_in_box(box_, rng);
      if (const std::optional<std::uint32_t> n = counter_.count(p)) return Sample{p, *n, kind, redraws};
      if (!spend(redraws)) return std::nullopt;
    }
  }

  // Takes one re-draw from the budget; false when none is left.
  [[nodiscard]] bool spend(std::uint32_t& redraws) const {
    if (redraws >= max_redraws_) return false;
    ++redraws;
    return true;
  }

 private:
  const Soup& soup_;
  const OccluderCounter& counter_;
  Box box_;
  std::uint32_t max_redraws_;
};

struct Tally {
  std::uint64_t redrawn = 0;
  std::uint64_t skipped = 0;
};

// `count` random samples of `kind`, drawn in parallel blocks with one stream each.
std::vector<Sample> draw_random(const Sampler& sampler, SampleKind kind, std::uint64_t count, std::uint64_t seed,
                                Tally& tally) {
  const std::uint64_t stream = kind == SampleKind::near_triangle ? kNearTriangleStream : kInBoxStream;
  const std::size_t blocks = static_cast<std::size_t>((count + kBlock - 1) / kBlock);
  std::vector<std::optional<Sample>> drawn(static_cast<std::size_t>(count));
  std::vector<std::uint32_t> redraws(drawn.size(), 0);  // also of the samples that ran out
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b < r.end(); ++b) {
      std::mt19937_64 rng = detail::sample_stream(seed, stream, b);
      for (std::size_t i = b * kBlock; i < std::min<std::size_t>(drawn.size(), (b + 1) * kBlock); ++i)
        drawn[i] = sampler.draw(kind, rng, redraws[i]);
    }
  });
  std::vector<Sample> samples;
  samples.reserve(drawn.size());
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    tally.redrawn += redraws[i];
    if (drawn[i])
      samples.push_back(*drawn[i]);
    else
      ++tally.skipped;
  }
  return samples;
}

// Every sample with a defined count: random ones, then the user's (a user point on a
// boundary is skipped, never moved).
std::vector<Sample> draw_samples(const Soup& soup, const OccluderCounter& counter, const Sampler& sampler,
                                 const CountSampling& sampling, Tally& tally) {
  std::vector<Sample> samples = draw_random(sampler, SampleKind::in_box, sampling.in_box, sampling.seed, tally);
  if (soup.triangles.empty()) {
    tally.skipped += sampling.on_triangles;  // nothing to sample near
  } else {
    std::vector<Sample> near =
        draw_random(sampler, SampleKind::near_triangle, sampling.on_triangles, sampling.seed, tally);
    samples.insert(samples.end(), near.begin(), near.end());
  }
  for (const Vec3& p : sampling.user_points) {
    if (const std::optional<std::uint32_t> n = counter.count(p))
      samples.push_back({p, *n, SampleKind::user, 0});
    else
      ++tally.skipped;
  }
  return samples;
}

// One comparison of docs/definitions.md#count-certificate: the segment reference -> sample.
struct Check {
  Sample reference;
  Sample sample;
  std::size_t stream = 0;  // for re-draws
};

class Comparison {
 public:
  Comparison(const detail::ChainCrossingIndex& index, const Sampler& sampler, std::uint64_t seed,
             CountCertificate& out, Tally& tally)
      : index_(index), sampler_(sampler), seed_(seed), out_(out), tally_(tally) {}

  // Runs the checks; those whose segment touched a face are re-drawn and run again, in
  // rounds, while their budgets last.
  void run(std::vector<Check> checks) {
    while (!checks.empty()) {
      std::vector<Check> degenerate = compare(checks);
      checks.clear();
      for (Check& c : degenerate)
        if (redraw(c)) checks.push_back(c);
    }
  }

 private:
  // Compares every check whose crossings are defined; returns the others.
  std::vector<Check> compare(const std::vector<Check>& checks) {
    std::vector<std::optional<std::int64_t>> crossed(checks.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, checks.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t k = r.begin(); k < r.end(); ++k)
                          crossed[k] = index_.crossings(checks[k].reference.point, checks[k].sample.point);
                      });
    std::vector<Check> degenerate;
    for (std::size_t k = 0; k < checks.size(); ++k) {
      if (!crossed[k]) {
        degenerate.push_back(checks[k]);
        continue;
      }
      record(checks[k], *crossed[k]);
    }
    return degenerate;
  }

  void record(const Check& c, std::int64_t crossed) {
    ++out_.checks;
    const std::int64_t expected = std::int64_t{c.sample.count} - std::int64_t{c.reference.count};
    if (crossed == expected) return;
    ++out_.failures;
    if (out_.first_failures.size() < kReportedFailures)
      out_.first_failures.push_back({c.sample.point, expected, crossed});
  }

  // A random sample is re-drawn where it was drawn (in the box, near a triangle); a user
  // point keeps its place and gets a new random reference instead. False: budget spent.
  bool redraw(Check& c) {
    std::uint32_t& redraws = c.sample.redraws;  // one budget per check, whichever end moves
    if (!sampler_.spend(redraws)) {
      ++tally_.skipped;
      return false;
    }
    ++tally_.redrawn;
    std::mt19937_64 rng = detail::sample_stream(seed_, kRedrawStream, (std::uint64_t{c.stream} << 16) + redraws);
    const std::uint32_t before = redraws;
    const bool user = c.sample.kind == SampleKind::user;
    const std::optional<Sample> fresh = sampler_.draw(user ? SampleKind::in_box : c.sample.kind, rng, redraws);
    tally_.redrawn += redraws - before;
    if (!fresh) {
      ++tally_.skipped;
      return false;
    }
    if (user)
      c.reference = *fresh;
    else
      c.sample = *fresh;  // carries the budget used so far
    return true;
  }

  const detail::ChainCrossingIndex& index_;
  const Sampler& sampler_;
  std::uint64_t seed_;
  CountCertificate& out_;
  Tally& tally_;
};

// Morton order, each sample checked against its predecessor (the first against its
// successor): short segments, few candidate faces. A lone sample gets a random reference.
std::vector<Check> consecutive_checks(std::vector<Sample> samples, const Sampler& sampler, std::uint64_t seed,
                                      Tally& tally) {
  std::vector<Vec3> points(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) points[i] = samples[i].point;
  const std::vector<std::uint32_t> order = detail::morton_order(points, sampler.box());
  std::vector<Check> checks;
  checks.reserve(samples.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t reference = k > 0 ? order[k - 1] : (order.size() > 1 ? order[1] : order[0]);
    checks.push_back({samples[reference], samples[order[k]], k});
  }
  if (checks.size() == 1) {
    std::mt19937_64 rng = detail::sample_stream(seed, kReferenceStream, 0);
    std::uint32_t redraws = 0;
    const std::optional<Sample> reference = sampler.draw(SampleKind::in_box, rng, redraws);
    tally.redrawn += redraws;
    if (reference) {
      checks[0].reference = *reference;
    } else {
      ++tally.skipped;
      checks.clear();
    }
  }
  return checks;
}

void require_matching(const Soup& canonical, const Light& light, const ShadowVolumeChain& chain) {
  if (chain.finite_vertices != canonical.vertices.size() || chain.directional != light.directional())
    throw std::invalid_argument("certify_counts: the chain was not assembled on this soup and light");
}

// Every point a check can use lies in here: random ones by construction, the user's added.
Box clip_box(const Box& sampling_box, const std::vector<Vec3>& user_points) {
  std::vector<Vec3> corners = user_points;
  corners.push_back(sampling_box.lo);
  corners.push_back(sampling_box.hi);
  return bounding_box(corners);
}

// Side faces are cut in pieces about as long as the typical segment between two consecutive
// samples: the side of the box's volume shared by the samples.
double piece_length(const Box& box, std::uint64_t samples) {
  const double volume = (box.hi[0] - box.lo[0]) * (box.hi[1] - box.lo[1]) * (box.hi[2] - box.lo[2]);
  const double length = portable::cbrt(volume / static_cast<double>(std::max<std::uint64_t>(samples, 1)));
  if (length > 0.0 && std::isfinite(length)) return length;
  return std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2], 1.0});
}

void require_finite(const std::vector<Vec3>& points) {
  for (const Vec3& p : points)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw std::invalid_argument("certify_counts: a user point has a non-finite coordinate");
}

}  // namespace

std::optional<std::int64_t> chain_crossings(const Soup& canonical, const Light& light, const ShadowVolumeChain& chain,
                                            const Vec3& from, const Vec3& to) {
  require_matching(canonical, light, chain);
  require_finite({from, to});
  return detail::chain_crossings_of_segment({canonical, light, chain}, from, to);
}

CountCertificate certify_counts(const Soup& canonical, const Light& light, const ShadowVolumeChain& chain,
                                const CountSampling& sampling) {
  const auto start = std::chrono::steady_clock::now();
  require_matching(canonical, light, chain);
  require_finite(sampling.user_points);
  const Box box = detail::sampling_box(canonical);
  const detail::CrossingQuery query{canonical, light, chain};
  // The two trees are independent: build them side by side.
  std::unique_ptr<OccluderCounter> counter;
  std::unique_ptr<detail::ChainCrossingIndex> index;
  const std::uint64_t requested = sampling.in_box + sampling.on_triangles + sampling.user_points.size();
  tbb::parallel_invoke([&] { counter = std::make_unique<OccluderCounter>(canonical, light); },
                       [&] {
                         index = std::make_unique<detail::ChainCrossingIndex>(
                             query, clip_box(box, sampling.user_points), piece_length(box, requested));
                       });
  const Sampler sampler(canonical, *counter, box, sampling);
  CountCertificate certificate;
  Tally tally;
  std::vector<Sample> samples = draw_samples(canonical, *counter, sampler, sampling, tally);
  if (!samples.empty()) {
    std::vector<Check> checks = consecutive_checks(std::move(samples), sampler, sampling.seed, tally);
    Comparison(*index, sampler, sampling.seed, certificate, tally).run(std::move(checks));
  }
  certificate.redrawn = tally.redrawn;
  certificate.skipped = tally.skipped;
  certificate.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return certificate;
}

}  // namespace shadowcert
