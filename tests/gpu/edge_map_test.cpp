// gpu/edge_map.h and gpu/g_buffer.h: each filter, run through its real shader pass, on
// hand-built G-buffers with known answers (a flat image, a step in depth, a crease in normals,
// a surface against the background), the thresholds that name those answers, and the G-buffer
// pass on geometry whose normals and depths are known.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/soup.h"
#include "gpu/edge_map.h"
#include "gpu/g_buffer.h"
#include "gpu/stencil_shadow_renderer.h"
#include "support/gl_test_support.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;

constexpr std::uint32_t kWidth = 16;
constexpr std::uint32_t kHeight = 12;
// What float arithmetic leaves of an exact answer in the filter shaders: a few float ulps of
// values in [0, 1] (dot products of unit normals, squares, sums of nine taps), plus the
// normals' own rounding when the test builds them with cos and sin.
constexpr double kShaderRounding = 1e-5;
// A unit normal's dot product with itself in float is 1 within a few ulps: the inner intensity
// a flat normal field can show.
constexpr double kUnitNormalRounding = 1e-6;

std::string name(EdgeFilter f) { return std::string(edge_filter_name(f)); }

// A G-buffer texel: unit normal and normalised depth (covered), or the uncovered value.
std::array<float, 4> texel(const std::array<double, 3>& n, double depth) {
  return {static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]), static_cast<float>(depth)};
}
constexpr std::array<float, 4> kUncovered{kUncoveredNormal[0], kUncoveredNormal[1], kUncoveredNormal[2],
                                          kBackgroundDepth};

// Builds a kWidth x kHeight G-buffer from `at(x, row)` (row 0 at the top), filters it, reads it.
template <class At>
EdgeMapImage filtered(EdgeFilter filter, At at, const EdgeMapOptions& options = {}) {
  std::vector<float> rgba;
  for (std::uint32_t row = 0; row < kHeight; ++row)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::array<float, 4> t = at(x, row);
      rgba.insert(rgba.end(), t.begin(), t.end());
    }
  const GBuffer g_buffer(kWidth, kHeight);
  g_buffer.upload(rgba);
  const EdgeMap map(kWidth, kHeight);
  const EdgeMapFilter pass;
  pass.apply(g_buffer, map, filter, options);
  EdgeMapImage image = map.read();
  EXPECT_EQ(image.width, kWidth);
  EXPECT_EQ(image.height, kHeight);
  return image;
}

constexpr std::array<double, 3> kFacing{0.0, 0.0, 1.0};

using EdgeMapFilterTest = GlTest;

TEST_F(EdgeMapFilterTest, FlatImage_NoEdges) {
  for (EdgeFilter filter : kEdgeFilters) {
    SCOPED_TRACE(name(filter));
    const EdgeMapImage map = filtered(filter, [](std::uint32_t, std::uint32_t) { return texel(kFacing, 0.5); });
    for (std::size_t i = 0; i < map.profile.size(); ++i) {
      EXPECT_EQ(map.profile[i], 0.0f) << "pixel " << i;
      EXPECT_LE(map.inner[i], kUnitNormalRounding) << "pixel " << i;
      EXPECT_EQ(map.covered[i], 1);
    }
    const EdgePixelCounts counts = count_edge_pixels(map, profile_threshold(filter, kDefaultEdgeDepthStep),
                                                     inner_threshold(filter, kDefaultEdgeCreaseAngleDegrees));
    EXPECT_EQ(counts.profile, 0u);
    EXPECT_EQ(counts.inner, 0u);
    EXPECT_EQ(counts.covered, std::uint64_t{kWidth} * kHeight);
  }
}

TEST_F(EdgeMapFilterTest, EmptyImage_NoEdgesNothingCovered) {
  for (EdgeFilter filter : kEdgeFilters) {
    SCOPED_TRACE(name(filter));
    const EdgeMapImage map = filtered(filter, [](std::uint32_t, std::uint32_t) { return kUncovered; });
    for (std::size_t i = 0; i < map.profile.size(); ++i) {
      EXPECT_EQ(map.profile[i], 0.0f);
      EXPECT_EQ(map.inner[i], 0.0f);
      EXPECT_EQ(map.covered[i], 0);
    }
  }
}

