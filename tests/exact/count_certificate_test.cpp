// Occluder counts (exact/count_certificate.h, docs/definitions.md#counts and #count-certificate): the direct count n(P),
// the crossing tests of caps and side faces against an independent rational computation,
// the sign convention of crossings, and certify_counts on closed and broken chains.
#include "core/vector3.h"
#include "exact/count_certificate.h"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "support/certificate_test_support.h"
#include "exact/closure_certificate.h"
#include "exact/chain_crossings.h"
#include "exact/count_sampling.h"
#include "exact/face_crossing.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;
using namespace shadowcert::test_support;
using detail::FaceMeeting;
using detail::Meeting;

// ---- an independent reference: integer inputs, exact rational arithmetic in __int128 -------

__extension__ typedef __int128 I128;  // exact for these integer ranges (|det| < 2^100)
using IVec = std::array<I128, 3>;

IVec sub(const IVec& a, const IVec& b) { return difference(a, b); }
IVec scaled(const IVec& a, I128 k) { return {a[0] * k, a[1] * k, a[2] * k}; }
IVec added(const IVec& a, const IVec& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
int sgn(I128 x) { return x > 0 ? 1 : (x < 0 ? -1 : 0); }

// Where the segment A -> B meets the plane through `origin` spanned by e1, e2: the
// coordinates (c1, c2) / den of X - origin = c1 e1 + c2 e2, by Cramer's rule on rationals.
struct PlaneHit {
  int start_side = 0, end_side = 0;  // signs of n . (A - origin), n . (B - origin), n = e1 x e2
  I128 c1 = 0, c2 = 0, den = 1;      // den > 0
};

PlaneHit hit_plane(const IVec& a, const IVec& b, const IVec& origin, const IVec& e1, const IVec& e2) {
  const IVec n = cross(e1, e2);
  const I128 da = dot(n, sub(a, origin)), db = dot(n, sub(b, origin));
  PlaneHit h{sgn(da), sgn(db)};
  if (da == db) return h;  // parallel (or the segment in the plane): no single point
  // X - origin = Y / D with D = da - db and Y = (A - origin) D + (B - A) da.
  const I128 d = da - db;
  const IVec y = added(scaled(sub(a, origin), d), scaled(sub(b, a), da));
  const I128 nn = dot(n, n);
  I128 c1 = dot(cross(y, e2), n), c2 = dot(cross(e1, y), n), den = d * nn;
  if (den < 0) {
    c1 = -c1;
    c2 = -c2;
    den = -den;
  }
  h.c1 = c1;
  h.c2 = c2;
  h.den = den;
  return h;
}

// Three-valued like exact/face_crossing.h, from the region's closed and open membership;
// nullopt where the reference itself does not decide (segment in the plane).
std::optional<FaceMeeting> reference_meeting(const PlaneHit& h, bool in_open, bool in_closed) {
  if (h.start_side == h.end_side) {
    if (h.start_side == 0) return std::nullopt;
    return FaceMeeting{Meeting::apart, Sign::zero};
  }
  if (!in_closed) return FaceMeeting{Meeting::apart, Sign::zero};
  if (!in_open || h.start_side == 0 || h.end_side == 0) return FaceMeeting{Meeting::touches, Sign::zero};
  return FaceMeeting{Meeting::crosses, h.start_side > 0 ? Sign::positive : Sign::negative};
}

// Side face of uv: point light {l + t (x - l): x on [u, v], t >= 1} = {l + a (u - l) + b (v - l):
// a, b >= 0, a + b >= 1}; directional {x - t l} = {u + a (v - u) + b (-l): 0 <= a <= 1, b >= 0}.
std::optional<FaceMeeting> reference_side(const IVec& a, const IVec& b, const IVec& l, bool directional,
                                          const IVec& u, const IVec& v) {
  if (!directional) {
    const PlaneHit h = hit_plane(a, b, l, sub(u, l), sub(v, l));
    const bool open = h.c1 > 0 && h.c2 > 0 && h.c1 + h.c2 > h.den;
    const bool closed = h.c1 >= 0 && h.c2 >= 0 && h.c1 + h.c2 >= h.den;
    return reference_meeting(h, open, closed);
  }
  const IVec minus_l = scaled(l, -1);
  const PlaneHit h = hit_plane(a, b, u, sub(v, u), minus_l);
  const bool open = h.c1 > 0 && h.c1 < h.den && h.c2 > 0;
  const bool closed = h.c1 >= 0 && h.c1 <= h.den && h.c2 >= 0;
  // The plane spanned by (v - u, -l) has normal (v - u) x (-l); orient(L, u, v, X) is the
  // sign against (v - u) x l (docs/certificates.md): the opposite orientation.
  PlaneHit flipped = h;
  flipped.start_side = -h.start_side;
  flipped.end_side = -h.end_side;
  return reference_meeting(flipped, open, closed);
}

std::optional<FaceMeeting> reference_triangle(const IVec& a, const IVec& b, const IVec& p, const IVec& q,
                                              const IVec& r) {
  const PlaneHit h = hit_plane(a, b, p, sub(q, p), sub(r, p));
  const bool open = h.c1 > 0 && h.c2 > 0 && h.c1 + h.c2 < h.den;
  const bool closed = h.c1 >= 0 && h.c2 >= 0 && h.c1 + h.c2 <= h.den;
  return reference_meeting(h, open, closed);
}

Vec3 to_vec(const IVec& v) { return {double(v[0]), double(v[1]), double(v[2])}; }

IVec random_ivec(std::mt19937_64& rng, int range) {
  std::uniform_int_distribution<int> c(-range, range);
  return {c(rng), c(rng), c(rng)};
}

bool degenerate_plane(const IVec& e1, const IVec& e2) {
  const IVec n = cross(e1, e2);
  return n[0] == 0 && n[1] == 0 && n[2] == 0;
}

struct Tally {
  int compared = 0, crossings = 0, touches = 0;
};

void expect_same(const FaceMeeting& got, const FaceMeeting& want, Tally& tally, const std::string& what) {
  ++tally.compared;
  tally.crossings += want.meeting == Meeting::crosses;
  tally.touches += want.meeting == Meeting::touches;
  EXPECT_EQ(got.meeting, want.meeting) << what;
  if (want.meeting == Meeting::crosses) {
    EXPECT_EQ(got.start_side, want.start_side) << what;
  }
}

// docs/definitions.md#count-certificate's side-quad formula against the rational reference, random integer inputs:
// a wide range for generic positions, a narrow one for many exact coplanarities and touches.
void check_side_formula(bool directional, std::uint64_t seed) {
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  Tally tally;
  for (int range : {1000, 3}) {
    for (int k = 0; k < 20000; ++k) {
      const IVec l = random_ivec(rng, range), u = random_ivec(rng, range), v = random_ivec(rng, range);
      const IVec a = random_ivec(rng, range), b = random_ivec(rng, range);
      if (directional && l == IVec{0, 0, 0}) continue;
      if (u == v || (directional ? degenerate_plane(sub(v, u), l) : degenerate_plane(sub(u, l), sub(v, l)))) continue;
      const std::optional<FaceMeeting> want = reference_side(a, b, l, directional, u, v);
      if (!want) continue;
      const HomogeneousPoint light{double(l[0]), double(l[1]), double(l[2]), directional ? 0.0 : 1.0};
      const FaceMeeting got = detail::segment_meets_side(to_vec(a), to_vec(b), light, to_vec(u), to_vec(v));
      expect_same(got, *want, tally, "sample " + std::to_string(k) + " range " + std::to_string(range));
      if (::testing::Test::HasFailure()) return;
    }
  }
  std::cout << (directional ? "directional" : "point") << ": " << tally.compared << " compared, " << tally.crossings
            << " crossings, " << tally.touches << " touches\n";
  EXPECT_GT(tally.crossings, 1000);
  EXPECT_GT(tally.touches, 50);
}

TEST(SideFaceCrossing, PointLight_MatchesRationalIntersection) { check_side_formula(false, 20240601); }

TEST(SideFaceCrossing, DirectionalLight_MatchesRationalIntersection) { check_side_formula(true, 20240602); }

TEST(TriangleCrossing, SegmentsAndRays_MatchRationalIntersection) {
  const std::uint64_t seed = 20240603;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  Tally tally;
  for (int range : {1000, 3}) {
    for (int k = 0; k < 20000; ++k) {
      const IVec p = random_ivec(rng, range), q = random_ivec(rng, range), r = random_ivec(rng, range);
      const IVec a = random_ivec(rng, range), b = random_ivec(rng, range);
      if (degenerate_plane(sub(q, p), sub(r, p))) continue;
      const std::optional<FaceMeeting> want = reference_triangle(a, b, p, q, r);
      if (!want) continue;
      const FaceMeeting got =
          detail::segment_meets_triangle(finite_point(to_vec(a)), finite_point(to_vec(b)), to_vec(p), to_vec(q),
                                         to_vec(r));
      expect_same(got, *want, tally, "sample " + std::to_string(k));
      if (HasFailure()) return;
      // The ray from a in direction b - a meets the triangle like a segment to a far point.
      const IVec far = added(a, scaled(sub(b, a), 1 << 20));
      const std::optional<FaceMeeting> ray_want = reference_triangle(a, far, p, q, r);
      const IVec d = sub(b, a);
      if (!ray_want || d == IVec{0, 0, 0}) continue;
      const FaceMeeting ray = detail::segment_meets_triangle(finite_point(to_vec(a)),
                                                             {double(d[0]), double(d[1]), double(d[2]), 0.0},
                                                             to_vec(p), to_vec(q), to_vec(r));
      expect_same(ray, *ray_want, tally, "ray sample " + std::to_string(k));
      if (HasFailure()) return;
    }
  }
  EXPECT_GT(tally.crossings, 1000);
  EXPECT_GT(tally.touches, 50);
}

TEST(TriangleCrossing, ZeroAreaTriangle_MeetsNothing) {
  const FaceMeeting m = detail::segment_meets_triangle(finite_point({0.5, 0, -1}), finite_point({0.5, 0, 1}),
                                                       {0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  EXPECT_EQ(m.meeting, Meeting::apart);
}

// ---- the direct count n(P) --------------------------------------------------------------

TEST(OccluderCounter, PointBehindSphere_CountsTwo) {
  const Soup sphere = uv_sphere({0, 0, 0}, 1.0, 24, 12);
  const OccluderCounter counter(sphere, point_light(0.01, 10.0, 0.02));
  EXPECT_EQ(counter.count({0.003, -3.0, 0.001}), std::optional<std::uint32_t>(2));  // behind: in and out
  EXPECT_EQ(counter.count({0.003, 0.0, 0.001}), std::optional<std::uint32_t>(1));   // inside
  EXPECT_EQ(counter.count({0.003, 3.0, 0.001}), std::optional<std::uint32_t>(0));   // between sphere and light
  EXPECT_EQ(counter.count({5.0, -3.0, 0.0}), std::optional<std::uint32_t>(0));      // beside the shadow
}

TEST(OccluderCounter, DirectionalLight_CountsAlongTheRay) {
  const OccluderCounter counter(unit_cube(), directional_light(0.01, 1.0, 0.02));
  EXPECT_EQ(counter.count({0.5, -7.0, 0.5}), std::optional<std::uint32_t>(2));
  EXPECT_EQ(counter.count({0.5, 0.5, 0.5}), std::optional<std::uint32_t>(1));
  EXPECT_EQ(counter.count({0.5, 1.5, 0.5}), std::optional<std::uint32_t>(0));
}

TEST(OccluderCounter, BoundaryPoints_AreUndefined) {
  const OccluderCounter counter(unit_cube(), point_light(0.5, 5.0, 0.5));
  EXPECT_EQ(counter.count({0.25, 1.0, 0.75}), std::nullopt);  // on the top face
  EXPECT_EQ(counter.count({0.5, -2.0, 0.5}), std::nullopt);   // the segment passes through the diagonal edges
  EXPECT_EQ(counter.count({0.25, -2.0, 0.7}), std::optional<std::uint32_t>(2));
}

TEST(OccluderCounter, LightInItsPlane_TriangleCastsNothing) {
  const Soup floor = floor_quad(1.0);
  const OccluderCounter counter(floor, point_light(3.0, 0.0, 0.0));
  EXPECT_EQ(counter.count({-3.0, 0.0, 0.5}), std::optional<std::uint32_t>(0));
  EXPECT_EQ(counter.count({-3.0, 1e-9, 0.5}), std::optional<std::uint32_t>(0));
}

// ---- crossings: the sign convention n(B) - n(A) ------------------------------------------

TEST(ChainCrossings, SingleTriangle_EnteringCountsPlusOneBothCapSigns) {
  const Light light = point_light(0.2, 0.2, 5.0);
  for (const Triangle& t : {Triangle{0, 1, 2}, Triangle{0, 2, 1}}) {
    const Pipeline p = build_pipeline(soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {t}), light);
    const Vec3 above{0.2, 0.25, 1.0}, below{0.2, 0.25, -1.0}, beside{3.0, 0.25, -1.0};
    EXPECT_EQ(chain_crossings(p.canonical, light, p.chain, above, below), std::optional<std::int64_t>(1));  // cap
    EXPECT_EQ(chain_crossings(p.canonical, light, p.chain, below, above), std::optional<std::int64_t>(-1));
    EXPECT_EQ(chain_crossings(p.canonical, light, p.chain, beside, below), std::optional<std::int64_t>(1));  // side
    EXPECT_EQ(chain_crossings(p.canonical, light, p.chain, below, beside), std::optional<std::int64_t>(-1));
    EXPECT_EQ(chain_crossings(p.canonical, light, p.chain, above, beside), std::optional<std::int64_t>(0));
  }
}

TEST(ChainCrossings, DirectionalSingleTriangle_EnteringCountsPlusOne) {
  const Light light = directional_light(0.1, 0.05, 1.0);
  const Pipeline p = build_pipeline(soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 2, 1}}), light);
  const Vec3 above{0.2, 0.25, 1.0}, below{0.2, 0.25, -1.0}, beside{3.0, 0.25, -1.0};
  EXPECT_EQ(chain_crossings(p.canonical, light, p.chain, above, below), std::optional<std::int64_t>(1));
  EXPECT_EQ(chain_crossings(p.canonical, light, p.chain, beside, below), std::optional<std::int64_t>(1));
  EXPECT_EQ(chain_crossings(p.canonical, light, p.chain, below, beside), std::optional<std::int64_t>(-1));
}

