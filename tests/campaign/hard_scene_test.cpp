// The hard-soup scenes of `fuzz --gl --gl-scenes hard` (campaign/hard_scene.h), GL-free: each is
// a function of (seed, index, size); it holds 3 to 5 distinct parts over a floor in y = 0 that
// lies under all of them, and every part of the seven is drawn; the first light is a point light
// above the floor close to a part, or exactly (exact/light_orientation.h) in the plane of a
// part's triangle; the camera sees every vertex of the parts inside the image beyond its fitted
// near plane, or looks along a side face's plane at the floor from within 1e-4 of it.
#include "campaign/hard_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>

#include "core/near_plane.h"
#include "core/pixel_ray.h"
#include "core/vector3.h"
#include "exact/light_orientation.h"
#include "scene/merged_soup.h"
#include "support/bit_digest.h"

namespace shadowcert {
namespace {

constexpr std::uint64_t kSeed = 5;
constexpr std::uint64_t kScenes = 60;
constexpr std::uint32_t kWidth = 1024, kHeight = 768;

bool same_soup(const Soup& a, const Soup& b) { return a.vertices == b.vertices && a.triangles == b.triangles; }

bool same_scene(const Scene& a, const Scene& b) {
  if (a.meshes.size() != b.meshes.size() || a.lights.size() != b.lights.size()) return false;
  for (std::size_t m = 0; m < a.meshes.size(); ++m)
    if (a.meshes[m].name != b.meshes[m].name || !same_soup(a.meshes[m].soup, b.meshes[m].soup)) return false;
  for (std::size_t k = 0; k < a.lights.size(); ++k)
    if (a.lights[k].position != b.lights[k].position) return false;
  return a.camera.eye == b.camera.eye && a.camera.target == b.camera.target &&
         a.camera.near_plane == b.camera.near_plane && a.camera.width == b.camera.width;
}

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

TEST(HardScene, SameSeedIndexAndSize_SameSceneElseAnother) {
  const HardSceneCase a = hard_scene_case(kSeed, 3, kWidth, kHeight);
  EXPECT_TRUE(same_scene(a.scene, hard_scene_case(kSeed, 3, kWidth, kHeight).scene));
  EXPECT_EQ(a.parts, hard_scene_case(kSeed, 3, kWidth, kHeight).parts);
  EXPECT_FALSE(same_scene(a.scene, hard_scene_case(kSeed, 4, kWidth, kHeight).scene));
  EXPECT_FALSE(same_scene(a.scene, hard_scene_case(kSeed + 1, 3, kWidth, kHeight).scene));
  // The size is the camera's alone.
  const HardSceneCase small = hard_scene_case(kSeed, 3, 64, 48);
  EXPECT_EQ(small.scene.camera.width, 64u);
  EXPECT_EQ(small.scene.camera.height, 48u);
  for (std::size_t m = 0; m < a.scene.meshes.size(); ++m)
    EXPECT_TRUE(same_soup(a.scene.meshes[m].soup, small.scene.meshes[m].soup));
  EXPECT_THROW((void)hard_scene_case(kSeed, 3, 0, 48), std::invalid_argument);
}

TEST(HardScene, EveryScene_PartsOverTheFloorALightCloseToOneAndAllInView) {
  std::array<std::uint64_t, kHardParts> drawn{};
  std::set<std::size_t> light_counts;
  std::size_t on_plane = 0, edge_on = 0;
  for (std::uint64_t i = 0; i < kScenes; ++i) {
    SCOPED_TRACE("seed " + std::to_string(kSeed) + ", scene " + std::to_string(i));
    const HardSceneCase h = hard_scene_case(kSeed, i, kWidth, kHeight);
    const Scene& s = h.scene;
    ASSERT_GE(h.parts.size(), 3u);
    ASSERT_LE(h.parts.size(), 5u);
    ASSERT_EQ(s.meshes.size(), h.parts.size() + 1);
    EXPECT_EQ(std::set<HardPart>(h.parts.begin(), h.parts.end()).size(), h.parts.size());  // distinct
    EXPECT_EQ(s.meshes[0].name, "floor");
    for (const Vec3& v : s.meshes[0].soup.vertices) EXPECT_EQ(v[1], 0.0);
    double reach = 0.0;
    const CameraFrame f = camera_frame(s.camera);
    for (std::size_t m = 1; m < s.meshes.size(); ++m) {
      EXPECT_EQ(s.meshes[m].name, hard_part_name(h.parts[m - 1]));
      ++drawn[static_cast<std::size_t>(h.parts[m - 1])];
      ASSERT_FALSE(s.meshes[m].soup.triangles.empty());
      for (const Vec3& v : s.meshes[m].soup.vertices) {
        ASSERT_TRUE(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]));
        EXPECT_GE(v[1], 0.0);  // on or above the floor
        reach = std::max({reach, std::fabs(v[0]), std::fabs(v[2])});
        if (h.edge_on_view) continue;  // it looks at a side face on the floor, not at the parts
        const Projected p = project(f, v);
        ASSERT_GT(p.depth, s.camera.near_plane);
        ASSERT_GE(p.x, 0.0);
        ASSERT_LE(p.x, double{kWidth});
        ASSERT_GE(p.y, 0.0);
        ASSERT_LE(p.y, double{kHeight});
      }
    }
    EXPECT_GE(s.meshes[0].soup.vertices[0][0] * s.meshes[0].soup.vertices[0][0], reach * reach);  // wider
    EXPECT_EQ(s.camera.near_plane, camera_fitted_to(s).near_plane);
    // The first light: a point above the floor within two radii of a part's box centre.
    ASSERT_GE(s.lights.size(), 1u);
    ASSERT_LE(s.lights.size(), 3u);
    light_counts.insert(s.lights.size());
    const auto& l = s.lights[0].position;
    EXPECT_EQ(l[3], 1.0);
    EXPECT_GT(l[1], 0.0);
    bool close = false;
    for (std::size_t m = 1; m < s.meshes.size(); ++m) {
      Vec3 lo = s.meshes[m].soup.vertices[0], hi = lo;
      for (const Vec3& v : s.meshes[m].soup.vertices)
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], v[k]);
          hi[k] = std::max(hi[k], v[k]);
        }
      double d2 = 0.0, r2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double c = 0.5 * (lo[k] + hi[k]);
        d2 += (l[k] - c) * (l[k] - c);
        r2 += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
      }
      close = close || d2 <= 4.0 * std::max(r2, 1.0);
    }
    EXPECT_TRUE(close || h.first_light_on_plane);
    if (h.edge_on_view) {
      // The eye within 1e-4 (relative to its distance from the light) of the plane through the
      // light and an edge of a part, at a floor point of that plane, above the floor.
      ++edge_on;
      const Vec3 light_point{s.lights[0].position[0], s.lights[0].position[1], s.lights[0].position[2]};
      const Vec3 e = difference(s.camera.eye, light_point);
      bool near_a_plane = false;
      for (std::size_t m = 1; m < s.meshes.size() && !near_a_plane; ++m)
        for (const Triangle& t : s.meshes[m].soup.triangles)
          for (int k = 0; k < 3 && !near_a_plane; ++k) {
            const Vec3 n = cross(difference(s.meshes[m].soup.vertices[t[k]], light_point),
                                 difference(s.meshes[m].soup.vertices[t[(k + 1) % 3]], light_point));
            const double nn = std::sqrt(dot(n, n));
            near_a_plane = nn > 0.0 && std::fabs(dot(e, n)) / nn <= 1.001e-4 * std::sqrt(dot(e, e)) &&
                           std::fabs(dot(difference(s.camera.target, light_point), n)) / nn <= 1e-9 * std::sqrt(dot(e, e));
          }
      EXPECT_TRUE(near_a_plane);
      EXPECT_GT(s.camera.eye[1], 0.0);
      EXPECT_EQ(s.camera.target[1], 0.0);
    }
    if (h.first_light_on_plane) {
      // Exactly in the plane of some triangle of a part that spans one.
      ++on_plane;
      bool in_a_plane = false;
      for (std::size_t m = 1; m < s.meshes.size() && !in_a_plane; ++m)
        for (const Triangle& t : s.meshes[m].soup.triangles) {
          const Vec3 &a = s.meshes[m].soup.vertices[t[0]], &b = s.meshes[m].soup.vertices[t[1]],
                     &c = s.meshes[m].soup.vertices[t[2]];
          const Vec3 n = cross(difference(b, a), difference(c, a));  // nonzero in double: not collinear
          if ((n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0) && light_orientation(a, b, c, s.lights[0]) == Sign::zero) {
            in_a_plane = true;
            break;
          }
        }
      EXPECT_TRUE(in_a_plane);
    }
  }
  for (std::size_t p = 0; p < kHardParts; ++p) EXPECT_GT(drawn[p], 0u) << hard_part_name(static_cast<HardPart>(p));
  EXPECT_GT(on_plane, 0u);
  EXPECT_GT(edge_on, 0u);
  EXPECT_EQ(light_counts.size(), 3u);  // one, two and three lights all occur
}

// A seed's hard scenes are the same bits on every machine (core/portable_math.h, not libm):
// soups, lights, camera and its pixel-ray frame, pinned; also run with glibc's FMA variants off.
TEST(HardScene, SeedThree_SameOnEveryMachine) {
  test::BitDigest digest;
  for (std::uint64_t index = 0; index < 12; ++index) {
    const HardSceneCase hard = hard_scene_case(3, index, 128, 96);
    digest.add(merged_soup(hard.scene));
    for (const Light& light : hard.scene.lights) digest.add(light);
    digest.add(hard.scene.camera);
  }
  EXPECT_EQ(digest.hex(), "5cdd1bc60ddf9a25");
}

}  // namespace
}  // namespace shadowcert
