#pragma once
// Internal to reference/exact_image.cpp: an eye tile's pixel rays cut into small blocks, and for
// a plane through the eye in its ray-direction form (the sign of d . n for a ray direction d),
// the side that every ray of a block takes, certified once per block instead of once per ray.
// A tile's list of candidate triangles holds every triangle some ray of the tile may meet; on a
// dense mesh a triangle covers a few pixels, so most of a long list misses most blocks, and a
// block's rays skip the triangles whose plane is behind the eye or whose crossing lies strictly
// outside an edge line for all of them (docs/diff.md#tiles-coherent-rays-share-their-queries).
// The verdicts are exact: only the scan shortens, never an answer.
//
// The bound: pixel_ray(frame, x, y) has direction d = fl(f + a r + b u) with a = pixel_ray_a(x)
// and b = pixel_ray_b(y) monotone in x and y, so a block's a lie in [a(X0), a(X1)] and its b in
// [b(Y1), b(Y0)]. With (ac, bc) the block's middle and c = f + ac r + bc u (exact), d . n is
// within the plane's margin of v = fl(gamma + ac alpha + bc beta), gamma, alpha, beta the
// rounded f . n~, r . n~, u . n~ of the double normal n~ (eye_blocks.cpp derives the margin).
#include <cstdint>
#include <vector>

#include "core/pixel_ray.h"
#include "core/sign.h"

namespace shadowcert::detail {

class EyeBlocks {
 public:
  // The rays pixel_ray(frame, x, y) of image points x in [x0, x1], y in [y0, y1] (a tile's
  // pixel centres and the corners on its closed square; x0 < x1, y0 < y1), in blocks of `block`
  // image units a side: block (column i, row j) holds x in [x0 + i block, min(x0 + (i + 1)
  // block, x1)] and y likewise. Throws std::invalid_argument for an empty tile or block = 0.
  EyeBlocks(const CameraFrame& frame, std::uint32_t x0, std::uint32_t x1, std::uint32_t y0, std::uint32_t y1,
            std::uint32_t block);

  [[nodiscard]] std::uint32_t columns() const { return static_cast<std::uint32_t>(a_middle_.size()); }
  [[nodiscard]] std::uint32_t rows() const { return static_cast<std::uint32_t>(b_middle_.size()); }
  // The column holding image point x in [x0, x1] (a point on a border between two: the later),
  // the row holding y in [y0, y1].
  [[nodiscard]] std::uint32_t column_of(std::uint32_t x) const;
  [[nodiscard]] std::uint32_t row_of(std::uint32_t y) const;

  // A plane's terms over the blocks: its value at each block's middle is gamma + ac alpha +
  // bc beta, and every ray direction of the block is within `margin` of it (+infinity where
  // no bound holds: every sign() is zero).
  struct Plane {
    double gamma = 0.0;
    double alpha = 0.0;
    double beta = 0.0;
    double margin = 0.0;
  };
  // The plane d . n for an exact normal n within `normal_error` of the double n~ in the sense
  // |d . (n - n~)| <= normal_error for every ray direction d of the tile (0 where n~ is exact;
  // a filter's bound, exact_image.cpp's CandidateRaySigns, otherwise).
  [[nodiscard]] Plane plane(const Vec3& normal, double normal_error) const;

  // The sign of d . n shared by every ray direction d of the block, or zero where the margin
  // cannot certify one.
  [[nodiscard]] Sign sign(const Plane& plane, std::uint32_t column, std::uint32_t row) const {
    const double v = value(plane, column, row);
    if (v > plane.margin) return Sign::positive;
    if (v < -plane.margin) return Sign::negative;
    return Sign::zero;
  }

  // The same verdicts for every block at once, as bit masks (bit column + row * columns()), for
  // at most kMaskBlocks blocks (std::logic_error otherwise): the blocks whose sign is `side`
  // (nonzero), and those whose sign is certain (either).
  static constexpr std::uint32_t kMaskBlocks = 32;
  [[nodiscard]] std::uint32_t blocks_on_side(const Plane& plane, Sign side) const;
  [[nodiscard]] std::uint32_t blocks_decided(const Plane& plane) const;

 private:
  // The bits of the blocks where holds(column, row); std::logic_error naming `function` beyond
  // kMaskBlocks blocks.
  template <typename Holds>
  [[nodiscard]] std::uint32_t mask(const char* function, Holds&& holds) const;

  [[nodiscard]] double value(const Plane& plane, std::uint32_t column, std::uint32_t row) const {
    return plane.gamma + a_middle_[column] * plane.alpha + b_middle_[row] * plane.beta;
  }

  CameraFrame frame_;
  std::uint32_t x0_, y0_, block_;
  std::vector<double> a_middle_, b_middle_;  // per column ac, per row bc
  double a_spread_ = 0.0, b_spread_ = 0.0;   // |a - ac| <= a_spread_ in every block, likewise b
  Vec3 magnitude_{};                         // per axis, |f_k| + amax |r_k| + bmax |u_k|
  bool usable_ = false;
};

}  // namespace shadowcert::detail