TEST(ChainCrossings, SegmentThroughACapEdge_IsDegenerate) {
  const Light light = point_light(0.2, 0.2, 5.0);
  const Pipeline p = build_pipeline(soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}), light);
  EXPECT_EQ(chain_crossings(p.canonical, light, p.chain, {0.5, 0.0, 1.0}, {0.5, 0.0, -1.0}), std::nullopt);
}

// ---- the accelerated crossings ----------------------------------------------------------

// The index (box tree, side faces cut in interval-bounded pieces) must give exactly what
// testing every face gives, for short and long segments, lights inside and outside the soup.
TEST(ChainCrossingIndex, RandomSegments_SameAsEveryFace) {
  const std::uint64_t seed = 0x1dec5;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5), unit(0.0, 1.0);
  int compared = 0;
  for (int round = 0; round < 12; ++round) {
    Soup soup = random_soup(rng(), 80, 1.0);
    std::uniform_int_distribution<std::uint32_t> pick(0, 39);
    for (Triangle& t : soup.triangles)
      for (std::uint32_t& i : t) i = pick(rng);
    const Light light = round % 3 == 0 ? directional_light(coordinate(rng), coordinate(rng), coordinate(rng))
                                       : point_light(coordinate(rng), coordinate(rng), coordinate(rng));
    const Pipeline p = build_pipeline(soup, light);
    const Box box = detail::sampling_box(p.canonical);
    const detail::CrossingQuery query{p.canonical, light, p.chain};
    for (const double piece : {0.01, 0.2, 5.0}) {
      const detail::ChainCrossingIndex index(query, box, piece);
      for (int k = 0; k < 150; ++k) {
        const Vec3 a = detail::draw_in_box(box, rng);
        Vec3 b = detail::draw_in_box(box, rng);
        const double shrink = k % 2 == 0 ? 0.05 : 1.0;  // short and long segments
        for (int d = 0; d < 3; ++d) b[d] = a[d] + shrink * (b[d] - a[d]);
        const std::optional<std::int64_t> fast = index.crossings(a, b);
        const std::optional<std::int64_t> every = chain_crossings(p.canonical, light, p.chain, a, b);
        ASSERT_EQ(fast, every) << "round " << round << " segment " << k;
        compared += every.has_value() && *every != 0;
      }
    }
  }
  EXPECT_GT(compared, 500);
}

