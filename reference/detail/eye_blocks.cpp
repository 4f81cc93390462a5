// EyeBlocks of reference/detail/eye_blocks.h. u = 2^-53 below; every bound is formed in
// round-to-nearest doubles from non-negative terms and widened by a relative 2^-40, far more
// than the few roundings of its own evaluation.
//
// The margin. For a ray direction d of block (i, j) and the exact normal n:
//   d . n = d . n~ + d . (n - n~), the second term within normal_error;
//   d . n~ = c . n~ + (d - c) . n~, with c = f + ac r + bc u exact. d_k = fl(fl(f_k + fl(a r_k))
//   + fl(b u_k)) is within 3u m_k of f_k + a r_k + b u_k (m_k = |f_k| + amax |r_k| + bmax |u_k|,
//   to first order), which is within sa |r_k| + sb |u_k| of c_k (|a - ac| <= sa, |b - bc| <=
//   sb), so |(d - c) . n~| <= sa R + sb U + 3u Q with R = sum |r_k n~_k|, U = sum |u_k n~_k|,
//   Q = sum m_k |n~_k|;
//   c . n~ = gamma + ac alpha + bc beta exactly (gamma = f . n~ and so on, exact), and the
//   stored gamma, alpha, beta (three-term dot products, each within 3u of its absolute terms)
//   and sign()'s v (two products and two sums, within 2u of its absolute terms) put v within
//   5.01u Q of it.
// So |d . n - v| <= normal_error + sa R + sb U + 8.01u Q, and the margin takes 2^-49 Q = 16u Q
// for the last term, plus 2^-1000 for the underflow of the few operations (each at most
// 2^-1074). Where the margin exceeds 2^1000 (or is not finite) no intermediate value is known
// not to overflow: the margin is +infinity and no block is decided.
#include "reference/detail/eye_blocks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace shadowcert::detail {
namespace {

constexpr double kWiden = 1.0 + 0x1p-40;

}  // namespace

EyeBlocks::EyeBlocks(const CameraFrame& frame, std::uint32_t x0, std::uint32_t x1, std::uint32_t y0,
                     std::uint32_t y1, std::uint32_t block)
    : frame_(frame), x0_(x0), y0_(y0), block_(block) {
  if (block == 0 || x0 >= x1 || y0 >= y1) throw std::invalid_argument("EyeBlocks: an empty tile or block");
  // Per column (row) its middle, and the largest distance of a block's a (b) from its middle.
  const auto cut = [&](std::uint32_t lo, std::uint32_t hi, auto&& value, std::vector<double>& middles,
                       double& spread) {
    for (std::uint32_t from = lo; from < hi; from += block) {
      const std::uint32_t to = std::min(hi, from + block);
      const double v0 = value(from), v1 = value(to);
      const double low = std::min(v0, v1), high = std::max(v0, v1);  // b falls as y grows
      const double middle = 0.5 * (low + high);
      middles.push_back(middle);
      spread = std::max({spread, (middle - low) * kWiden, (high - middle) * kWiden});
    }
  };
  cut(x0, x1, [&](std::uint32_t x) { return pixel_ray_a(frame, x); }, a_middle_, a_spread_);
  cut(y0, y1, [&](std::uint32_t y) { return pixel_ray_b(frame, y); }, b_middle_, b_spread_);
  // a and b are monotone in x and y: their largest magnitudes over the tile are at its ends.
  const double amax = std::max(std::fabs(pixel_ray_a(frame, x0)), std::fabs(pixel_ray_a(frame, x1)));
  const double bmax = std::max(std::fabs(pixel_ray_b(frame, y0)), std::fabs(pixel_ray_b(frame, y1)));
  for (int k = 0; k < 3; ++k)
    magnitude_[k] = std::fabs(frame.forward[k]) + amax * std::fabs(frame.right[k]) + bmax * std::fabs(frame.up[k]);
  usable_ = std::isfinite(a_spread_) && std::isfinite(b_spread_);
}

std::uint32_t EyeBlocks::column_of(std::uint32_t x) const {
  return std::min((x - x0_) / block_, columns() - 1);
}

std::uint32_t EyeBlocks::row_of(std::uint32_t y) const { return std::min((y - y0_) / block_, rows() - 1); }

EyeBlocks::Plane EyeBlocks::plane(const Vec3& n, double normal_error) const {
  const Vec3 &f = frame_.forward, &r = frame_.right, &u = frame_.up;
  Plane p;
  p.gamma = f[0] * n[0] + f[1] * n[1] + f[2] * n[2];
  p.alpha = r[0] * n[0] + r[1] * n[1] + r[2] * n[2];
  p.beta = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
  double R = 0.0, U = 0.0, Q = 0.0;
  for (int k = 0; k < 3; ++k) {
    R += std::fabs(r[k] * n[k]);
    U += std::fabs(u[k] * n[k]);
    Q += magnitude_[k] * std::fabs(n[k]);
  }
  const double margin = (normal_error + a_spread_ * R + b_spread_ * U + 0x1p-49 * Q) * kWiden + 0x1p-1000;
  p.margin = usable_ && margin <= 0x1p1000 ? margin : std::numeric_limits<double>::infinity();
  return p;
}

template <typename Holds>
std::uint32_t EyeBlocks::mask(const char* function, Holds&& holds) const {
  if (columns() * rows() > kMaskBlocks) throw std::logic_error(std::string(function) + ": more blocks than a mask holds");
  std::uint32_t mask = 0;  // without a branch per block
  for (std::uint32_t row = 0; row < rows(); ++row)
    for (std::uint32_t column = 0; column < columns(); ++column)
      mask |= static_cast<std::uint32_t>(holds(column, row)) << (row * columns() + column);
  return mask;
}

std::uint32_t EyeBlocks::blocks_on_side(const Plane& plane, Sign side) const {
  // s v > margin for s = +-1 (the negation is exact).
  const double s = side == Sign::negative ? -1.0 : 1.0;
  const std::uint32_t on_side = mask("EyeBlocks::blocks_on_side", [&](std::uint32_t column, std::uint32_t row) {
    return s * value(plane, column, row) > plane.margin;
  });
  return side == Sign::zero ? 0 : on_side;
}

std::uint32_t EyeBlocks::blocks_decided(const Plane& plane) const {
  return mask("EyeBlocks::blocks_decided", [&](std::uint32_t column, std::uint32_t row) {
    return std::fabs(value(plane, column, row)) > plane.margin;
  });
}

}  // namespace shadowcert::detail
