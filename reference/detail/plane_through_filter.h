#pragma once
// Internal to the exact image (reference/exact_image.cpp): a floating-point filter for the sign
// of orient(o, p, q, x) = (x - o) . ((p - o) x (q - o)) over many points x known only by a
// double x' and a radius R around it (a hit point's enclosure, reference/detail/ray_hit.h): the
// product is evaluated at x' in doubles against a bound B on its error, fixed per plane, so the
// count tiles decide most of count_at's signs with one dot product each
// (docs/diff.md#tiles-coherent-rays-share-their-queries). Where it cannot decide, the exact
// predicate does: the filter's verdict, when it gives one, is the exact sign.
#include <cmath>
#include <limits>

#include "core/soup.h"
#include "core/vector3.h"

namespace shadowcert::detail {

// The plane through o, p, q (doubles) for points x with |x - x'|_i <= R_i and |x' - o|_i <= W_i
// per axis. Error analysis (u = 2^-53): a = fl(p - o), b = fl(q - o), n = fl(a x b); with N the
// exact (p - o) x (q - o), |n_i - N_i| <= 4u (|a_j b_k| + |a_k b_j|) to first order (two
// differences, two products, one subtraction; 8.2u taken as e_i). The value v = fl((x' - o) . n)
// is within 5u sum_i W_i |n_i| of (x' - o) . n (one difference and a three-term dot product);
// (x' - o) . n within sum_i W_i e_i of (x' - o) . N; and that within sum_i R_i |N_i| <=
// sum_i R_i (|n_i| + e_i) of (x - o) . N. B is their sum, widened by 2^-20 relative for the
// second-order terms and by 2^-800 for underflow; inputs beyond 2^200 (overflow) decline.
// n = fl(a x b) for a, b themselves rounded differences of doubles (fl(p - o), fl(q - o)), and
// per axis e_i >= |n_i - N_i| against the exact (p - o) x (q - o): 4u (|a_j b_k| + |a_k b_j|) to
// first order (two differences, two products, one subtraction; 8.2u taken). Shared by this
// filter and the exact image's EdgePlaneFilter.
struct RoundedCross {
  Vec3 n{};
  Vec3 e{};
};
[[nodiscard]] inline RoundedCross rounded_cross(const Vec3& a, const Vec3& b) {
  constexpr double u = 0x1p-53;
  RoundedCross out;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    out.n[i] = a[j] * b[k] - a[k] * b[j];
    out.e[i] = 8.2 * u * (std::fabs(a[j] * b[k]) + std::fabs(a[k] * b[j]));
  }
  return out;
}

class PlaneThroughFilter {
 public:
  PlaneThroughFilter() = default;
  PlaneThroughFilter(const Vec3& o, const Vec3& p, const Vec3& q, const Vec3& W, const Vec3& R) : o_(o) {
    constexpr double u = 0x1p-53, kTame = 0x1p200;
    // rounded_cross's n and e, each component written where it is kept (a returned struct
    // copied in here was read back before its stores retired: a stall per filter).
    const Vec3 a = difference(p, o), b = difference(q, o);
    double bound = 0.0;
    bool tame = true;
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      n_[i] = a[j] * b[k] - a[k] * b[j];
      const double e = 8.2 * u * (std::fabs(a[j] * b[k]) + std::fabs(a[k] * b[j]));
      bound += W[i] * (5.0 * u * std::fabs(n_[i]) + e) + R[i] * (std::fabs(n_[i]) + e);
      for (const double x : {o[i], p[i], q[i], W[i], R[i]}) tame = tame && std::fabs(x) <= kTame;
    }
    bound_ = bound * (1.0 + 0x1p-20) + 0x1p-800;
    if (!tame || !std::isfinite(bound_)) bound_ = std::numeric_limits<double>::infinity();
  }

  // +1 or -1: the exact sign of orient(o, p, q, x) for every x within R of x'; 0: undecided.
  // Precondition: |x' - o|_i <= W_i (the constructor's W).
  [[nodiscard]] int sign(const Vec3& x) const {
    const double v = (x[0] - o_[0]) * n_[0] + (x[1] - o_[1]) * n_[1] + (x[2] - o_[2]) * n_[2];
    // Without a branch: the sign varies from point to point (a mispredicted branch per call).
    return static_cast<int>(v > bound_) - static_cast<int>(v < -bound_);
  }

 private:
  Vec3 o_{}, n_{};
  double bound_ = std::numeric_limits<double>::infinity();  // default: decides nothing
};

}  // namespace shadowcert::detail
