// The exact pipeline (canonical soup, edge table, multiplicities, chain, closure) runs in
// parallel (docs/certificates.md, "Measured figures"): its answers must not depend on the
// number of threads. Each soup here is large enough (over 65,536 triangles and vertices) that
// every parallel loop is cut into several chunks, and is run once under a TBB limit of one
// thread and once under two; every output must be equal, field by field. The soups: uniform
// random triangles, an unwelded soup on the integer grid {-2..2}^3 (125 distinct points shared
// by 600k input vertices: long runs of equal x in the weld, fans of thousands of triangles on
// one edge), a sphere grid, and the hard cases of docs/definitions.md#hard-cases tiled many
// times. Then, at that size, the invariances: vertex relabelling, face reversal and an exact
// translation.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "exact/closure_certificate.h"
#include "exact/edge_multiplicity.h"
#include "exact/shadow_volume_chain.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/hard_soups.h"
#include "scene/procedural_mesh.h"
#include "support/hard_case_scenes.h"

namespace {

using namespace shadowcert;
using namespace shadowcert::test_support;

struct Outputs {
  CanonicalSoup canonical;
  EdgeTable table;
  std::vector<EdgeMultiplicities> multiplicities;  // exact, then each float method and precision
  std::vector<Sign> exact_entries;
  ShadowVolumeChain exact_chain, kim_chain;
  ClosureCertificate exact_closure, kim_closure;
};

// all_methods false: exact and kim in float only (the tiled hard cases, many soups).
Outputs run_pipeline(const Soup& soup, const Light& light, std::size_t threads, bool all_methods = true) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  Outputs out;
  out.canonical = canonical_soup(soup);
  const Soup& c = out.canonical.soup;
  out.table = build_edge_table(c);
  out.multiplicities.push_back(exact_multiplicities(c, out.table, light));
  for (const MultiplicityMethod method : {MultiplicityMethod::kim, MultiplicityMethod::peciva, MultiplicityMethod::refedge})
    for (const Precision precision : {Precision::float32, Precision::float64})
      if (all_methods || (method == MultiplicityMethod::kim && precision == Precision::float32))
        out.multiplicities.push_back(edge_multiplicities(method, c, out.table, light, precision));
  out.exact_entries = edge_entry_signs(MultiplicityMethod::exact, c, out.table, light, Precision::float64);
  out.exact_chain = assemble_chain(c, out.table, out.multiplicities[0], light);
  // kim in float is not closed on many soups: its unbalanced edges are compared too.
  out.kim_chain = assemble_chain(c, out.table, out.multiplicities[1], light);
  out.exact_closure = certify_closure(out.exact_chain);
  out.kim_closure = certify_closure(out.kim_chain);
  return out;
}

void expect_same_chain(const ShadowVolumeChain& a, const ShadowVolumeChain& b) {
  EXPECT_EQ(a.finite_vertices, b.finite_vertices);
  EXPECT_EQ(a.directional, b.directional);
  EXPECT_TRUE(a.triangles == b.triangles);
  EXPECT_TRUE(a.quads == b.quads);
  EXPECT_TRUE(a.side_edges == b.side_edges);
  EXPECT_TRUE(a.side_multiplicity == b.side_multiplicity);
  EXPECT_TRUE(a.cap_triangles == b.cap_triangles);
  EXPECT_TRUE(a.cap_sign == b.cap_sign);
}

void expect_same_closure(const ClosureCertificate& a, const ClosureCertificate& b) {
  EXPECT_EQ(a.closed, b.closed);
  ASSERT_EQ(a.unbalanced.size(), b.unbalanced.size());
  for (std::size_t i = 0; i < a.unbalanced.size(); ++i) {
    EXPECT_EQ(a.unbalanced[i].from, b.unbalanced[i].from);
    EXPECT_EQ(a.unbalanced[i].to, b.unbalanced[i].to);
    EXPECT_EQ(a.unbalanced[i].excess, b.unbalanced[i].excess);
  }
}

void expect_same_outputs(const Outputs& a, const Outputs& b) {
  EXPECT_TRUE(a.canonical.soup.vertices == b.canonical.soup.vertices);
  EXPECT_TRUE(a.canonical.soup.triangles == b.canonical.soup.triangles);
  EXPECT_TRUE(a.canonical.soup.normals == b.canonical.soup.normals);
  EXPECT_TRUE(a.canonical.canonical_id == b.canonical.canonical_id);
  EXPECT_TRUE(a.table.edges == b.table.edges);
  EXPECT_TRUE(a.table.first_opposite == b.table.first_opposite);
  EXPECT_TRUE(a.table.opposite_vertex == b.table.opposite_vertex);
  EXPECT_TRUE(a.table.opposite_triangle == b.table.opposite_triangle);
  ASSERT_EQ(a.multiplicities.size(), b.multiplicities.size());
  for (std::size_t i = 0; i < a.multiplicities.size(); ++i) {
    SCOPED_TRACE("multiplicities " + std::to_string(i));
    EXPECT_TRUE(a.multiplicities[i].multiplicity == b.multiplicities[i].multiplicity);
    EXPECT_TRUE(a.multiplicities[i].triangle_sign == b.multiplicities[i].triangle_sign);
  }
  EXPECT_TRUE(a.exact_entries == b.exact_entries);
  expect_same_chain(a.exact_chain, b.exact_chain);
  expect_same_chain(a.kim_chain, b.kim_chain);
  expect_same_closure(a.exact_closure, b.exact_closure);
  expect_same_closure(a.kim_closure, b.kim_closure);
}

