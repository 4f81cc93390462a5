// The exact predicate D(a, b, c, L) and orient(p, q, r, s) of docs/definitions.md#orientation against an
// independent integer brute force (tests/exact/brute_force_orientation.h).
#include "exact/light_orientation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <random>
#include <stdexcept>

#include "brute_force_orientation.h"
#include "exact/light_orientation_filter.h"

namespace {

using namespace shadowcert;

constexpr std::uint64_t kSeed = 20240611;

Light point_light(const Vec3& p) { return Light{{p[0], p[1], p[2], 1.0}}; }
Light directional_light(const Vec3& d) { return Light{{d[0], d[1], d[2], 0.0}}; }
HomogeneousPoint direction(const Vec3& d) { return {d[0], d[1], d[2], 0.0}; }

class RandomPoints {
 public:
  explicit RandomPoints(std::uint64_t seed) : engine_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine_); }
  Vec3 in_box(double extent) { return {uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)}; }
  // A coordinate with a random sign, mantissa and decimal exponent in [lo, hi].
  double wide(int lo, int hi) {
    const double mantissa = uniform(1.0, 10.0);
    const int exponent = std::uniform_int_distribution<int>(lo, hi)(engine_);
    const double x = mantissa * std::pow(10.0, exponent);
    return (engine_() & 1) ? -x : x;
  }
  Vec3 wide_point(int lo, int hi) { return {wide(lo, hi), wide(lo, hi), wide(lo, hi)}; }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine_); }
  std::mt19937_64& engine() { return engine_; }

 private:
  std::mt19937_64 engine_;
};

// Checks D against brute force for both light kinds, and orient with the light in every
// argument position (so the reduction to "infinite point last" is exercised).
void expect_matches_brute_force(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& l) {
  for (const Light& light : {point_light(l), directional_light(l)}) {
    if (light.directional() && l == Vec3{0, 0, 0}) continue;
    const int expected = brute::light_orientation(a, b, c, light.position);
    ASSERT_EQ(to_int(light_orientation(a, b, c, light)), expected)
        << "a=" << a[0] << "," << a[1] << "," << a[2] << " b=" << b[0] << "," << b[1] << "," << b[2]
        << " c=" << c[0] << "," << c[1] << "," << c[2] << " l=" << l[0] << "," << l[1] << "," << l[2]
        << " w=" << light.position[3];
    const HomogeneousPoint pa = finite_point(a), pb = finite_point(b), pc = finite_point(c), pl = light.position;
    ASSERT_EQ(to_int(orient(pa, pb, pc, pl)), expected);
    ASSERT_EQ(to_int(orient(pa, pb, pl, pc)), brute::orient4(pa, pb, pl, pc));
    ASSERT_EQ(to_int(orient(pa, pl, pb, pc)), brute::orient4(pa, pl, pb, pc));
    ASSERT_EQ(to_int(orient(pl, pa, pb, pc)), brute::orient4(pl, pa, pb, pc));
    // The semi-static stage alone: whenever it answers, it is right.
    if (const std::optional<Sign> quick = detail::semi_static_light_orientation(a, b, c, light.position)) {
      ASSERT_EQ(to_int(*quick), expected);
    }
  }
}

TEST(Orient, UnitTetrahedron_PositiveLikeCgal) {
  // docs/definitions.md#orientation: orient = sign det[q - p, r - p, s - p]; det[e1, e2, e3] = 1.
  const HomogeneousPoint o{0, 0, 0, 1}, x{1, 0, 0, 1}, y{0, 1, 0, 1}, z{0, 0, 1, 1};
  EXPECT_EQ(orient(o, x, y, z), Sign::positive);
  EXPECT_EQ(orient(o, y, x, z), Sign::negative);
  EXPECT_EQ(brute::orient4(o, x, y, z), 1);  // the "minus the 4x4 determinant" definition agrees
  // The direction +z seen from the plane z = 0: same side as the point (0, 0, 1).
  EXPECT_EQ(orient(o, x, y, direction({0, 0, 1})), Sign::positive);
  EXPECT_EQ(orient(o, x, y, direction({0, 0, -1})), Sign::negative);
}

TEST(LightOrientation, LightOnNormalSide_Positive) {
  // (b - a) x (c - a) = +z for the unit triangle in z = 0.
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_EQ(light_orientation(a, b, c, point_light({0.2, 0.2, 5})), Sign::positive);
  EXPECT_EQ(light_orientation(a, b, c, point_light({0.2, 0.2, -5})), Sign::negative);
  EXPECT_EQ(light_orientation(a, b, c, directional_light({1, 1, 1})), Sign::positive);
  EXPECT_EQ(light_orientation(a, b, c, directional_light({1, 1, -1})), Sign::negative);
}

