// eye_tile_cone (reference/detail/eye_tile.h): every point of the scene box that a ray of the
// tile meets, and every such point of a pixel's eye pyramid in the tile, lies in one of the
// cone's dilated segments; the cone is not much wider than the tile's rays; and it declines
// where its bound does not hold.
#include "reference/detail/eye_tile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace {

using shadowcert::Camera;
using shadowcert::CameraFrame;
using shadowcert::Vec3;
using shadowcert::detail::DilatedSegment;
using shadowcert::detail::eye_tile_cone;
using shadowcert::detail::EyeTileCone;
using Point = std::array<long double, 3>;

// Whether p lies within piece.slack (per axis) of a point of the segment piece.from -> to:
// the parameters where each axis is within its slack, intersected (long double: its
// rounding, about 2^-64 relative, is far below the cone's margins of 2^-49).
bool in_piece(const Point& p, const DilatedSegment& piece) {
  long double lo = 0.0L, hi = 1.0L;
  for (int k = 0; k < 3; ++k) {
    const long double from = piece.from[k], step = static_cast<long double>(piece.to[k]) - from;
    const long double below = p[k] - piece.slack[k] - from, above = p[k] + piece.slack[k] - from;
    if (step == 0.0L) {
      if (below > 0.0L || above < 0.0L) return false;
      continue;
    }
    long double a = below / step, b = above / step;
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  }
  return lo <= hi;
}

bool in_cone(const Point& p, const EyeTileCone& cone) {
  return std::any_of(cone.begin(), cone.end(), [&](const DilatedSegment& piece) { return in_piece(p, piece); });
}

bool in_box(const Point& p, const Vec3& lo, const Vec3& hi) {
  for (int k = 0; k < 3; ++k)
    if (p[k] < lo[k] || p[k] > hi[k]) return false;
  return true;
}

// The ray's point at parameter t, in long double.
Point at(const shadowcert::PixelRay& ray, long double t) {
  return {ray.origin[0] + t * ray.direction[0], ray.origin[1] + t * ray.direction[1],
          ray.origin[2] + t * ray.direction[2]};
}

// A camera with eye and target in [-extent, extent]^3, a vertical field of view in
// [5, 5 + fov_spread] degrees and 16 to 2015 pixels a side.
Camera random_camera(std::mt19937_64& rng, double extent, double fov_spread) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), coordinate(-extent, extent);
  Camera camera;
  camera.eye = {coordinate(rng), coordinate(rng), coordinate(rng)};
  camera.target = {coordinate(rng), coordinate(rng), coordinate(rng)};
  camera.fov_y_degrees = 5.0 + fov_spread * unit(rng);
  camera.width = 16 + static_cast<std::uint32_t>(2000 * unit(rng));
  camera.height = 16 + static_cast<std::uint32_t>(2000 * unit(rng));
  return camera;
}

TEST(EyeTile, RandomTilesRaysAndPyramids_LieInTheCone) {
  const unsigned seed = 20261206;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t inside = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Camera camera = random_camera(rng, 50.0, 150.0);
    const CameraFrame frame = shadowcert::camera_frame(camera);
    // A tile of up to 16 pixels on a side anywhere in the image; the box around the target.
    const double size = 1.0 + 15.0 * std::floor(unit(rng) * 2.0);
    const double x0 = std::floor(unit(rng) * (camera.width - size)), y0 = std::floor(unit(rng) * (camera.height - size));
    const double x1 = x0 + size, y1 = y0 + size;
    Vec3 lo{}, hi{};
    for (int k = 0; k < 3; ++k) {
      lo[k] = camera.target[k] - 40.0 * unit(rng);
      hi[k] = camera.target[k] + 40.0 * unit(rng);
    }
    const std::optional<EyeTileCone> cone = eye_tile_cone(frame, x0, x1, y0, y1, lo, hi);
    double distance = 0.0;  // from the eye to the target: the box lies within about twice that
    for (int k = 0; k < 3; ++k) distance += (camera.target[k] - camera.eye[k]) * (camera.target[k] - camera.eye[k]);
    distance = std::sqrt(distance);
    ASSERT_TRUE(cone.has_value()) << "trial " << trial;
    for (int sample = 0; sample < 200; ++sample) {
      // The tile's corners, its pixel centres, and points between.
      const double x = sample < 4 ? (sample % 2 == 0 ? x0 : x1) : sample < 40 ? x0 + 0.5 + std::floor(unit(rng) * size) : x0 + size * unit(rng);
      const double y = sample < 4 ? (sample / 2 == 0 ? y0 : y1) : sample < 40 ? y0 + 0.5 + std::floor(unit(rng) * size) : y0 + size * unit(rng);
      const shadowcert::PixelRay ray = shadowcert::pixel_ray(frame, x, y);
      // Parameters up to beyond the box (|direction| >= 1).
      const long double t = (2.0L * distance + 80.0L) * unit(rng);
      const Point p = at(ray, t);
      if (!in_box(p, lo, hi)) continue;
      ++inside;
      ASSERT_TRUE(in_cone(p, *cone)) << "trial " << trial << " sample " << sample << " x " << x << " y " << y << " t "
                                     << static_cast<double>(t);
    }
    // The eye pyramid of a pixel of the tile: convex combinations of its four corner rays.
    const double px = x0 + std::floor(unit(rng) * size), py = y0 + std::floor(unit(rng) * size);
    const std::array<shadowcert::PixelRay, 4> corners{
        shadowcert::pixel_ray(frame, px, py), shadowcert::pixel_ray(frame, px + 1, py),
        shadowcert::pixel_ray(frame, px + 1, py + 1), shadowcert::pixel_ray(frame, px, py + 1)};
    for (int sample = 0; sample < 100; ++sample) {
      std::array<long double, 4> w{};
      long double sum = 0.0L;
      for (long double& v : w) sum += v = unit(rng);
      const long double t = (2.0L * distance + 80.0L) * unit(rng);
      Point p{};
      for (int k = 0; k < 3; ++k) {
        p[k] = frame.eye[k];
        for (std::size_t j = 0; j < 4; ++j) p[k] += t * w[j] / sum * corners[j].direction[k];
      }
      if (!in_box(p, lo, hi)) continue;
      ++inside;
      ASSERT_TRUE(in_cone(p, *cone)) << "trial " << trial << " pyramid sample " << sample;
    }
  }
  EXPECT_GT(inside, 10'000u);  // the samples did reach the boxes
}