// ---- certify_counts --------------------------------------------------------------------

TEST(CertifyCounts, CubeAndSphereBothLights_NoFailure) {
  Soup scene = unit_cube();
  append(scene, uv_sphere({2.5, 0.5, 0.5}, 0.75, 20, 10));
  for (const Light& light : {point_light(1.3, 4.0, 0.7), directional_light(-0.3, 1.0, 0.2)}) {
    const Pipeline p = build_pipeline(scene, light);
    const CountCertificate c = certify_counts(p.canonical, light, p.chain, small_sampling(7, 2000, 2000));
    EXPECT_EQ(c.failures, 0u);
    EXPECT_GE(c.checks, 3900u);
    EXPECT_LE(c.skipped, 5u);
  }
}

TEST(CertifyCounts, MissingCap_Fails) {
  const Light light = point_light(0.4, 3.0, 0.3);
  Pipeline p = build_pipeline(unit_cube(), light);
  // Drop the first front cap from the crossing lists: the chain is then open.
  p.chain.cap_triangles.erase(p.chain.cap_triangles.begin());
  p.chain.cap_sign.erase(p.chain.cap_sign.begin());
  const CountCertificate c = certify_counts(p.canonical, light, p.chain, small_sampling(3, 1000, 1000));
  EXPECT_GT(c.failures, 0u);
  ASSERT_FALSE(c.first_failures.empty());
  EXPECT_LE(c.first_failures.size(), 16u);
  EXPECT_NE(c.first_failures[0].expected, c.first_failures[0].crossed);
}

