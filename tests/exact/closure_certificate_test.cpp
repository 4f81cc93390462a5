// Closure (exact/closure_certificate.h, docs/definitions.md#closure): hand-made open chains with known
// unbalanced edges, closed chains of every per-triangle-consistent method on known and random
// soups, and the pinned near-degenerate soup where kim in float loses closure while refedge in
// float keeps it (found by DISABLED_SearchKimVersusRefedge below).
#include "exact/closure_certificate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <random>
#include <stdexcept>
#include <vector>

#include "support/certificate_test_support.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;
using namespace shadowcert::test_support;

ShadowVolumeChain chain_of(std::uint32_t n, std::vector<std::array<std::uint32_t, 3>> triangles,
                           std::vector<std::array<std::uint32_t, 4>> quads = {}, bool directional = false) {
  ShadowVolumeChain c;
  c.finite_vertices = n;
  c.directional = directional;
  c.triangles = std::move(triangles);
  c.quads = std::move(quads);
  return c;
}

// ---- hand-made chains ----------------------------------------------------------------------

TEST(CertifyClosure, Tetrahedron_Closed) {
  const ClosureCertificate c = certify_closure(chain_of(4, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}));
  EXPECT_TRUE(c.closed);
  EXPECT_TRUE(c.unbalanced.empty());
}

TEST(CertifyClosure, MissingFace_ReportsItsEdgesSortedWithExcess) {
  // The tetrahedron without face (1, 2, 3): its edges 1->2, 2->3, 3->1 are missing, so the rest
  // uses 2->1, 3->2, 1->3 once without partner.
  const ClosureCertificate c = certify_closure(chain_of(4, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}}));
  EXPECT_FALSE(c.closed);
  ASSERT_EQ(c.unbalanced.size(), 3u);
  EXPECT_EQ(c.unbalanced[0].from, 1u);
  EXPECT_EQ(c.unbalanced[0].to, 2u);
  EXPECT_EQ(c.unbalanced[0].excess, -1);  // used 2 -> 1 only
  EXPECT_EQ(c.unbalanced[1].from, 1u);
  EXPECT_EQ(c.unbalanced[1].to, 3u);
  EXPECT_EQ(c.unbalanced[1].excess, 1);  // used 1 -> 3 only
  EXPECT_EQ(c.unbalanced[2].from, 2u);
  EXPECT_EQ(c.unbalanced[2].to, 3u);
  EXPECT_EQ(c.unbalanced[2].excess, -1);
}

TEST(CertifyClosure, DoubledFace_ExcessTwo) {
  const ClosureCertificate c = certify_closure(chain_of(3, {{0, 1, 2}, {0, 1, 2}}));
  ASSERT_EQ(c.unbalanced.size(), 3u);
  EXPECT_EQ(c.unbalanced[0].excess, 2);   // 0 -> 1 twice
  EXPECT_EQ(c.unbalanced[1].excess, -2);  // 2 -> 0 twice: from 0 to 2 is -2
  EXPECT_EQ(c.unbalanced[2].excess, 2);   // 1 -> 2 twice
}

TEST(CertifyClosure, QuadsAndFarIds_CountLikeTriangles) {
  // A point-light chain of one triangle (0, 2, 1) and far ids 3 + x (exact/shadow_volume_chain.h).
  const ShadowVolumeChain closed =
      chain_of(3, {{0, 2, 1}, {3, 4, 5}}, {{2, 0, 3, 5}, {1, 2, 5, 4}, {0, 1, 4, 3}});
  EXPECT_TRUE(certify_closure(closed).closed);
  ShadowVolumeChain open = closed;
  open.quads.pop_back();
  const ClosureCertificate c = certify_closure(open);
  EXPECT_EQ(c.unbalanced.size(), 4u);  // the quad's four edges
}

TEST(CertifyClosure, SelfLoopsOfRepeatedVertices_AreNoEdges) {
  EXPECT_TRUE(certify_closure(chain_of(3, {{0, 1, 1}, {1, 1, 1}})).closed);
}

