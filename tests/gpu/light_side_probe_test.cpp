// The GL methods' light-side sign (gpu/shaders/light_side_sign.glsl) on llvmpipe or any EGL
// device, held to exact/ bit for bit (docs/gpu.md "Exact signs"):
//  1. the probe's sign of every float triple equals exact/'s light_orientation of the same
//     floats, for random triples at every scale (subnormals and near-overflow included),
//     coplanar triples (the exact stage must answer 0) and triples one ulp off their plane;
//  2. under SignMode::float32 it is core/light_side_formula.h's float sign;
//  3. cs's multiplicities and cap signs and pertri's signs equal glsign_multiplicities on
//     every hard case and on campaign cases of every family and light placement, and ts,
//     whose control shader defers what its float filter cannot decide to an exact compute
//     pass, draws the same triangles as cs (the deferred path runs on the hard cases).
#include "gpu/light_side_probe.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <random>
#include <vector>

#include "campaign/random_soup.h"
#include "core/light_side_formula.h"
#include "exact/edge_multiplicity.h"
#include "exact/light_orientation.h"
#include "gpu/compute_volume.h"
#include "gpu/per_triangle_volume.h"
#include "gpu/tessellation_volume.h"
#include "support/gl_test_support.h"
#include "support/hard_case_scenes.h"
#include "support/volume_test_support.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;
using namespace test;
using namespace test_support;

class LightSideProbeTest : public GlTest {};

Vec3 widened(const Vec3f& p) { return {p[0], p[1], p[2]}; }

Sign exact_sign(const Vec3f& a, const Vec3f& b, const Vec3f& c, const Vec4f& l) {
  return light_orientation(widened(a), widened(b), widened(c), Light{{l[0], l[1], l[2], l[3]}});
}

struct ProbeTally {
  std::size_t triples = 0;
  std::size_t mismatches = 0;
  std::size_t fallbacks = 0;
};

// Probes `points` (3 per triple) under `light` and counts the signs that differ from exact/'s.
ProbeTally probe_against_exact(const LightSideProbe& probe, const std::vector<Vec3f>& points, const Vec4f& light) {
  const std::vector<LightSideSample> samples = probe.evaluate(points, light);
  ProbeTally tally;
  tally.triples = samples.size();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sign expected = exact_sign(points[3 * i], points[3 * i + 1], points[3 * i + 2], light);
    if (samples[i].sign != to_int(expected)) {
      if (tally.mismatches < 5)
        ADD_FAILURE() << "triple " << i << ": GPU " << samples[i].sign << ", exact " << to_int(expected)
                      << (samples[i].fallback ? " (exact stage)" : " (filter)");
      ++tally.mismatches;
    }
    tally.fallbacks += samples[i].fallback;
  }
  return tally;
}

// A float with a random significand and an exponent uniform in [lo, hi], either sign.
float random_float(std::mt19937_64& rng, int lo, int hi) {
  std::uniform_real_distribution<float> significand(1.0f, 2.0f);
  std::uniform_int_distribution<int> exponent(lo, hi);
  const float x = std::ldexp(significand(rng), exponent(rng));
  return (rng() & 1) != 0 ? -x : x;
}

TEST_F(LightSideProbeTest, RandomTriplesAtEveryScale_SignsEqualExactOrientation) {
  const std::uint64_t seed = 20261201;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  const LightSideProbe probe;
  // Exponent ranges: unit scale, 1e-6 to 1e6, mixed magnitudes (differences lose bits),
  // subnormal and near-overflow coordinates (the filter must step aside for the exact stage).
  const int ranges[][2] = {{-1, 1}, {-20, 20}, {-60, 60}, {-149, -120}, {100, 127}, {-149, 127}};
  for (const auto& range : ranges) {
    for (const float w : {1.0f, 0.0f}) {
      std::vector<Vec3f> points;
      for (int i = 0; i < 3000; ++i)
        points.push_back({random_float(rng, range[0], range[1]), random_float(rng, range[0], range[1]),
                          random_float(rng, range[0], range[1])});
      const Vec4f light{random_float(rng, range[0], range[1]), random_float(rng, range[0], range[1]),
                        random_float(rng, range[0], range[1]), w};
      SCOPED_TRACE("exponents [" + std::to_string(range[0]) + ", " + std::to_string(range[1]) + "], w = " +
                   std::to_string(static_cast<int>(w)));
      const ProbeTally tally = probe_against_exact(probe, points, light);
      std::cout << "exponents [" << range[0] << ", " << range[1] << "], w = " << w << ": " << tally.fallbacks << " of "
                << tally.triples << " triples needed the exact stage\n";
      EXPECT_EQ(tally.mismatches, 0u);
    }
  }
}

