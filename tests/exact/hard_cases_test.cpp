// The hard cases of docs/definitions.md#hard-cases, one test each, through the exact module's certificates:
// for exact and for the float methods that are consistent per triangle (refedge and peciva,
// float and double) the chain is closed; exact counts are right at every sample; a float
// method's chain winds exactly as its own signs claim (test_support::expect_certified).
// Then the invariances of the certificate: vertex relabelling, face reversal and an exact
// translation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "support/certificate_test_support.h"
#include "support/hard_case_scenes.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;
using namespace shadowcert::test_support;

void expect_all_certified(const Soup& soup, const Light& light, std::uint64_t seed) {
  for (const MethodRun& run : consistent_runs()) expect_certified(soup, light, run, seed);
}

TEST(HardCases, LightExactlyOnTrianglePlanes_FloorAtGrazing) {
  const Soup soup = cube_on_floor();
  const Light light = point_light(5.0, 0.0, 0.75);  // in the floor's plane
  expect_all_certified(soup, light, 101);
  const Pipeline p = build_pipeline(soup, light);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(p.multiplicities.triangle_sign[i], Sign::zero);  // the floor
}

TEST(HardCases, LightOneUlpOffTrianglePlanes_FloorAtGrazing) {
  const Soup soup = translated(cube_on_floor(), {0.0, 1.0, 0.0});  // floor at y = 1: ulps are 2^-52 and 2^-53
  for (const double y : {std::nextafter(1.0, 2.0), std::nextafter(1.0, 0.0)}) {
    const Light light = point_light(5.0, y, 0.75);
    expect_all_certified(soup, light, 102);
    const Pipeline p = build_pipeline(soup, light);
    EXPECT_NE(p.multiplicities.triangle_sign[0], Sign::zero);  // exact sees the ulp
  }
}

TEST(HardCases, LightOnAnEdgeLine) {
  // The line of the cube's edge (0,0,0)-(1,0,0), beyond it: the light is in both faces' planes.
  expect_all_certified(unit_cube(), point_light(3.0, 0.0, 0.0), 103);
  expect_all_certified(uv_sphere({0, 0, 0}, 1.0, 12, 6), point_light(0.0, 5.0, 0.0), 104);  // the poles' axis
}

TEST(HardCases, LightAtAVertex) {
  expect_all_certified(unit_cube(), point_light(1.0, 1.0, 1.0), 105);
  Soup s = unit_cube();
  append(s, box({2.0, 0.0, 0.0}, {3.0, 1.0, 1.0}));
  expect_all_certified(s, point_light(2.0, 1.0, 0.0), 106);
}

TEST(HardCases, GrazingSliverAndZeroAreaTriangles) {
  const Soup s = slivers();
  expect_all_certified(s, point_light(0.7, 5.0, 1e-9), 107);
  expect_all_certified(s, point_light(9.0, 1e-12, 0.0), 108);
}

TEST(HardCases, RepeatedIndices) {
  expect_all_certified(repeated_indices(), point_light(0.3, 3.0, 0.4), 109);
}

TEST(HardCases, DuplicateAndFlippedDuplicateTriangles) {
  const Soup s = duplicated_triangles();
  expect_all_certified(s, point_light(0.3, 3.0, 0.4), 110);
  expect_all_certified(s, directional_light(0.2, 1.0, -0.3), 111);
}

TEST(HardCases, CoplanarOverlaps) {
  expect_all_certified(coplanar_overlaps(), point_light(0.2, 4.0, 0.3), 112);
}

TEST(HardCases, FansUpTo256TrianglesOnOneEdge) {
  for (std::uint32_t k : {1u, 2u, 33u, 256u}) {
    const Light light = point_light(-3.0, 0.5, 0.0);
    expect_all_certified(half_fan(k), light, 113 + k);
    const Pipeline p = build_pipeline(half_fan(k), light);
    std::int32_t largest = 0;
    for (std::int32_t m : p.chain.side_multiplicity) largest = std::max(largest, std::abs(m));
    EXPECT_EQ(largest, static_cast<std::int32_t>(k)) << "k = " << k;
  }
  expect_all_certified(nonmanifold_fan(256), point_light(0.3, 0.45, 2.0), 114);
}

TEST(HardCases, CoordinatesOffsetBy1e6With1e3Features) {
  const Vec3& offset = kFarOffset;
  const Soup s = offset_1e6_features();
  expect_all_certified(s, point_light(offset[0] + 1e-3, offset[1] + 5e-3, offset[2] + 2e-4), 115);
  expect_all_certified(s, directional_light(0.1, 1.0, 0.2), 116);
}

