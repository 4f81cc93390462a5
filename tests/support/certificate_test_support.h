#pragma once
// Shared by the chain and certificate tests: the pipeline soup -> canonical soup -> edge table
// -> multiplicities -> chain (docs/definitions.md#counts, docs/definitions.md#certificates), small soups, and the checks every hard case
// runs. Header-only, test code only.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "exact/closure_certificate.h"
#include "exact/count_certificate.h"
#include "exact/edge_multiplicity.h"
#include "scene/edge_table.h"
#include "exact/light_orientation.h"
#include "exact/shadow_volume_chain.h"
#include "scene/canonical_soup.h"
#include "scene/merged_soup.h"

namespace shadowcert::test_support {

inline Light point_light(double x, double y, double z) { return Light{{x, y, z, 1.0}}; }
inline Light directional_light(double x, double y, double z) { return Light{{x, y, z, 0.0}}; }

inline Soup soup_of(std::vector<Vec3> vertices, std::vector<Triangle> triangles) {
  Soup s;
  s.vertices = std::move(vertices);
  s.triangles = std::move(triangles);
  return s;
}

// Unit cube [0, 1]^3, outward faces: vertex i is (i & 1, (i >> 1) & 1, (i >> 2) & 1).
inline Soup unit_cube() {
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i) v.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  return soup_of(v, {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                     {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}});
}

// Appends `from` to `to` (scene/merged_soup.h); shading normals are dropped (no certificate
// reads them), so every soup built here has none.
inline void append(Soup& to, const Soup& from) {
  append_soup(to, from);
  to.normals.clear();
}

struct MethodRun {
  MultiplicityMethod method = MultiplicityMethod::exact;
  Precision precision = Precision::float64;
};

inline std::string run_name(const MethodRun& r) {
  if (r.method == MultiplicityMethod::exact) return "exact";
  return std::string(method_name(r.method)) + (r.precision == Precision::float32 ? " float" : " double");
}

// Methods that are consistent per triangle (docs/definitions.md#counts): their chains must close.
inline const std::vector<MethodRun>& consistent_runs() {
  static const std::vector<MethodRun> runs{{MultiplicityMethod::exact, Precision::float64},
                                           {MultiplicityMethod::refedge, Precision::float32},
                                           {MultiplicityMethod::refedge, Precision::float64},
                                           {MultiplicityMethod::peciva, Precision::float32},
                                           {MultiplicityMethod::peciva, Precision::float64}};
  return runs;
}

struct Pipeline {
  Soup canonical;
  EdgeTable table;
  EdgeMultiplicities multiplicities;
  ShadowVolumeChain chain;
};

inline Pipeline build_pipeline(const Soup& soup, const Light& light, MethodRun run = {}) {
  Pipeline p;
  p.canonical = canonical_soup(soup).soup;
  p.table = build_edge_table(p.canonical);
  p.multiplicities = edge_multiplicities(run.method, p.canonical, p.table, light, run.precision);
  p.chain = assemble_chain(p.canonical, p.table, p.multiplicities, light);
  return p;
}

// The winding number a per-triangle-consistent chain claims: sum over triangles of
// c(t) [P in V(t)] with c = s_method * s_exact (a reversed sign gives -dV(t); a triangle with
// the light on its plane has a flat V(t), which winds nowhere). For exact, c = 1: n(P).
class ClaimedCount {
 public:
  ClaimedCount(const Pipeline& p, const Light& light)
      : agreeing_(select(p, light, Sign::positive), light), reversed_(select(p, light, Sign::negative), light) {}

  [[nodiscard]] std::optional<std::int64_t> at(const Vec3& x) const {
    const std::optional<std::uint32_t> a = agreeing_.count(x), r = reversed_.count(x);
    if (!a || !r) return std::nullopt;
    return std::int64_t{*a} - std::int64_t{*r};
  }

