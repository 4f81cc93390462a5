#include "pipeline/method_certificate.h"

#include <algorithm>
#include <chrono>
#include <utility>

namespace shadowcert {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// How many unbalanced edges the JSON lists with their end points.
constexpr std::size_t kListedUnbalanced = 16;

}  // namespace

MethodCertificate certify_method(MultiplicityMethod method, Precision precision, const Soup& soup,
                                 const EdgeTable& table, const Light& light, const CountSampling& sampling,
                                 ShadowVolumeChain* chain_out) {
  MethodCertificate c;
  c.name = std::string(method_name(method));
  auto start = Clock::now();
  const EdgeMultiplicities m = edge_multiplicities(method, soup, table, light, precision);
  c.multiplicity_seconds = seconds_since(start);
  for (std::int32_t value : m.multiplicity) {
    if (value == 0) continue;
    const std::int32_t magnitude = value < 0 ? -value : value;
    ++c.silhouette_edges;
    ++c.histogram[magnitude];
    c.max_multiplicity = std::max(c.max_multiplicity, magnitude);
  }
  for (Sign s : m.triangle_sign)
    if (s == Sign::zero) ++c.zero_facing_triangles;
  start = Clock::now();
  ShadowVolumeChain chain = assemble_chain(soup, table, m, light);
  c.chain_seconds = seconds_since(start);
  start = Clock::now();
  c.closure = certify_closure(chain);
  c.closure_seconds = seconds_since(start);
  c.counts = certify_counts(soup, light, chain, sampling);
  if (chain_out != nullptr) *chain_out = std::move(chain);
  return c;
}

nlohmann::json method_certificate_json(const MethodCertificate& c) {
  nlohmann::json histogram = nlohmann::json::object();
  for (const auto& [magnitude, edges] : c.histogram) histogram[std::to_string(magnitude)] = edges;
  nlohmann::json failures = nlohmann::json::array();
  for (const CountFailure& f : c.counts.first_failures)
    failures.push_back({{"point", f.point}, {"expected", f.expected}, {"crossed", f.crossed}});
  nlohmann::json unbalanced = nlohmann::json::array();
  for (std::size_t i = 0; i < c.closure.unbalanced.size() && i < kListedUnbalanced; ++i) {
    const UnbalancedEdge& e = c.closure.unbalanced[i];
    unbalanced.push_back({{"from", e.from}, {"to", e.to}, {"excess", e.excess}});
  }
  return {{"closed", c.closure.closed},
          {"unbalanced_edges", c.closure.unbalanced.size()},
          {"first_unbalanced", unbalanced},
          {"count_checks", c.counts.checks},
          {"count_failures", c.counts.failures},
          {"count_redrawn", c.counts.redrawn},
          {"count_skipped", c.counts.skipped},
          {"first_count_failures", failures},
          {"silhouette_edges", c.silhouette_edges},
          {"max_multiplicity", c.max_multiplicity},
          {"multiplicity_histogram", histogram},
          {"zero_facing_triangles", c.zero_facing_triangles},
          {"seconds", c.seconds()},
          {"stage_seconds",
           {{"multiplicities", c.multiplicity_seconds},
            {"chain", c.chain_seconds},
            {"closure", c.closure_seconds},
            {"counts", c.counts.seconds}}}};
}

}  // namespace shadowcert
