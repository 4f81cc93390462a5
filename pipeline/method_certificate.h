#pragma once
// One multiplicity method's certificates for a soup and a light, as `shadowcert certify` and the
// Python module's certify report them (docs/certificates.md): the exact multiplicities by the
// method, the chain they assemble, its closure certificate and its count certificate, the
// silhouette's figures and each stage's time; and the JSON object both write per method.
//
//   const MethodCertificate c = certify_method(MultiplicityMethod::kim, Precision::float32,
//                                              canonical.soup, table, light, sampling);
//   json["methods"][c.name] = method_certificate_json(c);
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/light.h"
#include "core/soup.h"
#include "exact/closure_certificate.h"
#include "exact/count_certificate.h"
#include "exact/edge_multiplicity.h"
#include "exact/shadow_volume_chain.h"
#include "scene/edge_table.h"

namespace shadowcert {

struct MethodCertificate {
  std::string name;  // method_name(method)
  ClosureCertificate closure;
  CountCertificate counts;
  std::uint64_t silhouette_edges = 0;               // edges with m != 0
  std::int32_t max_multiplicity = 0;                // max |m|
  std::map<std::int32_t, std::uint64_t> histogram;  // |m| -> edges, m != 0
  std::uint64_t zero_facing_triangles = 0;          // s(t) = 0
  double multiplicity_seconds = 0, chain_seconds = 0, closure_seconds = 0;

  [[nodiscard]] double seconds() const {
    return multiplicity_seconds + chain_seconds + closure_seconds + counts.seconds;
  }
  [[nodiscard]] bool passed() const { return closure.closed && counts.failures == 0; }
};

// `soup` canonical (scene/canonical_soup.h) with `table` its edge table; `light` defined.
// Throws what edge_multiplicities, assemble_chain and certify_counts throw. With `chain_out`,
// the assembled chain is moved there (certify --volume-out draws it).
[[nodiscard]] MethodCertificate certify_method(MultiplicityMethod method, Precision precision, const Soup& soup,
                                               const EdgeTable& table, const Light& light,
                                               const CountSampling& sampling, ShadowVolumeChain* chain_out = nullptr);

// The per-method object of `certify --json`: closed, unbalanced_edges, first_unbalanced (the
// first 16), count_checks, count_failures, count_redrawn, count_skipped, first_count_failures,
// silhouette_edges, max_multiplicity, multiplicity_histogram, zero_facing_triangles, seconds and
// stage_seconds.
[[nodiscard]] nlohmann::json method_certificate_json(const MethodCertificate& c);

}  // namespace shadowcert