TEST(CertifyClosure, IdOutOfRange_Throws) {
  EXPECT_THROW((void)certify_closure(chain_of(3, {{0, 1, 6}})), std::invalid_argument);  // ids [0, 6)
  EXPECT_THROW((void)certify_closure(chain_of(3, {{0, 1, 4}}, {}, true)), std::invalid_argument);  // [0, 4)
  EXPECT_NO_THROW((void)certify_closure(chain_of(3, {{0, 1, 3}}, {}, true)));
}

TEST(CertifyClosure, EmptyChain_Closed) { EXPECT_TRUE(certify_closure(chain_of(0, {})).closed); }

// ---- chains of the methods -----------------------------------------------------------------

void expect_closed_for_consistent_methods(const Soup& soup, const Light& light, const std::string& what) {
  for (const MethodRun& run : consistent_runs()) {
    const Pipeline p = build_pipeline(soup, light, run);
    const ClosureCertificate c = certify_closure(p.chain);
    EXPECT_TRUE(c.closed) << what << ", " << run_name(run) << ": " << c.unbalanced.size() << " unbalanced";
  }
}

TEST(CertifyClosure, CubeAndSpherePointAndDirectional_ClosedForConsistentMethods) {
  for (const Light& light : {point_light(3.0, 4.0, 5.0), point_light(0.5, 0.5, 0.5), directional_light(1, 2, 3),
                             directional_light(1, 0, 0)}) {
    expect_closed_for_consistent_methods(unit_cube(), light, "cube");
    expect_closed_for_consistent_methods(uv_sphere({0, 0, 0}, 1.0, 24, 12), light, "sphere");
  }
}

TEST(CertifyClosure, FansOf1To256_ClosedMultiplicityUpToK) {
  for (std::uint32_t k = 1; k <= 256; ++k) {
    const Light light = point_light(0.3, 0.45, 2.0);
    expect_closed_for_consistent_methods(nonmanifold_fan(k), light, "fan " + std::to_string(k));
    const Pipeline p = build_pipeline(nonmanifold_fan(k), light);
    std::int32_t largest = 0;
    for (std::int32_t m : p.chain.side_multiplicity) largest = std::max(largest, std::abs(m));
    EXPECT_LE(largest, static_cast<std::int32_t>(k));
  }
}

TEST(CertifyClosure, OpenBoxWithFinsAndLightInFloorPlane_Closed) {
  expect_closed_for_consistent_methods(open_box_with_fins(), point_light(0.3, 2.0, 0.4), "open box");
  expect_closed_for_consistent_methods(floor_quad(2.0), point_light(5.0, 0.0, 1.0), "floor, light in its plane");
  const Pipeline p = build_pipeline(floor_quad(2.0), point_light(5.0, 0.0, 1.0));
  EXPECT_TRUE(p.chain.triangles.empty() && p.chain.quads.empty());  // it contributes nothing
}

// Property: random soups (any topology), random lights: every per-triangle-consistent method
// closes (exact, refedge and peciva, float and double).
TEST(CertifyClosure, RandomSoups_ConsistentMethodsAlwaysClosed) {
  const std::uint64_t seed = 0x5eed0001;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  for (int round = 0; round < 40; ++round) {
    Soup soup = random_soup(rng(), 200, 1.0);
    // Shared edges: reuse vertices, so edges carry several triangles.
    std::uniform_int_distribution<std::uint32_t> pick(0, 59);
    for (Triangle& t : soup.triangles)
      for (std::uint32_t& i : t) i = pick(rng);
    const Light light = round % 3 == 0 ? directional_light(coordinate(rng), coordinate(rng), coordinate(rng))
                                       : point_light(coordinate(rng), coordinate(rng), coordinate(rng));
    expect_closed_for_consistent_methods(soup, light, "round " + std::to_string(round));
  }
}