// Runs on 1 and 2 threads; returns the 1-thread outputs.
Outputs expect_thread_independent(const Soup& soup, const Light& light, bool all_methods = true) {
  Outputs one = run_pipeline(soup, light, 1, all_methods);
  const Outputs two = run_pipeline(soup, light, 2, all_methods);
  expect_same_outputs(one, two);
  EXPECT_TRUE(one.exact_closure.closed);  // exact is closed by construction
  return one;
}

// Every triangle with its own three vertices, as a binary STL stores them.
Soup unwelded_integer_grid(std::uint64_t seed, std::size_t triangles) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> grid(-2, 2);
  Soup s;
  for (std::size_t t = 0; t < triangles; ++t) {
    const auto base = static_cast<std::uint32_t>(s.vertices.size());
    for (int k = 0; k < 3; ++k) s.vertices.push_back({double(grid(rng)), double(grid(rng)), double(grid(rng))});
    s.triangles.push_back({base, base + 1, base + 2});
  }
  return s;
}

// `copies` copies of `soup` side by side along x, `step` apart (exact: integer multiples).
Soup tiled(const Soup& soup, std::size_t copies, double step) {
  Soup out;
  for (std::size_t i = 0; i < copies; ++i) append(out, translated(soup, {step * static_cast<double>(i), 0.0, 0.0}));
  return out;
}

TEST(ExactPipelineThreads, RandomSoup_TwoThreadsEqualOne) {
  const Soup soup = random_soup(7, 150'000, 1.0);
  expect_thread_independent(soup, point_light(0.3, 1.7, -0.2));
  expect_thread_independent(soup, directional_light(0.2, 1.0, -0.4));
}

TEST(ExactPipelineThreads, UnweldedIntegerGrid_TwoThreadsEqualOne) {
  const Soup soup = unwelded_integer_grid(11, 200'000);
  const Outputs one = expect_thread_independent(soup, point_light(1.0, 3.0, 2.0));  // light on grid planes
  EXPECT_EQ(one.canonical.soup.vertices.size(), 125u);
  expect_thread_independent(soup, directional_light(0.0, 1.0, 1.0));
}

TEST(ExactPipelineThreads, SphereGrid_TwoThreadsEqualOne) {
  expect_thread_independent(sphere_grid(200'000), point_light(5.3, 20.0, 3.7));
}

TEST(ExactPipelineThreads, TiledHardCases_TwoThreadsEqualOne) {
  for (const HardCaseScene& scene : hard_case_scenes()) {
    SCOPED_TRACE(scene.name);
    const std::size_t copies = 70'000 / scene.soup.triangles.size() + 1;
    // Step 0: every copy on the first (bitwise duplicates, welded together); step 64: apart.
    for (const double step : {0.0, 64.0})
      expect_thread_independent(tiled(scene.soup, copies, step), scene.light, /*all_methods=*/false);
  }
}

// Relabelling the input vertices changes nothing canonical; reversing every face leaves the
// multiplicities and negates the cap signs; translating soup and light by an exact integer
// amount (the integer grid stays exact) changes nothing but the positions. At a size where
// every stage runs in parallel chunks, on two threads.
TEST(ExactPipelineThreads, Invariances_AtParallelSize) {
  const Soup soup = unwelded_integer_grid(13, 120'000);
  const Light light = point_light(1.0, 3.0, 2.0);
  const Outputs base = run_pipeline(soup, light, 2);

  Soup relabelled;
  std::vector<std::uint32_t> order(soup.vertices.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937_64(17));
  std::vector<std::uint32_t> new_id(order.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) {
    new_id[order[i]] = i;
    relabelled.vertices.push_back(soup.vertices[order[i]]);
  }
  for (const Triangle& t : soup.triangles) relabelled.triangles.push_back({new_id[t[0]], new_id[t[1]], new_id[t[2]]});
  const Outputs r = run_pipeline(relabelled, light, 2);
  EXPECT_TRUE(r.canonical.soup.vertices == base.canonical.soup.vertices);
  EXPECT_TRUE(r.canonical.soup.triangles == base.canonical.soup.triangles);
  EXPECT_TRUE(r.multiplicities[0].multiplicity == base.multiplicities[0].multiplicity);
  expect_same_chain(r.exact_chain, base.exact_chain);

  Soup reversed = soup;
  for (Triangle& t : reversed.triangles) std::swap(t[1], t[2]);
  const Outputs f = run_pipeline(reversed, light, 2);
  EXPECT_TRUE(f.multiplicities[0].multiplicity == base.multiplicities[0].multiplicity);
  ASSERT_EQ(f.multiplicities[0].triangle_sign.size(), base.multiplicities[0].triangle_sign.size());
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    ASSERT_EQ(f.multiplicities[0].triangle_sign[t], -base.multiplicities[0].triangle_sign[t]) << "triangle " << t;
  EXPECT_TRUE(f.exact_closure.closed);

  const Vec3 by{8.0, -4.0, 16.0};
  const Outputs m = run_pipeline(translated(soup, by), point_light(1.0 + by[0], 3.0 + by[1], 2.0 + by[2]), 2);
  EXPECT_TRUE(m.canonical.soup.triangles == base.canonical.soup.triangles);
  EXPECT_TRUE(m.table.edges == base.table.edges);
  EXPECT_TRUE(m.multiplicities[0].multiplicity == base.multiplicities[0].multiplicity);
  EXPECT_TRUE(m.multiplicities[0].triangle_sign == base.multiplicities[0].triangle_sign);
  expect_same_chain(m.exact_chain, base.exact_chain);
}

}  // namespace