TEST(LightOrientation, RandomInputs_MatchExactBruteForce) {
  std::cout << "seed " << kSeed << "\n";
  RandomPoints rng(kSeed);
  for (int i = 0; i < 4000; ++i) expect_matches_brute_force(rng.in_box(10), rng.in_box(10), rng.in_box(10), rng.in_box(100));
}

TEST(LightOrientation, PointsOnPlanePerturbedByUlps_MatchExactBruteForce) {
  std::cout << "seed " << kSeed + 1 << "\n";
  RandomPoints rng(kSeed + 1);
  for (int i = 0; i < 400; ++i) {
    const Vec3 a = rng.in_box(1), b = rng.in_box(1), c = rng.in_box(1);
    // A point on the plane of a, b, c up to the rounding of this construction, then moved by
    // -2..2 ulps on each coordinate: the filter must give up and the exact stage decide.
    const double s = rng.uniform(-2, 2), t = rng.uniform(-2, 2);
    Vec3 l;
    for (int k = 0; k < 3; ++k) l[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]);
    for (int step = 0; step < 8; ++step) {
      Vec3 moved = l;
      for (int k = 0; k < 3; ++k)
        for (int u = rng.integer(-2, 2); u != 0; u += (u > 0 ? -1 : 1))
          moved[k] = std::nextafter(moved[k], u > 0 ? 1e300 : -1e300);
      expect_matches_brute_force(a, b, c, moved);
      // The direction of the light as seen from a, on the plane's direction space.
      expect_matches_brute_force(a, b, c, {moved[0] - a[0], moved[1] - a[1], moved[2] - a[2]});
    }
  }
}

TEST(LightOrientation, HugeAndTinyMagnitudes_MatchExactBruteForce) {
  std::cout << "seed " << kSeed + 2 << "\n";
  RandomPoints rng(kSeed + 2);
  for (int i = 0; i < 1500; ++i)
    expect_matches_brute_force(rng.wide_point(-300, 300), rng.wide_point(-300, 300), rng.wide_point(-300, 300),
                               rng.wide_point(-300, 300));
  // All tiny (products underflow in double), all huge (products overflow in double).
  for (int i = 0; i < 300; ++i)
    expect_matches_brute_force(rng.wide_point(-310, -290), rng.wide_point(-310, -290), rng.wide_point(-310, -290),
                               rng.wide_point(-310, -290));
  for (int i = 0; i < 300; ++i)
    expect_matches_brute_force(rng.wide_point(290, 300), rng.wide_point(290, 300), rng.wide_point(290, 300),
                               rng.wide_point(290, 300));
}

TEST(LightOrientation, DifferenceRoundsInDouble_ExactSignStillFound) {
  // b and c lie on the line y = x through the origin, a = (t, 0, 0) just below it, so
  // det2[b - a, c - a] = 2t > 0. In doubles 1 - t == 1 and -1 - t == -1: a predicate that
  // rounded b - a, c - a first would see three collinear points and answer zero.
  const double t = 1e-300;
  const Vec3 a{t, 0, 0}, b{1, 1, 0}, c{-1, -1, 0};
  const double naive = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  ASSERT_EQ(naive, 0.0);
  EXPECT_EQ(light_orientation(a, b, c, directional_light({0, 0, 1})), Sign::positive);
  EXPECT_EQ(light_orientation(a, b, c, point_light({0, 0, 1})), Sign::positive);
  EXPECT_EQ(light_orientation(a, b, c, directional_light({0, 0, -1e-300})), Sign::negative);
  EXPECT_EQ(orient(finite_point(a), finite_point(b), finite_point(c), direction({0, 0, 1})), Sign::positive);
}

TEST(LightOrientation, ExactDegeneracies_Zero) {
  const Vec3 a{1, 2, 3}, b{4, 6, 8}, c{-2, 5, 1};
  const Vec3 mid{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};  // exact: small integers
  for (const Light& light : {point_light({7, -3, 2}), directional_light({0.25, 1, -3})}) {
    EXPECT_EQ(light_orientation(a, a, c, light), Sign::zero) << "repeated vertex";
    EXPECT_EQ(light_orientation(a, b, mid, light), Sign::zero) << "collinear vertices";
  }
  // Point light at a vertex, on an edge's line, in the plane.
  EXPECT_EQ(light_orientation(a, b, c, point_light(a)), Sign::zero);
  EXPECT_EQ(light_orientation(a, b, c, point_light({2 * b[0] - a[0], 2 * b[1] - a[1], 2 * b[2] - a[2]})), Sign::zero);
  EXPECT_EQ(light_orientation(a, b, c, point_light({b[0] + c[0] - a[0], b[1] + c[1] - a[1], b[2] + c[2] - a[2]})),
            Sign::zero);
  // Directional light parallel to the plane (and parallel to an edge).
  EXPECT_EQ(light_orientation(a, b, c, directional_light({b[0] - a[0], b[1] - a[1], b[2] - a[2]})), Sign::zero);
  EXPECT_EQ(light_orientation(a, b, c, directional_light({b[0] + c[0] - 2 * a[0], b[1] + c[1] - 2 * a[1],
                                                          b[2] + c[2] - 2 * a[2]})),
            Sign::zero);
  // A floor at y = 0 lit exactly at grazing angle, and one ulp above.
  const Vec3 f0{-1, 0, -1}, f1{-1, 0, 1}, f2{1, 0, 1};
  EXPECT_EQ(light_orientation(f0, f1, f2, point_light({5, 0, 3})), Sign::zero);
  EXPECT_EQ(light_orientation(f0, f1, f2, point_light({5, std::numeric_limits<double>::denorm_min(), 3})),
            Sign::positive);
  EXPECT_EQ(light_orientation(f0, f1, f2, directional_light({1, -std::numeric_limits<double>::denorm_min(), 0})),
            Sign::negative);
}