// The certificate by definition: every directed use counted in a map, the edges whose uses
// do not balance, sorted by (from, to).
std::vector<UnbalancedEdge> naive_unbalanced(const ShadowVolumeChain& chain) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::int64_t> excess;
  const auto use = [&](std::uint32_t a, std::uint32_t b) {
    if (a == b) return;
    excess[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
  };
  for (const auto& t : chain.triangles)
    for (int k = 0; k < 3; ++k) use(t[k], t[(k + 1) % 3]);
  for (const auto& q : chain.quads)
    for (int k = 0; k < 4; ++k) use(q[k], q[(k + 1) % 4]);
  std::vector<UnbalancedEdge> out;
  for (const auto& [edge, e] : excess)
    if (e != 0) out.push_back({edge.first, edge.second, e});
  return out;
}

// Property: random chains (faces in random order, on few vertices so that edges repeat in both
// directions, near each other in face order and far apart, within one chunk of faces and across
// chunks) report exactly the naive count's unbalanced edges. The closure cancels a use against
// its reverse as it meets them (exact/closure_certificate.cpp): this checks that nothing is lost
// or counted twice on the way.
TEST(CertifyClosure, RandomChains_ReportTheNaiveCount) {
  const std::uint64_t seed = 0x5eed0c10;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  for (const std::size_t faces : {std::size_t{50}, std::size_t{3000}, std::size_t{150000}}) {
    for (int round = 0; round < 4; ++round) {
      const std::uint32_t n = round % 2 == 0 ? 12 : 900;
      std::uniform_int_distribution<std::uint32_t> id(0, 2 * n - 1);
      ShadowVolumeChain chain = chain_of(n, {});
      for (std::size_t f = 0; f < faces; ++f) {
        if (f % 5 == 4) {
          chain.quads.push_back({id(rng), id(rng), id(rng), id(rng)});
          continue;
        }
        std::array<std::uint32_t, 3> t{id(rng), id(rng), id(rng)};
        chain.triangles.push_back(t);
        // Often its reverse soon after (a closed surface's neighbour), sometimes twice.
        if (rng() % 3 == 0) chain.triangles.push_back({t[0], t[2], t[1]});
        if (rng() % 17 == 0) chain.triangles.push_back({t[1], t[0], t[2]});
      }
      const ClosureCertificate c = certify_closure(chain);
      const std::vector<UnbalancedEdge> expected = naive_unbalanced(chain);
      ASSERT_EQ(c.unbalanced.size(), expected.size()) << faces << " faces, round " << round;
      for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(c.unbalanced[i].from, expected[i].from) << i;
        EXPECT_EQ(c.unbalanced[i].to, expected[i].to) << i;
        EXPECT_EQ(c.unbalanced[i].excess, expected[i].excess) << i;
      }
      EXPECT_EQ(c.closed, expected.empty());
    }
  }
}

// A closed surface whose faces come in an order that keeps each edge's two uses far apart (every
// face, then every reversed face: no pair within the cancelling table's reach early on) is still
// closed, and drops one face to be open exactly there.
TEST(CertifyClosure, ReversedCopyFarApart_ClosedAndOpenWhereAFaceIsMissing) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::uint32_t> id(0, 4999);
  ShadowVolumeChain chain = chain_of(5000, {});
  for (int f = 0; f < 100000; ++f) chain.triangles.push_back({id(rng), id(rng), id(rng)});
  for (int f = 0; f < 100000; ++f) {
    const auto t = chain.triangles[static_cast<std::size_t>(f)];
    chain.triangles.push_back({t[0], t[2], t[1]});
  }
  EXPECT_TRUE(certify_closure(chain).closed);
  chain.triangles.pop_back();
  const ClosureCertificate open = certify_closure(chain);
  EXPECT_EQ(open.unbalanced.size(), naive_unbalanced(chain).size());
  EXPECT_FALSE(open.closed);
}

// ---- kim in float versus refedge in float ---------------------------------------------------