TEST(CertifyCounts, ReversedChain_FailsEverywhereInShadow) {
  const Light light = point_light(0.4, 3.0, 0.3);
  Pipeline p = build_pipeline(unit_cube(), light);
  for (Sign& s : p.chain.cap_sign) s = -s;
  for (std::int32_t& m : p.chain.side_multiplicity) m = -m;
  const CountCertificate c = certify_counts(p.canonical, light, p.chain, small_sampling(3, 1000, 1000));
  EXPECT_GT(c.failures, 0u);
}

TEST(CertifyCounts, UserPoints_CheckedOrSkippedNeverMoved) {
  const Light light = point_light(0.5, 5.0, 0.5);
  const Pipeline p = build_pipeline(unit_cube(), light);
  CountSampling s = small_sampling(1, 0, 0);
  s.user_points = {{0.25, -2.0, 0.7}, {0.25, 1.0, 0.75} /* on the top face */, {3.0, 3.0, 3.0}};
  const CountCertificate c = certify_counts(p.canonical, light, p.chain, s);
  EXPECT_EQ(c.checks, 2u);
  EXPECT_EQ(c.failures, 0u);
  EXPECT_EQ(c.skipped, 1u);
}

TEST(CertifyCounts, LoneUserPoint_GetsARandomReference) {
  const Light light = point_light(0.5, 5.0, 0.5);
  const Pipeline p = build_pipeline(unit_cube(), light);
  CountSampling s = small_sampling(1, 0, 0);
  s.user_points = {{0.25, -2.0, 0.7}};
  const CountCertificate c = certify_counts(p.canonical, light, p.chain, s);
  EXPECT_EQ(c.checks, 1u);
  EXPECT_EQ(c.failures, 0u);
}

