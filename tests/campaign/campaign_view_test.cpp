// campaign/campaign_view.h: the view `fuzz --gl` renders each case in. Undoing the case's frame is
// exact (re-framing gives the case back bit for bit, and every exact light side is unchanged);
// the camera sees every vertex of the soup inside the image, in front of the near plane; the
// floor lies under the soup and is exact in float.
#include "campaign/campaign_view.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "core/pixel_ray.h"
#include "exact/light_orientation.h"

namespace {

using namespace shadowcert;

constexpr std::uint64_t kSeed = 20240612;
constexpr std::uint64_t kCases = 400;
constexpr std::uint32_t kTriangles = 40;
// The near plane of a unit scene (core/camera.h); a fitted one (core/near_plane.h) is at most
// half the distance to the nearest triangle, so a vertex beyond this one is never clipped.
constexpr double kNearPlane = kDefaultNearPlane;

double reframed(double x, const SoupFrame& frame) { return std::ldexp(x, frame.scale_exponent) + frame.offset; }

// Where `p` lands in image coordinates (x right, y down), and its depth along the view.
struct Projected {
  double x = 0.0, y = 0.0, depth = 0.0;
};
Projected project(const CameraFrame& f, const Vec3& p) {
  const Vec3 v{p[0] - f.eye[0], p[1] - f.eye[1], p[2] - f.eye[2]};
  const double depth = dot(v, f.forward);
  const double a = dot(v, f.right) / depth, b = dot(v, f.up) / depth;
  return {(a / f.half_width + 1.0) * 0.5 * f.width, (1.0 - b / f.half_height) * 0.5 * f.height, depth};
}

}  // namespace

TEST(CampaignView, Unframed_ReframesBitForBitAndKeepsEveryExactLightSide) {
  std::uint64_t framed_cases = 0, kept_frames = 0;
  for (std::uint64_t i = 0; i < kCases; ++i) {
    SCOPED_TRACE("seed " + std::to_string(kSeed) + ", case " + std::to_string(i));
    const CampaignCase c = campaign_case(kSeed, i, kTriangles);
    const SoupFrame& frame = c.kind.frame;
    const bool framed = frame.scale_exponent != 0 || frame.offset != 0.0;
    framed_cases += framed ? 1 : 0;
    const CampaignView view = campaign_view(c, 64, 48);
    EXPECT_EQ(view.unframed, framed && unframes_exactly(c));
    if (!view.unframed) {
      // As generated: only where the map would round (a subnormal light coordinate).
      kept_frames += framed ? 1 : 0;
      EXPECT_EQ(view.soup.vertices, c.soup.vertices);
      EXPECT_EQ(view.light.position, c.light.position);
      continue;
    }
    const Soup& soup = view.soup;
    const Light& light = view.light;
    ASSERT_EQ(soup.triangles, c.soup.triangles);
    for (std::size_t v = 0; v < soup.vertices.size(); ++v)
      for (int k = 0; k < 3; ++k) ASSERT_EQ(reframed(soup.vertices[v][k], frame), c.soup.vertices[v][k]) << v;
    if (c.light.directional()) {
      EXPECT_EQ(light.position, c.light.position);
    } else {
      for (int k = 0; k < 3; ++k) ASSERT_EQ(reframed(light.position[k], frame), c.light.position[k]);
      EXPECT_EQ(light.position[3], 1.0);
    }
    for (const Triangle& t : soup.triangles)
      ASSERT_EQ(light_orientation(soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]], light),
                light_orientation(c.soup.vertices[t[0]], c.soup.vertices[t[1]], c.soup.vertices[t[2]], c.light));
  }
  EXPECT_GT(framed_cases, kCases / 4);  // the scaled and offset frames are exercised
  EXPECT_LT(kept_frames * 50, framed_cases) << kept_frames << " of " << framed_cases << " frames kept";
  EXPECT_GE(kept_frames, 1u);  // this seed has one (case 286): the fallback is exercised
}

TEST(CampaignView, Camera_SeesEveryVertexInsideTheImageBeyondTheNearPlane) {
  for (std::uint64_t i = 0; i < kCases; ++i) {
    SCOPED_TRACE("seed " + std::to_string(kSeed) + ", case " + std::to_string(i));
    const CampaignView view = campaign_view(campaign_case(kSeed, i, kTriangles), 64, 48);
    EXPECT_EQ(view.camera.width, 64u);
    EXPECT_EQ(view.camera.height, 48u);
    const CameraFrame f = camera_frame(view.camera);
    for (const Triangle& t : view.soup.triangles)
      for (const std::uint32_t index : t) {
        const Projected p = project(f, view.soup.vertices[index]);
        ASSERT_GT(p.depth, kNearPlane);
        ASSERT_GE(p.x, 0.0);
        ASSERT_LE(p.x, 64.0);
        ASSERT_GE(p.y, 0.0);
        ASSERT_LE(p.y, 48.0);
      }
  }
}

TEST(CampaignView, Floor_UnderTheSoupFacingUpExactInFloat) {
  for (std::uint64_t i = 0; i < kCases; ++i) {
    SCOPED_TRACE("seed " + std::to_string(kSeed) + ", case " + std::to_string(i));
    const CampaignView view = campaign_view(campaign_case(kSeed, i, kTriangles), 64, 48);
    ASSERT_EQ(view.floor.triangles.size(), 2u);
    const double y = view.floor.vertices[0][1];
    for (const Vec3& v : view.floor.vertices) {
      EXPECT_EQ(v[1], y);
      for (const double x : v) EXPECT_EQ(static_cast<double>(static_cast<float>(x)), x);
    }
    for (const Triangle& t : view.soup.triangles)
      for (const std::uint32_t index : t) EXPECT_LT(y, view.soup.vertices[index][1]);
    // Facing +y: the light (0, +inf) side; seen from above, counter-clockwise.
    for (const Triangle& t : view.floor.triangles)
      EXPECT_EQ(light_orientation(view.floor.vertices[t[0]], view.floor.vertices[t[1]], view.floor.vertices[t[2]],
                                  Light{{0.0, 1.0, 0.0, 0.0}}),
                Sign::positive);
  }
}

TEST(CampaignView, Camera_DependsOnTheUsedVerticesOnly) {
  Soup soup;
  soup.vertices = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  soup.triangles = {{0, 1, 2}};
  Soup with_unused = soup;
  with_unused.vertices.push_back({1e9, 1e9, 1e9});
  const Camera a = campaign_view_camera(soup, 32, 24), b = campaign_view_camera(with_unused, 32, 24);
  EXPECT_EQ(a.eye, b.eye);
  EXPECT_EQ(a.target, b.target);
  EXPECT_THROW((void)campaign_view_camera(soup, 0, 24), std::invalid_argument);
}