// A step of height s between columns 7 and 8 (vertical) or rows 5 and 6 (horizontal): the two
// pixels beside it, on either side, answer profile_threshold(filter, s) exactly; every other
// pixel 0; no inner edge (the normals are equal).
TEST_F(EdgeMapFilterTest, DepthStep_BothSidesAnswerTheStepsThreshold_NothingElse) {
  for (EdgeFilter filter : kEdgeFilters)
    for (const double step : {0.02, 0.1, 0.5})
      for (const bool vertical : {true, false}) {
        SCOPED_TRACE(name(filter) + ", step " + std::to_string(step) + (vertical ? ", vertical" : ", horizontal"));
        const auto far_side = [&](std::uint32_t x, std::uint32_t row) { return vertical ? x >= 8 : row >= 6; };
        const EdgeMapImage map = filtered(filter, [&](std::uint32_t x, std::uint32_t row) {
          return texel(kFacing, 0.25 + (far_side(x, row) ? step : 0.0));
        });
        for (std::uint32_t row = 0; row < kHeight; ++row)
          for (std::uint32_t x = 0; x < kWidth; ++x) {
            const bool beside = vertical ? (x == 7 || x == 8) : (row == 5 || row == 6);
            const std::size_t i = map.index(x, row);
            if (beside)
              EXPECT_NEAR(map.profile[i], profile_threshold(filter, step), kShaderRounding) << x << ", " << row;
            else
              EXPECT_EQ(map.profile[i], 0.0f) << x << ", " << row;
            EXPECT_LE(map.inner[i], kUnitNormalRounding) << x << ", " << row;
          }
      }
}

// Normals that differ by `angle` across the line between columns 7 and 8, one depth: the two
// pixels beside the crease answer inner_threshold(filter, angle); no profile edge anywhere.
TEST_F(EdgeMapFilterTest, NormalCrease_BothSidesAnswerTheAnglesThreshold_NoProfile) {
  for (EdgeFilter filter : kEdgeFilters)
    for (const double degrees : {20.0, 30.0, 90.0, 135.0}) {
      SCOPED_TRACE(name(filter) + ", crease " + std::to_string(degrees));
      const double half = degrees / 2.0 * std::numbers::pi / 180.0;
      const std::array<double, 3> left{-std::sin(half), 0.0, std::cos(half)}, right{std::sin(half), 0.0, std::cos(half)};
      const EdgeMapImage map = filtered(filter, [&](std::uint32_t x, std::uint32_t) {
        return texel(x >= 8 ? right : left, 0.5);
      });
      for (std::uint32_t row = 0; row < kHeight; ++row)
        for (std::uint32_t x = 0; x < kWidth; ++x) {
          const std::size_t i = map.index(x, row);
          EXPECT_EQ(map.profile[i], 0.0f) << x << ", " << row;
          if (x == 7 || x == 8)
            EXPECT_NEAR(map.inner[i], inner_threshold(filter, degrees), kShaderRounding) << x << ", " << row;
          else
            EXPECT_LE(map.inner[i], kUnitNormalRounding) << x << ", " << row;
        }
    }
}

// --crease-angle's meaning: with the threshold of 30 degrees, a 40-degree crease is an edge
// and a 20-degree one is not, for every filter.
TEST_F(EdgeMapFilterTest, CreaseAngleThreshold_SeparatesSharperFromFlatterCreases) {
  for (EdgeFilter filter : kEdgeFilters) {
    SCOPED_TRACE(name(filter));
    const double threshold = inner_threshold(filter, 30.0);
    for (const double degrees : {20.0, 40.0}) {
      const double half = degrees / 2.0 * std::numbers::pi / 180.0;
      const EdgeMapImage map = filtered(filter, [&](std::uint32_t x, std::uint32_t) {
        return texel({(x >= 8 ? 1.0 : -1.0) * std::sin(half), 0.0, std::cos(half)}, 0.5);
      });
      const EdgePixelCounts counts = count_edge_pixels(map, 1.0, threshold);
      EXPECT_EQ(counts.inner, degrees > 30.0 ? 2u * kHeight : 0u) << degrees << " degrees";
    }
  }
}

// A covered 6 x 4 block in an empty frame: its boundary is a full step (the background lies at
// infinity), reported as profile only; no inner edge; coverage as built.
TEST_F(EdgeMapFilterTest, SurfaceAgainstBackground_FullProfileStep_NoInnerEdge) {
  const auto inside = [](std::uint32_t x, std::uint32_t row) { return x >= 5 && x < 11 && row >= 4 && row < 8; };
  for (EdgeFilter filter : kEdgeFilters) {
    SCOPED_TRACE(name(filter));
    const EdgeMapImage map = filtered(filter, [&](std::uint32_t x, std::uint32_t row) {
      return inside(x, row) ? texel(kFacing, 0.9) : kUncovered;
    });
    for (std::uint32_t row = 0; row < kHeight; ++row)
      for (std::uint32_t x = 0; x < kWidth; ++x) {
        const std::size_t i = map.index(x, row);
        EXPECT_EQ(map.covered[i], inside(x, row) ? 1 : 0);
        EXPECT_LE(map.inner[i], kUnitNormalRounding) << x << ", " << row;
      }
    // Mid-side pixels of the block's left boundary see the step axis-aligned: a full step of 1.
    for (const std::uint32_t x : {4u, 5u})
      EXPECT_NEAR(map.profile[map.index(x, 6)], profile_threshold(filter, 1.0), kShaderRounding) << x;
    EXPECT_EQ(map.profile[map.index(0, 0)], 0.0f);
    EXPECT_EQ(map.profile[map.index(8, 6)], 0.0f) << "inside, away from the boundary";
  }
}

