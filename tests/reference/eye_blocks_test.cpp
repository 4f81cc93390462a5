// EyeBlocks (reference/detail/eye_blocks.h): every ray of a block whose side of a plane it
// certifies lies on that side (exactly, the normal's error included), near planes through the
// tile's own rays where the margin is what decides; it decides the blocks a plane leaves far
// behind; it declines where its bound does not hold; and it refuses an empty tile.
#include "reference/detail/eye_blocks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "reference/detail/eye_tile.h"

namespace {

using shadowcert::Camera;
using shadowcert::CameraFrame;
using shadowcert::Sign;
using shadowcert::Vec3;
using shadowcert::detail::EyeBlocks;

// The sign of d . (n + delta), computed in binary128: each product of two doubles is exact in
// it (106 of its 113 bits), and the sum of six rounds by a relative 2^-112 at most, far below
// the values the verdicts leave (`ambiguous` flags a sum within that of zero).
Sign exact_side(const Vec3& d, const Vec3& n, const Vec3& delta, bool& ambiguous) {
  __float128 sum = 0, magnitude = 0;
  for (int k = 0; k < 3; ++k) {
    const __float128 a = static_cast<__float128>(d[k]) * n[k], b = static_cast<__float128>(d[k]) * delta[k];
    sum += a;
    sum += b;
    magnitude += (a < 0 ? -a : a) + (b < 0 ? -b : b);
  }
  ambiguous = (sum < 0 ? -sum : sum) <= magnitude * static_cast<__float128>(0x1p-100);
  return sum > 0 ? Sign::positive : sum < 0 ? Sign::negative : Sign::zero;
}

Camera random_camera(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), coordinate(-50.0, 50.0);
  Camera camera;
  camera.eye = {coordinate(rng), coordinate(rng), coordinate(rng)};
  camera.target = {coordinate(rng), coordinate(rng), coordinate(rng)};
  camera.fov_y_degrees = 5.0 + 150.0 * unit(rng);
  camera.width = 16 + static_cast<std::uint32_t>(2000 * unit(rng));
  camera.height = 16 + static_cast<std::uint32_t>(2000 * unit(rng));
  return camera;
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// A camera at (0, 0, 5) looking down -z at the origin, `width` x `height` pixels: image x
// grows along +x, the middle column looks along the plane x = 0.
Camera looking_down(std::uint32_t width, std::uint32_t height) {
  Camera camera;
  camera.eye = {0.0, 0.0, 5.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.width = width;
  camera.height = height;
  return camera;
}

TEST(EyeBlocks, PlanesThroughTheTilesRays_EveryRayOfADecidedBlockHasItsSign) {
  const unsigned seed = 20261207;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), signed_unit(-1.0, 1.0);
  std::size_t decided = 0, undecided = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const Camera camera = random_camera(rng);
    const CameraFrame frame = shadowcert::camera_frame(camera);
    const std::uint32_t size = 1 + static_cast<std::uint32_t>(unit(rng) * 8.0);
    const std::uint32_t block = 1 + static_cast<std::uint32_t>(unit(rng) * 3.0);
    const std::uint32_t x0 = static_cast<std::uint32_t>(unit(rng) * (camera.width - size));
    const std::uint32_t y0 = static_cast<std::uint32_t>(unit(rng) * (camera.height - size));
    const std::uint32_t x1 = x0 + size, y1 = y0 + size;
    const EyeBlocks blocks(frame, x0, x1, y0, y1, block);
    const Vec3 W = shadowcert::detail::eye_tile_direction_bound(frame, x0, x1, y0, y1);
    for (int p = 0; p < 20; ++p) {
      // A plane through the eye and one of the tile's ray directions (a point of the tile,
      // not only a centre or a corner), turned about it by a random amount: it cuts the tile
      // or passes just beside it, where the blocks next to it test the margin.
      const Vec3 through = shadowcert::pixel_ray(frame, x0 + size * unit(rng), y0 + size * unit(rng)).direction;
      Vec3 n = cross(through, {signed_unit(rng), signed_unit(rng), signed_unit(rng)});
      const double turn = std::pow(2.0, -40.0 * unit(rng));
      for (double& c : n) c += turn * signed_unit(rng);
      // Half the planes carry an error of the normal the caller bounds (a filter's rounding).
      Vec3 delta{};
      double normal_error = 0.0;
      if (p % 2 == 1) {
        for (int k = 0; k < 3; ++k) {
          delta[k] = std::ldexp(signed_unit(rng), -45) * std::fabs(n[k]);
          normal_error += W[k] * std::fabs(delta[k]);
        }
        normal_error *= 1.0 + 0x1p-40;
      }
      const EyeBlocks::Plane plane = blocks.plane(n, normal_error);
      // The masks give sign()'s verdicts, block by block.
      if (blocks.columns() * blocks.rows() <= EyeBlocks::kMaskBlocks) {
        const std::uint32_t positive = blocks.blocks_on_side(plane, Sign::positive),
                            negative = blocks.blocks_on_side(plane, Sign::negative), decided_mask = blocks.blocks_decided(plane);
        for (std::uint32_t row = 0; row < blocks.rows(); ++row)
          for (std::uint32_t column = 0; column < blocks.columns(); ++column) {
            const std::uint32_t bit = 1u << (row * blocks.columns() + column);
            const Sign verdict = blocks.sign(plane, column, row);
            ASSERT_EQ((positive & bit) != 0, verdict == Sign::positive) << "trial " << trial;
            ASSERT_EQ((negative & bit) != 0, verdict == Sign::negative) << "trial " << trial;
            ASSERT_EQ((decided_mask & bit) != 0, verdict != Sign::zero) << "trial " << trial;
          }
        EXPECT_EQ(blocks.blocks_on_side(plane, Sign::zero), 0u);
      }
      for (std::uint32_t y = y0; y <= y1; ++y)
        for (std::uint32_t x = x0; x <= x1; ++x)
          for (const double half : {0.0, 0.5}) {  // the corner at (x, y), the centre beside it
            if (half > 0.0 && (x == x1 || y == y1)) continue;
            const Sign verdict = blocks.sign(plane, blocks.column_of(x), blocks.row_of(y));
            if (verdict == Sign::zero) {
              ++undecided;
              continue;
            }
            ++decided;
            bool ambiguous = false;
            const Vec3 d = shadowcert::pixel_ray(frame, x + half, y + half).direction;
            const Sign side = exact_side(d, n, delta, ambiguous);
            ASSERT_FALSE(ambiguous) << "trial " << trial << " plane " << p;
            ASSERT_EQ(side, verdict) << "trial " << trial << " plane " << p << " x " << x + half << " y " << y + half;
          }
    }
  }
  // The verdicts are not vacuous: many rays' blocks are decided, and many are not (the planes
  // cut the tiles, some a single block).
  EXPECT_GT(decided, 100'000u);
  EXPECT_GT(undecided, 100'000u);
}

// An 8-pixel tile of a 1024x768 image looking down -z, in blocks of 2: the plane x = 0 through
// the eye (normal (1, 0, 0)) cuts the tile at the image's middle column; the blocks left of
// that column are negative, those right of it positive, the block it crosses undecided.
TEST(EyeBlocks, VerticalPlaneThroughTheTile_DecidesTheBlocksBesideIt) {
  const Camera camera = looking_down(1024, 768);
  const CameraFrame frame = shadowcert::camera_frame(camera);
  const EyeBlocks blocks(frame, 509, 517, 100, 108, 2);  // columns [509, 511], [511, 513], ...
  ASSERT_EQ(blocks.columns(), 4u);
  ASSERT_EQ(blocks.rows(), 4u);
  const EyeBlocks::Plane plane = blocks.plane({1.0, 0.0, 0.0}, 0.0);
  for (std::uint32_t row = 0; row < 4; ++row) {
    EXPECT_EQ(blocks.sign(plane, 0, row), Sign::negative);
    EXPECT_EQ(blocks.sign(plane, 1, row), Sign::zero);  // holds x = 512, the plane's
    EXPECT_EQ(blocks.sign(plane, 2, row), Sign::positive);
    EXPECT_EQ(blocks.sign(plane, 3, row), Sign::positive);
  }
  // The block borders: a corner on one belongs to the later block, the last corner to the last.
  EXPECT_EQ(blocks.column_of(509), 0u);
  EXPECT_EQ(blocks.column_of(511), 1u);
  EXPECT_EQ(blocks.column_of(516), 3u);
  EXPECT_EQ(blocks.column_of(517), 3u);
  EXPECT_EQ(blocks.row_of(108), 3u);
}

// A normal whose terms overflow the margin's products, or one with an unbounded error: no
// block is decided.
TEST(EyeBlocks, HugeNormalOrUnboundedError_DecidesNothing) {
  const Camera camera = looking_down(64, 64);
  const EyeBlocks blocks(shadowcert::camera_frame(camera), 0, 8, 0, 8, 2);
  for (const auto& [n, error] : {std::pair{Vec3{1e308, -1e308, 1e308}, 0.0},
                                 std::pair{Vec3{1.0, 0.0, 0.0}, std::numeric_limits<double>::infinity()},
                                 std::pair{Vec3{1.0, 0.0, 0.0}, std::nan("")}}) {
    const EyeBlocks::Plane plane = blocks.plane(n, error);
    for (std::uint32_t row = 0; row < blocks.rows(); ++row)
      for (std::uint32_t column = 0; column < blocks.columns(); ++column)
        EXPECT_EQ(blocks.sign(plane, column, row), Sign::zero) << n[0] << " " << error;
  }
  // The same plane with a bounded error decides the tile's blocks (all left of x = 32).
  EXPECT_EQ(blocks.sign(blocks.plane({1.0, 0.0, 0.0}, 0.0), 0, 0), Sign::negative);
}

TEST(EyeBlocks, MoreBlocksThanAMaskHolds_MasksThrow) {
  const Camera camera = looking_down(64, 64);
  const EyeBlocks blocks(shadowcert::camera_frame(camera), 0, 12, 0, 12, 2);  // 36 blocks
  const EyeBlocks::Plane plane = blocks.plane({1.0, 0.0, 0.0}, 0.0);
  EXPECT_EQ(blocks.sign(plane, 0, 0), Sign::negative);
  EXPECT_THROW((void)blocks.blocks_on_side(plane, Sign::negative), std::logic_error);
  EXPECT_THROW((void)blocks.blocks_decided(plane), std::logic_error);
}

TEST(EyeBlocks, EmptyTileOrBlock_Throws) {
  const Camera camera = looking_down(64, 64);
  const CameraFrame frame = shadowcert::camera_frame(camera);
  EXPECT_THROW(EyeBlocks(frame, 4, 4, 0, 8, 2), std::invalid_argument);
  EXPECT_THROW(EyeBlocks(frame, 0, 8, 5, 3, 2), std::invalid_argument);
  EXPECT_THROW(EyeBlocks(frame, 0, 8, 0, 8, 0), std::invalid_argument);
}

}  // namespace