TEST(HardCases, ScalesFrom1eMinus6To1e6) {
  for (const double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
    expect_all_certified(cube_and_sphere_scaled(scale), point_light(1.1 * scale, 4.0 * scale, 0.3 * scale), 117);
  }
}

TEST(HardCases, TJunctionsAndCracks) {
  const Soup s = t_junctions_and_cracks();
  expect_all_certified(s, point_light(1.2, 3.0, 0.4), 118);
  expect_all_certified(s, point_light(1.0, 3.0, 0.5), 119);  // above the T vertex
}

TEST(HardCases, BowTieVertices) {
  const Soup s = bow_ties();
  expect_all_certified(s, point_light(0.2, 3.0, 0.1), 120);
  expect_all_certified(s, point_light(0.0, 0.0, 4.0), 121);  // on the axis through the bow-tie vertex
}

TEST(HardCases, DirectionalLightParallelToFaces) {
  expect_all_certified(unit_cube(), directional_light(1.0, 0.0, 0.0), 122);
  expect_all_certified(unit_cube(), directional_light(1.0, 1.0, 0.0), 123);  // parallel to the z faces
  expect_all_certified(cube_on_floor(), directional_light(0.0, 0.0, -1.0), 124);
}

TEST(HardCases, CameraInsideAShadowVolume_CountsFromInside) {
  // The exact module's side of it: points inside volumes, counted directly and by crossings.
  const Soup soup = cube_on_floor();
  const Light light = point_light(0.1, 4.0, 0.2);
  const Pipeline p = build_pipeline(soup, light);
  CountSampling s = small_sampling(125, 200, 200);
  s.user_points = {{0.0, 0.5, 0.0}, {0.1, -0.5, 0.0}, {0.0, 0.999, 0.0}};  // in the cube; below the floor
  const CountCertificate c = certify_counts(p.canonical, light, p.chain, s);
  EXPECT_EQ(c.failures, 0u);
  const OccluderCounter counter(p.canonical, light);
  EXPECT_EQ(counter.count({0.0, 0.5, 0.0}), std::optional<std::uint32_t>(1));
  EXPECT_EQ(counter.count({0.1, -0.5, 0.0}), std::optional<std::uint32_t>(3));  // cube in and out, floor
}

TEST(HardCases, LightInsideAClosedCaster) {
  expect_all_certified(uv_sphere({0, 0, 0}, 1.0, 16, 8), point_light(0.1, 0.2, -0.05), 126);
  expect_all_certified(unit_cube(), point_light(0.5, 0.5, 0.5), 127);
  const Pipeline p = build_pipeline(unit_cube(), point_light(0.5, 0.5, 0.5));
  const OccluderCounter counter(p.canonical, point_light(0.5, 0.5, 0.5));
  EXPECT_EQ(counter.count({3.0, 0.4, 0.3}), std::optional<std::uint32_t>(1));  // everything outside: once
}

TEST(HardCases, SoupsSnappedToASmallIntegerGrid) {
  const std::uint64_t seed = 128;
  std::cout << "seed " << seed << "\n";
  int round = 0;
  for (const GridSoup& g : integer_grid_soups(seed, 4)) {
    expect_all_certified(g.soup, g.point, seed + round);
    expect_all_certified(g.soup, g.directional, seed + round);
    ++round;
  }
}

// ---- invariances of the certificate ----------------------------------------------------

using Face = std::vector<std::uint32_t>;

std::vector<Face> chain_faces(const ShadowVolumeChain& chain) {
  std::vector<Face> faces;
  auto cycle = [](Face f) {
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    return f;
  };
  for (const auto& t : chain.triangles) faces.push_back(cycle({t[0], t[1], t[2]}));
  for (const auto& q : chain.quads) faces.push_back(cycle({q[0], q[1], q[2], q[3]}));
  std::sort(faces.begin(), faces.end());
  return faces;
}

Soup invariance_scene() {
  Soup s = cube_on_floor();
  append(s, half_fan(40));
  append(s, uv_sphere({2.0, 1.0, 0.0}, 0.5, 10, 5));
  return s;
}