// An 8-pixel tile of a 1024x768 image: at its far end the cone is as wide as the tile's rays
// spread there (the slack of the far piece within 1.2x of the spread of the tile's corner rays
// at that parameter), so a tile lists few triangles.
TEST(EyeTile, EightPixelTile_IsAsNarrowAsItsRays) {
  Camera camera;
  camera.eye = {0.0, 2.0, 5.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.width = 1024;
  camera.height = 768;
  const CameraFrame frame = shadowcert::camera_frame(camera);
  const Vec3 lo{-2.0, -1.0, -2.0}, hi{2.0, 1.0, 2.0};
  const std::optional<EyeTileCone> cone = eye_tile_cone(frame, 512.0, 520.0, 384.0, 392.0, lo, hi);
  ASSERT_TRUE(cone.has_value());
  const DilatedSegment& far = cone->back();
  // The far end's parameter along the middle direction: |to - eye| / |c|, c ~ forward (unit).
  double far_t = 0.0;
  for (int k = 0; k < 3; ++k) far_t += (far.to[k] - frame.eye[k]) * frame.forward[k];
  const shadowcert::PixelRay a = shadowcert::pixel_ray(frame, 512.0, 384.0), b = shadowcert::pixel_ray(frame, 520.0, 392.0);
  for (int k = 0; k < 3; ++k) {
    const double spread = far_t * std::fabs(a.direction[k] - b.direction[k]) / 2.0;
    EXPECT_LE(far.slack[k], 1.2 * spread + 1e-12) << "axis " << k;
    EXPECT_GE(far.slack[k], spread) << "axis " << k;
  }
}

// eye_tile_direction_bound bounds every ray direction of the tile per axis (the per-tile sign
// filters of exact_image.cpp rest on it), and not by much more than the largest of them.
TEST(EyeTile, DirectionBound_HoldsEveryRayOfTheTile) {
  const unsigned seed = 20261207;
  std::printf("seed %u\n", seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const Camera camera = random_camera(rng, 1e3, 170.0);
    const CameraFrame frame = shadowcert::camera_frame(camera);
    const double size = 8.0;
    const double x0 = std::floor(unit(rng) * (camera.width - size)), y0 = std::floor(unit(rng) * (camera.height - size));
    const Vec3 w = shadowcert::detail::eye_tile_direction_bound(frame, x0, x0 + size, y0, y0 + size);
    Vec3 largest{};
    for (int sample = 0; sample < 100; ++sample) {
      const double x = sample < 4 ? x0 + size * (sample % 2) : x0 + size * unit(rng);
      const double y = sample < 4 ? y0 + size * (sample / 2) : y0 + size * unit(rng);
      const shadowcert::PixelRay ray = shadowcert::pixel_ray(frame, x, y);
      for (int k = 0; k < 3; ++k) {
        ASSERT_LE(std::fabs(ray.direction[k]), w[k]) << "trial " << trial << " axis " << k;
        largest[k] = std::max(largest[k], std::fabs(ray.direction[k]));
      }
    }
    // Not loose: within the sum of the three terms' magnitudes, which at most a few times the
    // largest direction component over the unit frame vectors (|f|, |r|, |u| = 1).
    const double norm = std::sqrt(largest[0] * largest[0] + largest[1] * largest[1] + largest[2] * largest[2]);
    for (int k = 0; k < 3; ++k) EXPECT_LE(w[k], 3.0 * norm + 1e-12) << "trial " << trial << " axis " << k;
  }
}

TEST(EyeTile, WideFieldOrUntameInput_DeclinesTheCone) {
  Camera camera;
  camera.eye = {0.0, 0.0, 5.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.width = 64;
  camera.height = 64;
  const Vec3 lo{-1.0, -1.0, -1.0}, hi{1.0, 1.0, 1.0};
  EXPECT_TRUE(eye_tile_cone(shadowcert::camera_frame(camera), 0.0, 8.0, 0.0, 8.0, lo, hi).has_value());
  camera.fov_y_degrees = 179.99;  // the image plane's edge about 11,000 units from its axis
  EXPECT_FALSE(eye_tile_cone(shadowcert::camera_frame(camera), 0.0, 8.0, 0.0, 8.0, lo, hi).has_value());
  camera.fov_y_degrees = 60.0;
  const CameraFrame frame = shadowcert::camera_frame(camera);
  EXPECT_FALSE(eye_tile_cone(frame, 0.0, 8.0, 0.0, 8.0, lo, {1.0, std::nan(""), 1.0}).has_value());
  EXPECT_FALSE(eye_tile_cone(frame, 0.0, 8.0, 0.0, 8.0, lo, {1.0, 0x1p500, 1.0}).has_value());
  EXPECT_FALSE(eye_tile_cone(frame, 8.0, 0.0, 0.0, 8.0, lo, hi).has_value());  // x0 > x1
}

}  // namespace