TEST_F(LightSideProbeTest, UnitScaleRandomTriples_FilterDecidesAlmostAll) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<Vec3f> points;
  for (int i = 0; i < 30000; ++i) points.push_back({unit(rng), unit(rng), unit(rng)});
  const ProbeTally tally = probe_against_exact(LightSideProbe{}, points, {0.3f, 2.0f, -0.4f, 1.0f});
  EXPECT_EQ(tally.mismatches, 0u);
  // A proven bound wider than needed would send everything to the slow stage.
  EXPECT_LT(tally.fallbacks, tally.triples / 1000);
}

// Triples on small-integer planes with the light on the plane too: D = 0 exactly, which no
// filter can decide, so the exact stage answers, and it must answer 0. One ulp off the plane
// (the light's coordinate moved by nextafter), the exact stage decides the nonzero sign.
TEST_F(LightSideProbeTest, LightOnAndOneUlpOffTheirPlane_ExactStageAnswers) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> small(-40, 40);
  const LightSideProbe probe;
  for (const int scale_exponent : {0, -30, 30, -140}) {
    std::vector<Vec3f> on_plane;
    std::vector<Vec3f> off_plane;
    std::vector<Vec4f> lights;
    // The plane x + 2y + 3z = 6 in integers, then scaled by a power of two (exact).
    auto plane_point = [&] {
      const int x = small(rng), y = small(rng);
      // z = (6 - x - 2y) / 3 exact only for multiples of 3: pick x to make it so.
      const int xx = x + ((6 - x - 2 * y) % 3 + 3) % 3;
      const float s = std::ldexp(1.0f, scale_exponent);
      return Vec3f{static_cast<float>(xx) * s, static_cast<float>(y) * s,
                   static_cast<float>((6 - xx - 2 * y) / 3) * s};
    };
    std::vector<Vec3f> points;
    for (int i = 0; i < 600; ++i) points.push_back(plane_point());
    const Vec3f l = plane_point();
    SCOPED_TRACE("scale 2^" + std::to_string(scale_exponent));
    const std::vector<LightSideSample> on = probe.evaluate(points, {l[0], l[1], l[2], 1.0f});
    std::size_t zero = 0, fallback = 0;
    for (const LightSideSample& s : on) {
      zero += s.sign == 0;
      fallback += s.fallback;
    }
    EXPECT_EQ(zero, on.size());
    EXPECT_EQ(fallback, on.size());
    const Vec4f moved{l[0], l[1], std::nextafter(l[2], 1e30f), 1.0f};
    const ProbeTally tally = probe_against_exact(probe, points, moved);
    EXPECT_EQ(tally.mismatches, 0u);
    // A directional light parallel to the plane: (l - 0) with l on the plane through 0 is not
    // parallel in general, so use a direction in the plane x + 2y + 3z = 0.
    const ProbeTally parallel = probe_against_exact(probe, points, {3.0f, 0.0f, -1.0f, 0.0f});
    EXPECT_EQ(parallel.mismatches, 0u);
  }
}

TEST_F(LightSideProbeTest, FloatMode_SignsEqualTheFloatFormula) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<Vec3f> points;
  for (int i = 0; i < 3000; ++i) points.push_back({unit(rng), unit(rng), unit(rng)});
  const Vec4f light{0.5f, 0.25f, 0.125f, 1.0f};
  const std::vector<LightSideSample> samples = LightSideProbe(SignMode::float32).evaluate(points, light);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sign expected = light_side_sign<float>(points[3 * i], points[3 * i + 1], points[3 * i + 2], light);
    ASSERT_EQ(samples[i].sign, to_int(expected)) << "triple " << i;
    ASSERT_FALSE(samples[i].fallback);
  }
}

// The triangles as a 2-chain: each oriented triangle, rotated to start at its least vertex,
// counted +1, and -1 for the opposite orientation. ts appends deferred quads after the captured
// ones: only the chain is cs's. (Where an edge has more opposites than a record holds, ts's
// partial quads of both orientations are triangulated along other diagonals: the chains then
// differ as triangles while both are closed.)
std::map<VolumeTriangle, int> chain_of(const std::vector<VolumeTriangle>& triangles) {
  std::map<VolumeTriangle, int> chain;
  for (VolumeTriangle t : triangles) {
    int sign = 1;
    if (t[2] < t[1]) {  // odd permutation: (a, c, b) is -(a, b, c)
      std::swap(t[1], t[2]);
      sign = -1;
    }
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    if (t[2] < t[1]) {
      std::swap(t[1], t[2]);
      sign = -sign;
    }
    chain[t] += sign;
  }
  std::erase_if(chain, [](const auto& entry) { return entry.second == 0; });
  return chain;
}