TEST(CertifyCounts, SameSeed_SameCertificate) {
  const Light light = point_light(1.3, 4.0, 0.7);
  const Pipeline p = build_pipeline(uv_sphere({0, 0, 0}, 1.0, 16, 8), light);
  const CountCertificate a = certify_counts(p.canonical, light, p.chain, small_sampling(11));
  const CountCertificate b = certify_counts(p.canonical, light, p.chain, small_sampling(11));
  EXPECT_EQ(a.checks, b.checks);
  EXPECT_EQ(a.redrawn, b.redrawn);
  EXPECT_EQ(a.skipped, b.skipped);
}

TEST(CertifyCounts, PointBehindSphere_CheckedAtCountTwo) {
  const Light light = point_light(0.01, 10.0, 0.02);
  const Pipeline p = build_pipeline(uv_sphere({0, 0, 0}, 1.0, 24, 12), light);
  CountSampling s = small_sampling(5, 200, 200);
  s.user_points = {{0.003, -3.0, 0.001}};
  const CountCertificate c = certify_counts(p.canonical, light, p.chain, s);
  EXPECT_EQ(c.failures, 0u);
  EXPECT_EQ(OccluderCounter(p.canonical, light).count({0.003, -3.0, 0.001}), std::optional<std::uint32_t>(2));
}

