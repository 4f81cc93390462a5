// reference/detail/plane_through_filter.h: where PlaneThroughFilter gives a sign it is the exact
// orient(o, p, q, x) for every point x within R of the evaluated x' (checked against the exact
// predicate on points at the box's corners and inside), at every scale the campaign draws,
// with points on the plane and within rounding of it; and it decides the clear cases.
#include "reference/detail/plane_through_filter.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "exact/light_orientation.h"
#include "exact/orient_unchecked.h"

namespace {

using shadowcert::Vec3;
using shadowcert::detail::PlaneThroughFilter;

int exact_sign(const Vec3& o, const Vec3& p, const Vec3& q, const Vec3& x) {
  using shadowcert::finite_point;
  return static_cast<int>(
      shadowcert::detail::orient_unchecked(finite_point(o), finite_point(p), finite_point(q), finite_point(x)));
}

TEST(PlaneThroughFilter, RandomPlanesAtEveryScale_AgreeWithTheExactSign) {
  const unsigned seed = 2024120601;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), weight(0.0, 1.0);
  int decided = 0, checked = 0, near_decided = 0;
  for (double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6})
    for (double offset : {0.0, 1e3, 1e6})
      for (int trial = 0; trial < 300; ++trial) {
        const auto point = [&](double spread) {
          return Vec3{offset + spread * unit(rng), offset + spread * unit(rng), offset + spread * unit(rng)};
        };
        const Vec3 o = point(scale), p = point(scale), q = point(scale);
        // x' on the plane (a rounded affine combination), near it, or anywhere in the box.
        const double s = weight(rng), t = weight(rng);
        Vec3 x{};
        for (int k = 0; k < 3; ++k) x[k] = o[k] + s * (p[k] - o[k]) + t * (q[k] - o[k]);
        const int kind = trial % 3;
        const double nudge = kind == 0 ? 0.0 : kind == 1 ? 1e-12 * scale : scale;
        for (double& v : x) v += nudge * unit(rng);
        const Vec3 R{1e-14 * scale * weight(rng), 1e-14 * scale * weight(rng), 0.0};
        Vec3 W{};
        for (int k = 0; k < 3; ++k) W[k] = std::fabs(x[k] - o[k]) * (1.0 + 0x1p-50);
        const PlaneThroughFilter filter(o, p, q, W, R);
        const int verdict = filter.sign(x);
        if (verdict == 0) continue;
        ++decided;
        near_decided += kind == 1;
        // Every corner of x's box and points inside have the verdict's sign.
        for (int corner = 0; corner < 12; ++corner) {
          Vec3 y = x;
          for (int k = 0; k < 3; ++k) {
            const double f = corner < 8 ? ((corner >> k) & 1 ? 1.0 : -1.0) : unit(rng);
            y[k] = x[k] + f * R[k];
            if (std::fabs(y[k] - x[k]) > R[k]) y[k] = x[k];  // rounded outside the box: its centre
          }
          ASSERT_EQ(exact_sign(o, p, q, y), verdict) << "scale " << scale << " offset " << offset << " trial " << trial;
          ++checked;
        }
      }
  EXPECT_GT(decided, 2000);     // the clear cases (points a scale away) are decided
  EXPECT_GT(checked, 24000);
  std::printf("decided %d (within 1e-12 of the plane: %d)\n", decided, near_decided);
}

TEST(PlaneThroughFilter, PointOnThePlaneOrUntameInput_DecidesNothing) {
  const Vec3 o{0.0, 0.0, 0.0}, p{1.0, 0.0, 0.0}, q{0.0, 1.0, 0.0};
  const Vec3 W{2.0, 2.0, 2.0}, R{0.0, 0.0, 1e-9};
  const PlaneThroughFilter filter(o, p, q, W, R);
  EXPECT_EQ(filter.sign({0.5, 0.5, 0.0}), 0);    // on the plane
  EXPECT_EQ(filter.sign({0.5, 0.5, 5e-10}), 0);  // within R of it: either side
  EXPECT_EQ(filter.sign({0.5, 0.5, 1.0}), 1);
  EXPECT_EQ(filter.sign({0.5, 0.5, -1.0}), -1);
  EXPECT_EQ(PlaneThroughFilter(o, p, {0.0, 0x1p300, 0.0}, W, R).sign({0.5, 0.5, 1.0}), 0);
  EXPECT_EQ(PlaneThroughFilter(o, p, q, W, {0.0, 0.0, std::nan("")}).sign({0.5, 0.5, 1.0}), 0);
  EXPECT_EQ(PlaneThroughFilter().sign({0.5, 0.5, 1.0}), 0);
}

}  // namespace