TEST(LightOrientation, IntegerGridCoplanarities_MatchExactBruteForce) {
  // Small integer grids make exact zeros frequent (docs/definitions.md#hard-cases: soups snapped to a grid).
  std::cout << "seed " << kSeed + 3 << "\n";
  RandomPoints rng(kSeed + 3);
  auto grid_point = [&rng] {
    return Vec3{double(rng.integer(-2, 2)), double(rng.integer(-2, 2)), double(rng.integer(-2, 2))};
  };
  int zeros = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 a = grid_point(), b = grid_point(), c = grid_point(), l = grid_point();
    expect_matches_brute_force(a, b, c, l);
    zeros += light_orientation(a, b, c, point_light(l)) == Sign::zero;
  }
  EXPECT_GT(zeros, 100);
}

TEST(LightOrientation, Permutations_FollowParity) {
  std::cout << "seed " << kSeed + 4 << "\n";
  RandomPoints rng(kSeed + 4);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a = rng.in_box(1), b = rng.in_box(1), c = rng.in_box(1);
    for (const Light& light : {point_light(rng.in_box(3)), directional_light(rng.in_box(1))}) {
      const Sign s = light_orientation(a, b, c, light);
      ASSERT_EQ(light_orientation(b, c, a, light), s);
      ASSERT_EQ(light_orientation(c, a, b, light), s);
      ASSERT_EQ(light_orientation(b, a, c, light), -s);
      ASSERT_EQ(light_orientation(a, c, b, light), -s);
      ASSERT_EQ(light_orientation(c, b, a, light), -s);
    }
    // orient is alternating in all four arguments, finite or not.
    const HomogeneousPoint p = finite_point(a), q = finite_point(b), r = finite_point(c);
    for (const HomogeneousPoint& s : {finite_point(rng.in_box(2)), direction(rng.in_box(1))}) {
      const Sign o = orient(p, q, r, s);
      ASSERT_EQ(orient(q, p, r, s), -o);
      ASSERT_EQ(orient(p, r, q, s), -o);
      ASSERT_EQ(orient(p, q, s, r), -o);
      ASSERT_EQ(orient(s, q, r, p), -o);
      ASSERT_EQ(orient(q, r, s, p), -o);  // a 4-cycle is odd
      ASSERT_EQ(orient(r, s, p, q), o);   // two transpositions
    }
  }
}

TEST(Orient, TwoPointsAtInfinity_Throws) {
  const HomogeneousPoint p{0, 0, 0, 1}, q{1, 0, 0, 1}, d1{0, 0, 1, 0}, d2{0, 1, 0, 0};
  EXPECT_THROW((void)orient(p, q, d1, d2), std::invalid_argument);
  EXPECT_THROW((void)orient(d1, p, q, d2), std::invalid_argument);
}

TEST(Orient, InvalidHomogeneousPoint_Throws) {
  const HomogeneousPoint p{0, 0, 0, 1}, q{1, 0, 0, 1}, r{0, 1, 0, 1};
  EXPECT_THROW((void)orient(p, q, r, {0, 0, 1, 0.5}), std::invalid_argument);
  EXPECT_THROW((void)orient(p, q, r, {0, 0, 0, 0}), std::invalid_argument);
  EXPECT_THROW((void)orient(p, q, r, {std::nan(""), 0, 1, 1}), std::invalid_argument);
  EXPECT_THROW((void)orient(p, q, r, {std::numeric_limits<double>::infinity(), 0, 1, 1}), std::invalid_argument);
}

TEST(LightOrientation, InvalidLight_Throws) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_THROW((void)light_orientation(a, b, c, Light{{0, 0, 1, 2}}), std::invalid_argument);
  EXPECT_THROW((void)light_orientation(a, b, c, Light{{0, 0, 0, 0}}), std::invalid_argument);
  EXPECT_THROW((void)light_orientation(a, b, c, Light{{std::nan(""), 0, 1, 1}}), std::invalid_argument);
}

}  // namespace