// The paper's three passes added by blending give the one pass's sums, up to the order of the
// float additions.
TEST_F(EdgeMapFilterTest, C1ThreePasses_EqualOnePass) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<std::array<float, 4>> texels;
  for (std::uint32_t i = 0; i < kWidth * kHeight; ++i) {
    if (unit(random) > 0.7) {
      texels.push_back(kUncovered);
      continue;
    }
    std::array<double, 3> n{unit(random), unit(random), std::abs(unit(random)) + 0.1};
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& c : n) c /= length;
    texels.push_back(texel(n, 0.5 + 0.5 * unit(random)));
  }
  const auto at = [&](std::uint32_t x, std::uint32_t row) { return texels[row * kWidth + x]; };
  const EdgeMapImage one = filtered(EdgeFilter::c1, at);
  const EdgeMapImage three = filtered(EdgeFilter::c1, at, EdgeMapOptions{true});
  for (std::size_t i = 0; i < one.profile.size(); ++i) {
    EXPECT_NEAR(one.profile[i], three.profile[i], kShaderRounding) << i;
    EXPECT_NEAR(one.inner[i], three.inner[i], kShaderRounding) << i;
    EXPECT_EQ(one.covered[i], three.covered[i]) << i;
  }
}

TEST_F(EdgeMapFilterTest, SizeMismatch_Throws) {
  const GBuffer g_buffer(8, 8);
  const EdgeMap map(8, 4);
  const EdgeMapFilter pass;
  EXPECT_THROW(pass.apply(g_buffer, map, EdgeFilter::diagonal), std::invalid_argument);
  EXPECT_THROW(g_buffer.upload(std::vector<float>(3)), std::invalid_argument);
}

TEST(EdgeFilterNames, RoundTrip_UnknownIsNullopt) {
  for (EdgeFilter f : kEdgeFilters) EXPECT_EQ(parse_edge_filter(edge_filter_name(f)), f);
  EXPECT_EQ(parse_edge_filter("Sobel"), std::nullopt);
  EXPECT_EQ(parse_edge_filter(""), std::nullopt);
}