// Found by DISABLED_SearchKimVersusRefedge (seed 0x6b696d, attempt 1): two triangles sharing
// an edge, their vertices on a tilted plane through the light up to float rounding, so that
// kim's separately rounded evaluations of one triangle disagree in float.
Soup pinned_near_degenerate_soup() {
  return soup_of({{-0x1.2e5834p+1, 0x1.69abdap+1, -0x1.5f31ap+1},
                  {-0x1.3d9ae6p+0, 0x1.cbdd66p+1, -0x1.12dd5p+1},
                  {-0x1.de841cp+1, 0x1.e98b84p+1, -0x1.01dcbap+2},
                  {-0x1.e9ad6cp+1, 0x1.d2b9e6p+1, -0x1.02aa1p+2}},
                 {{0, 1, 2}, {1, 3, 2}});
}
const Light kPinnedLight{{-0x1.b79118p-2, -0x1.0e081p-1, -0x1.878fbp-2, 1.0}};

TEST(CertifyClosure, PinnedNearDegenerateSoup_KimFloatOpenRefedgeFloatClosed) {
  const Soup soup = pinned_near_degenerate_soup();
  const ClosureCertificate kim =
      certify_closure(build_pipeline(soup, kPinnedLight, {MultiplicityMethod::kim, Precision::float32}).chain);
  const ClosureCertificate refedge =
      certify_closure(build_pipeline(soup, kPinnedLight, {MultiplicityMethod::refedge, Precision::float32}).chain);
  EXPECT_FALSE(kim.closed);
  EXPECT_GT(kim.unbalanced.size(), 0u);
  EXPECT_TRUE(refedge.closed);
  EXPECT_TRUE(certify_closure(build_pipeline(soup, kPinnedLight).chain).closed);  // exact
}

// x rounded to float, through memory: GCC 12.2 at -O2 (SLP vectorizer) was seen to drop the
// round trip (double)(float)x inside a braced initializer of a Light (docs/certificates.md).
double float_value(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}

// Seeded search for the pinned case: two triangles sharing an edge, their vertices on a
// tilted plane through the light up to the rounding of every coordinate to float (so the
// hexfloats are short and the float methods read the soup unrounded). Run with
//   --gtest_also_run_disabled_tests --gtest_filter='*SearchKimVersusRefedge*'
TEST(CertifyClosure, DISABLED_SearchKimVersusRefedge) {
  const std::uint64_t seed = 0x6b696d;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), far(2.0, 6.0);
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Vec3 l{unit(rng), unit(rng), unit(rng)};
    const Vec3 e1{unit(rng), unit(rng), unit(rng)}, e2{unit(rng), unit(rng), unit(rng)};
    auto on_plane = [&](double s, double t) {
      return Vec3{float_value(l[0] + s * e1[0] + t * e2[0]), float_value(l[1] + s * e1[1] + t * e2[1]),
                  float_value(l[2] + s * e1[2] + t * e2[2])};
    };
    Soup soup;
    for (int i = 0; i < 4; ++i) soup.vertices.push_back(on_plane(far(rng), far(rng)));
    soup.triangles = {{0, 1, 2}, {1, 3, 2}};
    const Light light{{float_value(l[0]), float_value(l[1]), float_value(l[2]), 1.0}};
    const bool kim_closed =
        certify_closure(build_pipeline(soup, light, {MultiplicityMethod::kim, Precision::float32}).chain).closed;
    if (kim_closed) continue;
    const bool refedge_closed =
        certify_closure(build_pipeline(soup, light, {MultiplicityMethod::refedge, Precision::float32}).chain).closed;
    if (!refedge_closed) continue;
    std::printf("attempt %d\n", attempt);
    for (const Vec3& v : soup.vertices) std::printf("  {%a, %a, %a},\n", v[0], v[1], v[2]);
    std::printf("light {%a, %a, %a, 1.0}\n", light.position[0], light.position[1], light.position[2]);
    return;
  }
  ADD_FAILURE() << "no case found";
}

}  // namespace
