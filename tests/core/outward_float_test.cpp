// Outward roundings to float (core/outward_float.h): down(x) <= x <= up(x) for doubles of every
// magnitude a float holds, including zero, float subnormals and the exact floats themselves.
#include "core/outward_float.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace {

using shadowcert::round_down_to_float;
using shadowcert::round_up_to_float;

void expect_enclosed(double x) {
  EXPECT_LE(static_cast<double>(round_down_to_float(x)), x) << x;
  EXPECT_GE(static_cast<double>(round_up_to_float(x)), x) << x;
}

TEST(OutwardFloat, RandomDoublesOfEveryFloatMagnitude_AreEnclosed) {
  const std::uint64_t seed = 5;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-160, 126);
  for (int i = 0; i < 200000; ++i) expect_enclosed(std::ldexp(mantissa(rng), exponent(rng)));
}

TEST(OutwardFloat, ExactFloatsZeroAndSubnormals_AreEnclosedAndTight) {
  for (const double x : {0.0, -0.0, 1.0, -1.0, 0.1, 3.0e38, -3.0e38, 0x1p-149, -0x1p-149, 0x1p-130, 0x1p-126}) {
    expect_enclosed(x);
    // Loose by at most a few float steps: 2^-21 of |x| and two subnormal steps.
    EXPECT_LE(static_cast<double>(round_up_to_float(x)) - static_cast<double>(round_down_to_float(x)),
              std::fabs(x) * 0x1p-20 + 0x1p-147)
        << x;
  }
}

}  // namespace