 private:
  static Soup select(const Pipeline& p, const Light& light, Sign agreement) {
    Soup s;
    s.vertices = p.canonical.vertices;
    for (std::size_t t = 0; t < p.canonical.triangles.size(); ++t) {
      const Triangle& tri = p.canonical.triangles[t];
      const Sign exact = light_orientation(p.canonical.vertices[tri[0]], p.canonical.vertices[tri[1]],
                                           p.canonical.vertices[tri[2]], light);
      if (exact != Sign::zero && p.multiplicities.triangle_sign[t] * exact == agreement) s.triangles.push_back(tri);
    }
    return s;
  }

  OccluderCounter agreeing_;
  OccluderCounter reversed_;
};

// True iff the method's cap signs are the exact ones on every triangle (then its chain is the
// exact chain and certify_counts must find no failure).
inline bool signs_are_exact(const Pipeline& p, const Light& light) {
  for (std::size_t t = 0; t < p.canonical.triangles.size(); ++t) {
    const Triangle& tri = p.canonical.triangles[t];
    const Sign exact = light_orientation(p.canonical.vertices[tri[0]], p.canonical.vertices[tri[1]],
                                         p.canonical.vertices[tri[2]], light);
    if (p.multiplicities.triangle_sign[t] != exact) return false;
  }
  return true;
}

inline CountSampling small_sampling(std::uint64_t seed, std::uint64_t in_box = 300, std::uint64_t near = 300) {
  CountSampling s;
  s.in_box = in_box;
  s.on_triangles = near;
  s.seed = seed;
  return s;
}

// Every check a hard case runs (docs/definitions.md#hard-cases), for one consistent method:
//  - the chain is closed;
//  - certify_counts finds no failure, when the method's signs are the exact ones (always for
//    exact); a float method that rounds a sign differently claims another count there, so
//  - along random segments, the chain's crossings equal the change of its claimed count.
inline void expect_certified(const Soup& soup, const Light& light, const MethodRun& run, std::uint64_t seed,
                             std::uint64_t samples = 300) {
  SCOPED_TRACE(run_name(run) + ", seed " + std::to_string(seed));
  const Pipeline p = build_pipeline(soup, light, run);
  const ClosureCertificate closure = certify_closure(p.chain);
  EXPECT_TRUE(closure.closed) << closure.unbalanced.size() << " unbalanced edges";
  const bool exact_signs = signs_are_exact(p, light);
  if (run.method == MultiplicityMethod::exact) {
    EXPECT_TRUE(exact_signs);
  }
  const CountCertificate counts = certify_counts(p.canonical, light, p.chain, small_sampling(seed, samples, samples));
  EXPECT_GT(counts.checks, 0u);
  if (exact_signs) {
    EXPECT_EQ(counts.failures, 0u);
    for (const CountFailure& f : counts.first_failures)
      ADD_FAILURE() << "at (" << f.point[0] << ", " << f.point[1] << ", " << f.point[2] << "): expected "
                    << f.expected << ", crossed " << f.crossed;
  }
  // The chain against its own claim, on segments between random points near the soup.
  const ClaimedCount claimed(p, light);
  std::mt19937_64 rng(seed);
  Vec3 lo = p.canonical.vertices.front(), hi = lo;
  for (const Vec3& v : p.canonical.vertices)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], v[i]);
      hi[i] = std::max(hi[i], v[i]);
    }
  double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (!(extent > 0.0)) extent = 1.0;
  auto draw = [&] {
    Vec3 x{};
    for (int i = 0; i < 3; ++i)
      x[i] = std::uniform_real_distribution<double>(lo[i] - 0.25 * extent, hi[i] + 0.25 * extent)(rng);
    return x;
  };
  int compared = 0;
  for (int k = 0; k < 60; ++k) {
    const Vec3 a = draw(), b = draw();
    const std::optional<std::int64_t> wa = claimed.at(a), wb = claimed.at(b);
    const std::optional<std::int64_t> crossed = chain_crossings(p.canonical, light, p.chain, a, b);
    if (!wa || !wb || !crossed) continue;
    ++compared;
    EXPECT_EQ(*crossed, *wb - *wa) << "segment " << k;
  }
  EXPECT_GT(compared, 0);
}

}  // namespace shadowcert::test_support