TEST(HardCases, VertexRelabelling_SameChain) {
  const Soup soup = invariance_scene();
  const Light light = point_light(0.3, 3.0, 0.2);
  std::vector<std::uint32_t> relabel(soup.vertices.size());
  std::iota(relabel.begin(), relabel.end(), 0u);
  std::shuffle(relabel.begin(), relabel.end(), std::mt19937_64(129));
  Soup shuffled;
  shuffled.vertices.resize(soup.vertices.size());
  for (std::size_t i = 0; i < relabel.size(); ++i) shuffled.vertices[relabel[i]] = soup.vertices[i];
  for (const Triangle& t : soup.triangles) shuffled.triangles.push_back({relabel[t[0]], relabel[t[1]], relabel[t[2]]});
  for (const MethodRun& run : consistent_runs()) {
    const Pipeline a = build_pipeline(soup, light, run), b = build_pipeline(shuffled, light, run);
    EXPECT_EQ(chain_faces(a.chain), chain_faces(b.chain)) << run_name(run);
    EXPECT_TRUE(certify_closure(b.chain).closed) << run_name(run);
  }
}

TEST(HardCases, FaceReversal_SameChain) {
  const Soup soup = invariance_scene();
  Soup reversed = soup;
  for (Triangle& t : reversed.triangles) std::swap(t[1], t[2]);
  for (const Light& light : {point_light(0.3, 3.0, 0.2), directional_light(0.2, 1.0, 0.1)}) {
    for (const MethodRun& run : consistent_runs()) {
      const Pipeline a = build_pipeline(soup, light, run), b = build_pipeline(reversed, light, run);
      EXPECT_EQ(chain_faces(a.chain), chain_faces(b.chain)) << run_name(run);
    }
    const Pipeline a = build_pipeline(soup, light), b = build_pipeline(reversed, light);
    const CountCertificate ca = certify_counts(a.canonical, light, a.chain, small_sampling(130));
    const CountCertificate cb = certify_counts(b.canonical, light, b.chain, small_sampling(130));
    EXPECT_EQ(ca.checks, cb.checks);
    EXPECT_EQ(ca.redrawn, cb.redrawn);
    EXPECT_EQ(cb.failures, 0u);
  }
}

TEST(HardCases, ExactTranslationBy2To20_SameCertificate) {
  // Coordinates that are multiples of 2^-20 below 2^10 translate exactly by 2^20.
  const std::uint64_t seed = 131;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> fixed(-(1 << 21), 1 << 21);  // in units of 2^-20: [-2, 2]
  Soup s = invariance_scene();
  for (Vec3& v : s.vertices)
    for (double& x : v) x = std::ldexp(std::round(std::ldexp(x, 20)), -20);
  for (int i = 0; i < 30; ++i) {
    const auto base = static_cast<std::uint32_t>(s.vertices.size());
    for (int k = 0; k < 3; ++k)
      s.vertices.push_back({std::ldexp(fixed(rng), -20), std::ldexp(fixed(rng), -20), std::ldexp(fixed(rng), -20)});
    s.triangles.push_back({base, base + 1, base + 2});
  }
  const double shift = std::ldexp(1.0, 20);
  const Soup moved = translated(s, {shift, shift, shift});
  const Light light = point_light(std::ldexp(307.0, -10), 3.0, std::ldexp(-151.0, -10));
  const Light moved_light =
      point_light(light.position[0] + shift, light.position[1] + shift, light.position[2] + shift);
  const Pipeline a = build_pipeline(s, light), b = build_pipeline(moved, moved_light);
  EXPECT_EQ(a.multiplicities.multiplicity, b.multiplicities.multiplicity);
  EXPECT_EQ(a.multiplicities.triangle_sign, b.multiplicities.triangle_sign);
  EXPECT_EQ(chain_faces(a.chain), chain_faces(b.chain));
  EXPECT_TRUE(certify_closure(b.chain).closed);
  const OccluderCounter ca(a.canonical, light), cb(b.canonical, moved_light);
  std::uniform_int_distribution<int> point(-(3 << 20), 3 << 20);
  for (int k = 0; k < 300; ++k) {
    const Vec3 p{std::ldexp(point(rng), -20), std::ldexp(point(rng), -20), std::ldexp(point(rng), -20)};
    EXPECT_EQ(ca.count(p), cb.count({p[0] + shift, p[1] + shift, p[2] + shift})) << "point " << k;
  }
  const CountCertificate c = certify_counts(b.canonical, moved_light, b.chain, small_sampling(seed));
  EXPECT_EQ(c.failures, 0u);
}

}  // namespace
