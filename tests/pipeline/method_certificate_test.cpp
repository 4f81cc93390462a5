// pipeline/method_certificate.h: one method's certificates and the JSON object certify and the
// Python module write for it.
#include "pipeline/method_certificate.h"

#include <gtest/gtest.h>

#include "scene/canonical_soup.h"
#include "scene/edge_table.h"

namespace shadowcert {
namespace {

// A closed tetrahedron and a light above it: its silhouette is the lit face's three edges, each
// of multiplicity 2 (one lit and one unlit face on it, docs/definitions.md), and every count checks.
Soup tetrahedron() {
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return s;
}

TEST(MethodCertificate, ClosedTetrahedron_EveryMethodCertifiesItAndTheJsonSaysSo) {
  const CanonicalSoup canonical = canonical_soup(tetrahedron());
  const EdgeTable table = build_edge_table(canonical.soup);
  const Light light{{0.2, 0.2, 5.0, 1.0}};
  CountSampling sampling;
  sampling.in_box = 200;
  sampling.on_triangles = 200;
  for (const MultiplicityMethod method : {MultiplicityMethod::exact, MultiplicityMethod::kim,
                                          MultiplicityMethod::peciva, MultiplicityMethod::refedge}) {
    SCOPED_TRACE(std::string(method_name(method)));
    ShadowVolumeChain chain;
    const MethodCertificate c =
        certify_method(method, Precision::float64, canonical.soup, table, light, sampling, &chain);
    EXPECT_EQ(c.name, method_name(method));
    EXPECT_TRUE(c.passed());
    EXPECT_TRUE(c.closure.closed);
    EXPECT_EQ(c.counts.failures, 0u);
    EXPECT_GT(c.counts.checks, 0u);
    // The light sees the face (1, 2, 3) alone: its three edges are the silhouette.
    EXPECT_EQ(c.silhouette_edges, 3u);
    EXPECT_EQ(c.max_multiplicity, 2);
    EXPECT_EQ(c.histogram, (std::map<std::int32_t, std::uint64_t>{{2, 3}}));
    EXPECT_EQ(c.zero_facing_triangles, 0u);
    EXPECT_EQ(chain.side_edges.size(), 3u);  // the chain handed out: one side per silhouette edge

    const nlohmann::json j = method_certificate_json(c);
    EXPECT_EQ(j.at("closed"), true);
    EXPECT_EQ(j.at("unbalanced_edges"), 0);
    EXPECT_EQ(j.at("count_checks"), c.counts.checks);
    EXPECT_EQ(j.at("count_failures"), 0);
    EXPECT_EQ(j.at("silhouette_edges"), 3);
    EXPECT_EQ(j.at("multiplicity_histogram"), (nlohmann::json{{"2", 3}}));
    EXPECT_DOUBLE_EQ(j.at("seconds").get<double>(), c.seconds());
  }
}

TEST(MethodCertificate, OpenSoup_ItsExactChainStillClosesAndCounts) {
  Soup open = tetrahedron();
  open.triangles.pop_back();  // the lit face gone: its edges bound one side only
  const CanonicalSoup canonical = canonical_soup(open);
  const EdgeTable table = build_edge_table(canonical.soup);
  const MethodCertificate c = certify_method(MultiplicityMethod::exact, Precision::float64, canonical.soup, table,
                                             Light{{0.2, 0.2, 5.0, 1.0}}, CountSampling{});
  // The exact chain of any soup is closed (Kim 2008's multiplicities); the counts hold too.
  EXPECT_TRUE(c.passed());
  const nlohmann::json j = method_certificate_json(c);
  EXPECT_EQ(j.at("first_unbalanced").size(), 0u);
  EXPECT_EQ(j.at("first_count_failures").size(), 0u);
}

}  // namespace
}  // namespace shadowcert