// Returns how many edge records ts deferred to its exact pass.
std::uint32_t expect_gpu_signs_equal_glsign(const Soup& soup, const Light& light) {
  const Prepared p = prepare(soup);
  const ComputeVolumeSoup gpu_soup(p.canonical.soup, p.table);
  const EdgeMultiplicities cpu = glsign_multiplicities(p.canonical.soup, p.table, light);
  ComputeShadowVolume cs(gpu_soup);
  cs.build(light);
  EXPECT_EQ(cs.read_multiplicities(), cpu.multiplicity);
  EXPECT_EQ(cs.read_triangle_signs(), triangle_signs(cpu));
  PerTriangleShadowVolume pertri(gpu_soup);
  pertri.build(light);
  EXPECT_EQ(pertri.read_triangle_signs(), triangle_signs(cpu));
  TessellationShadowVolume ts(gpu_soup, p.table);
  ts.build(light);
  bool split_records = false;
  for (std::size_t e = 0; e < p.table.size(); ++e)
    split_records |= p.table.first_opposite[e + 1] - p.table.first_opposite[e] > kTessellationOppositesPerRecord;
  const std::vector<VolumeTriangle> ts_triangles = ts.read_triangles();
  if (split_records)
    EXPECT_TRUE(unbalanced_edges(ts_triangles).empty());
  else
    EXPECT_EQ(chain_of(ts_triangles), chain_of(cs.read_triangles()));
  return ts.read_deferred_records();
}

TEST_F(LightSideProbeTest, HardCases_GpuSignsEqualGlsign) {
  std::uint32_t deferred = 0;
  for (const HardCaseScene& scene : hard_case_scenes()) {
    SCOPED_TRACE(scene.name);
    deferred += expect_gpu_signs_equal_glsign(scene.soup, scene.light);
  }
  EXPECT_GT(deferred, 0u);  // lights on planes and lines: ts's exact pass ran
}

// A 40 x 40 integer grid in the plane x + y + z = 0 lit from one float ulp (2^-18) off it:
// every triangle's sign is nonzero exactly, but the float filter decides none (its bound is
// about 2^-21 x 40), so ts defers every edge record of a draw of
// about 8,000 patches to its exact pass, which must find the right records (named by
// gl_PrimitiveID, they were another batch's on llvmpipe: tests/regressions/gl/
// ts_deferred_record_index.json).
TEST_F(LightSideProbeTest, LargeDrawWithEveryRecordDeferred_TsChainEqualsCs) {
  constexpr std::uint32_t kSide = 40;
  Soup grid;
  for (std::uint32_t z = 0; z <= kSide; ++z)
    for (std::uint32_t x = 0; x <= kSide; ++x) grid.vertices.push_back({double(x), -double(x + z), double(z)});
  const auto at = [&](std::uint32_t x, std::uint32_t z) { return z * (kSide + 1) + x; };
  for (std::uint32_t z = 0; z < kSide; ++z)
    for (std::uint32_t x = 0; x < kSide; ++x) {
      grid.triangles.push_back({at(x, z), at(x, z + 1), at(x + 1, z)});
      grid.triangles.push_back({at(x + 1, z), at(x, z + 1), at(x + 1, z + 1)});
    }
  const Light light{{20.5, -40.75 + std::ldexp(1.0, -18), 20.25, 1.0}};
  const std::uint32_t deferred = expect_gpu_signs_equal_glsign(grid, light);
  EXPECT_GT(deferred, 4000u);
}

TEST_F(LightSideProbeTest, CampaignCasesOfEveryPlacement_GpuSignsEqualGlsign) {
  const std::uint64_t seed = 4242;
  std::cout << "campaign seed " << seed << "\n";
  for (std::size_t family = 0; family < kSoupFamilies; ++family) {
    for (std::size_t placement = 0; placement < kLightPlacements; ++placement) {
      for (std::uint64_t index = 0; index < 3; ++index) {
        CampaignCaseKind kind = draw_case_kind(seed, index);
        kind.family = static_cast<SoupFamily>(family);
        kind.light = static_cast<LightPlacement>(placement);
        const CampaignCase c = make_campaign_case(seed, 100 * family + 10 * placement + index, 60, kind);
        SCOPED_TRACE(std::string(family_name(kind.family)) + " / " + std::string(placement_name(c.kind.light)) +
                     " case " + std::to_string(index));
        expect_gpu_signs_equal_glsign(c.soup, c.light);
      }
    }
  }
}

}  // namespace
}  // namespace shadowcert::gpu