TEST(EdgeThresholds, KnownValues_AndRangeChecks) {
  EXPECT_DOUBLE_EQ(profile_threshold(EdgeFilter::diagonal, 1.0), 1.0 - 1.0 / 16.0);
  EXPECT_DOUBLE_EQ(profile_threshold(EdgeFilter::c1, 0.3), 0.1);
  EXPECT_DOUBLE_EQ(profile_threshold(EdgeFilter::sobel, 0.3), 0.3);
  EXPECT_NEAR(inner_threshold(EdgeFilter::diagonal, 90.0), 0.5, 1e-15);
  EXPECT_NEAR(inner_threshold(EdgeFilter::c1, 180.0), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(inner_threshold(EdgeFilter::sobel, 60.0), 0.5, 1e-15);
  for (EdgeFilter f : kEdgeFilters) {
    EXPECT_EQ(profile_threshold(f, 0.0), 0.0);
    EXPECT_EQ(inner_threshold(f, 0.0), 0.0);
    EXPECT_THROW((void)profile_threshold(f, 1.5), std::invalid_argument);
    EXPECT_THROW((void)profile_threshold(f, -0.1), std::invalid_argument);
    EXPECT_THROW((void)inner_threshold(f, 181.0), std::invalid_argument);
    EXPECT_THROW((void)inner_threshold(f, std::nan("")), std::invalid_argument);
  }
}

TEST(FittedDepthRange, BoxCornersAlongTheViewAxis_NearClampedToTheCameraNearPlane) {
  Camera camera;
  camera.eye = {0.0, 0.0, 10.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.near_plane = 0.5;
  const SceneBounds bounds{{-1.0, -2.0, -3.0}, {1.0, 2.0, 4.0}};
  DepthRange range = fitted_depth_range(camera, bounds);
  EXPECT_DOUBLE_EQ(range.near, 6.0);
  EXPECT_DOUBLE_EQ(range.far, 13.0);
  camera.eye = {0.0, 0.0, 3.0};  // inside the box: the near plane bounds it
  range = fitted_depth_range(camera, bounds);
  EXPECT_DOUBLE_EQ(range.near, 0.5);
  EXPECT_DOUBLE_EQ(range.far, 6.0);
  camera.eye = {0.0, 0.0, -10.0};  // the box behind the camera: far = near + 1
  camera.target = {0.0, 0.0, -20.0};
  range = fitted_depth_range(camera, bounds);
  EXPECT_DOUBLE_EQ(range.far, range.near + 1.0);
}

// Two squares facing the eye at z = 0 (wound one way) and z = -2 (the other way), seen from
// (0, 0, 5) down -z: eye-space normals (0, 0, 1) on both (turned towards the eye whatever the
// winding), depths 0 and 1 (the range is fitted to the bounds, view depths 5 to 7).
using GBufferTest = GlTest;

TEST_F(GBufferTest, FacingSquares_NormalsTowardsTheEye_DepthsNormalisedToTheBounds) {
  Soup soup;
  soup.vertices = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {-4, -4, -2}, {4, -4, -2}, {4, 4, -2}, {-4, 4, -2}};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 7, 6}};
  Camera camera;
  camera.eye = {0.0, 0.0, 5.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.fov_y_degrees = 90.0;
  camera.width = 32;
  camera.height = 32;
  camera.near_plane = 0.1;
  const std::array parts{ShadedSoupPart{&soup}};
  EdgeMapRenderer renderer(parts);
  const DepthRange range = renderer.depth_range(camera);
  EXPECT_DOUBLE_EQ(range.near, 5.0);
  EXPECT_DOUBLE_EQ(range.far, 7.0);
  renderer.draw(camera.width, camera.height, camera, EdgeFilter::diagonal);
  const std::vector<float> g = renderer.g_buffer().read();
  // A pixel spans 10/32 world units at z = 0 and 14/32 at z = -2: pixel (16, 16)'s centre ray
  // meets the near square at 0.16 off the axis, (8, 8)'s the far square at (-3.3, 3.3), (24, 20)'s
  // it at (3.7, -2.0) (beside the near square's shadow from the eye), (1, 1)'s nothing (6.3).
  const auto at = [&](std::uint32_t x, std::uint32_t row) { return &g[(std::size_t{row} * camera.width + x) * 4]; };
  for (const auto& [x, row, depth] : {std::tuple{16u, 16u, 0.0}, std::tuple{8u, 8u, 1.0}, std::tuple{24u, 20u, 1.0}}) {
    const float* t = at(x, row);
    EXPECT_NEAR(t[0], 0.0, kShaderRounding);
    EXPECT_NEAR(t[1], 0.0, kShaderRounding);
    EXPECT_NEAR(t[2], 1.0, kShaderRounding);
    EXPECT_NEAR(t[3], depth, kShaderRounding) << x << ", " << row;
  }
  const float* empty = at(1, 1);
  EXPECT_EQ(empty[0], 0.0f);
  EXPECT_EQ(empty[3], kBackgroundDepth);
}

// A tilted plane's eye-space normal, from the face normal and from vertex normals that point
// the other way (a soup's normals need not agree with its winding): both turned towards the eye.
TEST_F(GBufferTest, TiltedPlane_EyeSpaceNormal_FromFaceOrFlippedVertexNormals) {
  const double c = std::cos(std::numbers::pi / 6.0), s = std::sin(std::numbers::pi / 6.0);
  // The plane through the origin with normal (s, 0, c): 30 degrees about y.
  Soup soup;
  soup.vertices = {{-c, -1, s}, {c, -1, -s}, {c, 1, -s}, {-c, 1, s}};
  soup.triangles = {{0, 1, 2}, {0, 2, 3}};
  Camera camera;
  camera.eye = {0.0, 0.0, 5.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.fov_y_degrees = 30.0;
  camera.width = 16;
  camera.height = 16;
  for (const bool vertex_normals : {false, true}) {
    SCOPED_TRACE(vertex_normals ? "vertex normals pointing away" : "face normals");
    Soup drawn = soup;
    if (vertex_normals) drawn.normals.assign(4, {static_cast<float>(-s), 0.0f, static_cast<float>(-c)});
    const std::array parts{ShadedSoupPart{&drawn}};
    EdgeMapRenderer renderer(parts);
    renderer.draw(camera.width, camera.height, camera, EdgeFilter::sobel);
    const std::vector<float> g = renderer.g_buffer().read();
    const float* t = &g[(8 * 16 + 8) * 4];
    EXPECT_NEAR(t[0], s, kShaderRounding);
    EXPECT_NEAR(t[1], 0.0, kShaderRounding);
    EXPECT_NEAR(t[2], c, kShaderRounding);
  }
}

TEST_F(GBufferTest, NoTriangle_Throws) {
  const Soup empty;
  const std::array parts{ShadedSoupPart{&empty}};
  EXPECT_THROW(EdgeMapRenderer{parts}, std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert::gpu