// Every fan size from 1 to 256 (docs/definitions.md#hard-cases), exact: closed and counts right.
TEST(CertifyCounts, FansOf1To256_CountsRight) {
  for (std::uint32_t k = 1; k <= 256; ++k) {
    for (const Light& light : {point_light(0.3, 0.45, 2.0), directional_light(0.2, 0.3, 1.0)}) {
      const Pipeline p = build_pipeline(nonmanifold_fan(k), light);
      ASSERT_TRUE(certify_closure(p.chain).closed) << "k = " << k;
      const CountCertificate c = certify_counts(p.canonical, light, p.chain, small_sampling(k, 40, 40));
      ASSERT_EQ(c.failures, 0u) << "k = " << k;
      ASSERT_GT(c.checks, 70u) << "k = " << k;
    }
  }
}

// Property: seeded random soups with shared edges, random lights of both kinds; exact counts
// right, and every consistent float method's chain winds as its own signs claim.
TEST(CertifyCounts, RandomSoups_CountsRightAndChainsAsClaimed) {
  const std::uint64_t seed = 0xc0ffee;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  for (int round = 0; round < 8; ++round) {
    Soup soup = random_soup(rng(), 60, 1.0);
    std::uniform_int_distribution<std::uint32_t> pick(0, 29);
    for (Triangle& t : soup.triangles)
      for (std::uint32_t& i : t) i = pick(rng);
    const Light light = round % 2 == 0 ? directional_light(coordinate(rng), coordinate(rng), coordinate(rng))
                                       : point_light(coordinate(rng), coordinate(rng), coordinate(rng));
    for (const MethodRun& run : consistent_runs()) expect_certified(soup, light, run, seed + round, 150);
  }
}

TEST(CertifyCounts, MismatchedChain_Throws) {
  const Light light = point_light(1.3, 4.0, 0.7);
  const Pipeline p = build_pipeline(unit_cube(), light);
  EXPECT_THROW((void)certify_counts(p.canonical, directional_light(0, 1, 0), p.chain, small_sampling(1)),
               std::invalid_argument);
}

}  // namespace
