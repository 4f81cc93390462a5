// exact/float_sign_bound.h: wherever a triangle is decided at a precision, every float
// evaluation of core/light_side_formula.h in that precision, in each of the six vertex orders,
// has the exact sign; exactly degenerate configurations are never decided; a well-separated
// light is decided in float and double; near-coplanar lights are undecided in float first.
#include "exact/float_sign_bound.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <random>

#include "core/light_side_formula.h"
#include "exact/light_orientation.h"

namespace {

using namespace shadowcert;

constexpr std::uint64_t kSeed = 0x51676e;

// The float sign of D(a, b, c, L) as a method evaluating the order (p, q, r) sees it, turned
// back into the orientation (a, b, c) by the permutation's parity.
template <typename Real>
Sign float_sign(const std::array<Vec3, 3>& v, const std::array<int, 3>& order, const Light& light) {
  const std::array<Real, 4> l{static_cast<Real>(light.position[0]), static_cast<Real>(light.position[1]),
                              static_cast<Real>(light.position[2]), static_cast<Real>(light.position[3])};
  const Sign s = light_side_sign(to_precision<Real>(v[order[0]]), to_precision<Real>(v[order[1]]),
                                 to_precision<Real>(v[order[2]]), l);
  const int inversions = (order[0] > order[1]) + (order[0] > order[2]) + (order[1] > order[2]);
  return inversions % 2 == 0 ? s : -s;
}

constexpr std::array<std::array<int, 3>, 6> kOrders{{{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}}};

struct Tally {
  int decided = 0, undecided = 0, undecided_and_wrong = 0;
};

// Checks one configuration at one precision; returns whether it was decided.
template <typename Real>
void check(const std::array<Vec3, 3>& v, const Light& light, Precision precision, Tally& tally) {
  const Sign exact = light_orientation(v[0], v[1], v[2], light);
  const bool decided = float_sign_is_decided(v[0], v[1], v[2], light, precision);
  bool wrong = false;
  for (const auto& order : kOrders) wrong |= float_sign<Real>(v, order, light) != exact;
  if (decided) {
    ++tally.decided;
    EXPECT_NE(exact, Sign::zero);
    EXPECT_FALSE(wrong) << "decided but a float evaluation has another sign: (" << v[0][0] << ", " << v[0][1] << ", "
                        << v[0][2] << ") ...";
  } else {
    ++tally.undecided;
    tally.undecided_and_wrong += wrong;
  }
}

// Random triangles at random scales and offsets, with the light on the plane pushed off it
// by a random relative distance from 1e-1 down to 1e-19: across both precisions' thresholds.
TEST(FloatSignBound, NearCoplanarLights_DecidedImpliesEveryOrderHasTheExactSign) {
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-19, -1);
  Tally single, twice;
  for (int k = 0; k < 20000; ++k) {
    const double scale = std::ldexp(1.0, static_cast<int>(std::round(unit(rng) * 20)));
    const double offset = k % 4 == 0 ? 1e6 : 0.0;
    std::array<Vec3, 3> v;
    for (Vec3& p : v)
      for (double& x : p) x = offset + scale * unit(rng);
    const double s = unit(rng) * 2, t = unit(rng) * 2, lift = std::pow(10.0, exponent(rng)) * scale;
    Light light;
    if (k % 3 == 0) {  // directional, nearly parallel to the plane
      for (int d = 0; d < 3; ++d)
        light.position[d] = s * (v[1][d] - v[0][d]) + t * (v[2][d] - v[0][d]) + lift * unit(rng);
      light.position[3] = 0.0;
      if (light.position[0] == 0.0 && light.position[1] == 0.0 && light.position[2] == 0.0) continue;
    } else {
      for (int d = 0; d < 3; ++d)
        light.position[d] = v[0][d] + s * (v[1][d] - v[0][d]) + t * (v[2][d] - v[0][d]) + lift * unit(rng);
      light.position[3] = 1.0;
    }
    check<float>(v, light, Precision::float32, single);
    check<double>(v, light, Precision::float64, twice);
  }
  // Both outcomes occur, and rounding does flip signs where the bound says it may.
  EXPECT_GT(single.decided, 1000);
  EXPECT_GT(single.undecided, 1000);
  EXPECT_GT(single.undecided_and_wrong, 100);
  EXPECT_GT(twice.decided, single.decided);
  EXPECT_GT(twice.undecided_and_wrong, 10);
}

TEST(FloatSignBound, LightExactlyOnThePlaneOrDegenerateTriangle_NeverDecided) {
  const Vec3 a{0.1, 0.2, 0.3}, b{1.5, -0.25, 0.75}, c{-0.5, 2.0, 0.125};
  for (Precision p : {Precision::float32, Precision::float64}) {
    EXPECT_FALSE(float_sign_is_decided(a, b, c, Light{{b[0], b[1], b[2], 1.0}}, p));               // at a vertex
    EXPECT_FALSE(float_sign_is_decided(a, a, c, Light{{5, 5, 5, 1}}, p));                          // a repeated vertex
    EXPECT_FALSE(float_sign_is_decided({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, Light{{1, 1, 0, 0}}, p));  // parallel
    EXPECT_FALSE(float_sign_is_decided({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, Light{{0.3, 0.3, 0, 1}}, p));  // in plane
  }
}

TEST(FloatSignBound, WellSeparatedLight_DecidedInBothPrecisions) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  for (Precision p : {Precision::float32, Precision::float64}) {
    EXPECT_TRUE(float_sign_is_decided(a, b, c, Light{{0.2, 0.3, 5.0, 1.0}}, p));
    EXPECT_TRUE(float_sign_is_decided(a, b, c, Light{{0.2, 0.3, -1.0, 0.0}}, p));
  }
}

// The same unit triangle and light offset by 1e6: double subtracts exactly what it reads, so it
// stays decided; float first rounds every coordinate to 1/16 there, which can move the plane
// by more than the light's height: undecided.
TEST(FloatSignBound, OffsetBy1e6_DecidedInDoubleUndecidedInFloat) {
  const Vec3 a{1e6, 1e6, 1e6}, b{1e6 + 1, 1e6, 1e6}, c{1e6, 1e6 + 1, 1e6};
  const Light light{{1e6, 1e6, 1e6 + 0.5, 1.0}};
  EXPECT_TRUE(float_sign_is_decided(a, b, c, light, Precision::float64));
  EXPECT_FALSE(float_sign_is_decided(a, b, c, light, Precision::float32));
}

TEST(FloatSignBound, LightOneMillionthOffThePlane_UndecidedInFloatDecidedInDouble) {
  const Vec3 a{0.1, 0.2, 0.3}, b{1.1, 0.2, 0.3}, c{0.1, 1.2, 0.3};
  const Light light{{0.5, 0.5, 0.3 + 1e-9, 1.0}};
  EXPECT_FALSE(float_sign_is_decided(a, b, c, light, Precision::float32));
  EXPECT_TRUE(float_sign_is_decided(a, b, c, light, Precision::float64));
}

TEST(FloatSignBound, BadLight_Throws) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_THROW((void)float_sign_is_decided(a, b, c, Light{{0, 0, 1, 2}}, Precision::float32), std::invalid_argument);
  EXPECT_THROW((void)float_sign_is_decided(a, b, c, Light{{NAN, 0, 1, 1}}, Precision::float32), std::invalid_argument);
}

}  // namespace
