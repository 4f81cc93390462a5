// campaign/random_soup.h: the campaign's cases are a function of (seed, index) alone, have exactly
// the triangles asked for, cover every family and light placement, and the adversarial lights
// are EXACTLY where they claim (checked with the exact predicate, docs/definitions.md#orientation).
#include "campaign/random_soup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <set>

#include "exact/face_crossing.h"
#include "exact/light_orientation.h"
#include "campaign/campaign_view.h"
#include "support/bit_digest.h"

namespace {

using namespace shadowcert;

constexpr std::uint64_t kSeed = 20240611;

bool same_case(const CampaignCase& a, const CampaignCase& b) {
  return a.soup.vertices == b.soup.vertices && a.soup.triangles == b.soup.triangles &&
         a.light.position == b.light.position && a.kind.family == b.kind.family && a.kind.light == b.kind.light &&
         a.target == b.target && a.corner == b.corner;
}

const Vec3& corner(const CampaignCase& c, int k) { return c.soup.vertices[c.soup.triangles[c.target][(c.corner + k) % 3]]; }

// p, q, r on one line (r may be a direction): they span no plane.
bool collinear(const Vec3& p, const Vec3& q, const HomogeneousPoint& r) {
  return detail::spans_no_plane(finite_point(p), finite_point(q), r);
}

// x differs from y in exactly one coordinate, by exactly one ulp.
bool one_ulp_apart(const std::array<double, 4>& x, const std::array<double, 4>& y) {
  int moved = 0;
  for (int k = 0; k < 4; ++k) {
    if (x[k] == y[k]) continue;
    ++moved;
    if (x[k] != std::nextafter(y[k], x[k])) return false;
  }
  return moved == 1;
}

TEST(RandomSoup, SameSeedAndIndex_SameCaseOnEveryCall) {
  std::cout << "seed " << kSeed << "\n";
  for (std::uint64_t i = 0; i < 50; ++i)
    EXPECT_TRUE(same_case(campaign_case(kSeed, i, 100), campaign_case(kSeed, i, 100))) << i;
  // Cases do not depend on the order they are made in: index 7 alone equals index 7 after others.
  const CampaignCase alone = campaign_case(kSeed, 7, 60);
  for (std::uint64_t i = 0; i < 7; ++i) (void)campaign_case(kSeed, i, 60);
  EXPECT_TRUE(same_case(alone, campaign_case(kSeed, 7, 60)));
}

TEST(RandomSoup, OtherSeedOrIndex_OtherCase) {
  int different_seed = 0, different_index = 0;
  for (std::uint64_t i = 0; i < 20; ++i) {
    different_seed += !same_case(campaign_case(kSeed, i, 50), campaign_case(kSeed + 1, i, 50));
    different_index += !same_case(campaign_case(kSeed, i, 50), campaign_case(kSeed, i + 1, 50));
  }
  EXPECT_EQ(different_seed, 20);
  EXPECT_EQ(different_index, 20);
}

TEST(RandomSoup, EveryCase_ExactTriangleCountValidIndicesFiniteCoordinatesNoNormals) {
  std::cout << "seed " << kSeed << "\n";
  for (const std::uint32_t k : {1u, 2u, 7u, 100u, 333u}) {
    for (std::uint64_t i = 0; i < 60; ++i) {
      const CampaignCase c = campaign_case(kSeed, i, k);
      ASSERT_EQ(c.soup.triangles.size(), k) << "case " << i;
      EXPECT_TRUE(c.soup.normals.empty());
      for (const Triangle& t : c.soup.triangles)
        for (std::uint32_t v : t) ASSERT_LT(v, c.soup.vertices.size()) << "case " << i;
      for (const Vec3& p : c.soup.vertices)
        for (double x : p) ASSERT_TRUE(std::isfinite(x)) << "case " << i;
      for (double x : c.light.position) ASSERT_TRUE(std::isfinite(x));
      const double w = c.light.position[3];
      EXPECT_TRUE(w == 0.0 || w == 1.0);
      if (w == 0.0) {
        EXPECT_FALSE(c.light.position[0] == 0.0 && c.light.position[1] == 0.0 && c.light.position[2] == 0.0);
      }
    }
  }
}

TEST(RandomSoup, ManyCases_CoverEveryFamilyPlacementAndFrame) {
  std::set<SoupFamily> families;
  std::set<LightPlacement> placements;
  bool offset = false, small = false, large = false;
  for (std::uint64_t i = 0; i < 400; ++i) {
    const CampaignCaseKind k = draw_case_kind(kSeed, i);
    families.insert(k.family);
    placements.insert(k.light);
    EXPECT_GE(k.frame.scale_exponent, -20);
    EXPECT_LE(k.frame.scale_exponent, 20);
    EXPECT_TRUE(k.frame.offset == 0.0 || k.frame.offset == 1e6);
    offset |= k.frame.offset == 1e6;
    small |= k.frame.scale_exponent <= -15;
    large |= k.frame.scale_exponent >= 15;
  }
  EXPECT_EQ(families.size(), kSoupFamilies);
  EXPECT_EQ(placements.size(), kLightPlacements);
  EXPECT_TRUE(offset && small && large);
}

// Every adversarial placement on every family, in every frame: the light is exactly on the
// plane, on the edge line, at the vertex, parallel to the plane; the off_* ones one ulp away.
TEST(RandomSoup, AdversarialLights_ExactlyWhereTheyClaim) {
  std::cout << "seed " << kSeed << "\n";
  const std::array<SoupFrame, 4> frames{{{0, 0.0}, {-20, 0.0}, {20, 0.0}, {-10, 1e6}}};
  int placed = 0;
  std::uint64_t index = 0;
  for (std::size_t f = 0; f < kSoupFamilies; ++f) {
    for (std::size_t p = 2; p < kLightPlacements; ++p) {  // the adversarial ones
      for (const SoupFrame& frame : frames) {
        for (int repeat = 0; repeat < 6; ++repeat) {
          const CampaignCaseKind kind{static_cast<SoupFamily>(f), static_cast<LightPlacement>(p), frame};
          const CampaignCase c = make_campaign_case(kSeed, index++, 40, kind);
          SCOPED_TRACE(std::string(family_name(kind.family)) + " / " + std::string(placement_name(kind.light)) +
                       ", case " + std::to_string(index - 1));
          if (c.target == kNoTarget) {  // no usable triangle: it says so, and fell back
            EXPECT_TRUE(c.kind.light == LightPlacement::point || c.kind.light == LightPlacement::directional);
            continue;
          }
          ++placed;
          EXPECT_EQ(c.kind.light, kind.light);
          const Light& on = c.unmoved;
          const Sign plane = light_orientation(corner(c, 0), corner(c, 1), corner(c, 2), on);
          switch (kind.light) {
            case LightPlacement::on_plane:
            case LightPlacement::off_plane:
            case LightPlacement::directional_parallel:
            case LightPlacement::directional_parallel_off:
              EXPECT_EQ(plane, Sign::zero);
              break;
            case LightPlacement::on_edge_line:
            case LightPlacement::off_edge_line:
              EXPECT_TRUE(collinear(corner(c, 0), corner(c, 1), on.position));
              EXPECT_EQ(plane, Sign::zero);
              break;
            case LightPlacement::at_vertex:
            case LightPlacement::off_vertex:
              EXPECT_EQ((Vec3{on.position[0], on.position[1], on.position[2]}), corner(c, 0));
              break;
            case LightPlacement::point:
            case LightPlacement::directional:
              break;
          }
          const bool moved = kind.light == LightPlacement::off_plane || kind.light == LightPlacement::off_edge_line ||
                             kind.light == LightPlacement::off_vertex ||
                             kind.light == LightPlacement::directional_parallel_off;
          if (moved)
            EXPECT_TRUE(one_ulp_apart(c.light.position, on.position));
          else
            EXPECT_EQ(c.light.position, on.position);
          const bool directional = kind.light == LightPlacement::directional_parallel ||
                                   kind.light == LightPlacement::directional_parallel_off;
          EXPECT_EQ(c.light.position[3], directional ? 0.0 : 1.0);
        }
      }
    }
  }
  EXPECT_GT(placed, 500);
}

// On the plane means off the edge lines (the combinations avoid them): exactly on a line is
// its own placement.
TEST(RandomSoup, OnPlane_NotOnTheTargetsEdgeLines) {
  int checked = 0;
  for (std::uint64_t i = 0; i < 200; ++i) {
    const CampaignCase c = make_campaign_case(kSeed, i, 30, {SoupFamily::uniform, LightPlacement::on_plane, {}});
    if (c.target == kNoTarget) continue;
    for (int k = 0; k < 3; ++k) EXPECT_FALSE(collinear(corner(c, k), corner(c, k + 1), c.light.position)) << i;
    ++checked;
  }
  EXPECT_GT(checked, 150);
}

// Grid families stay on the grid in every frame: coordinates are integers times 2^e plus the
// offset, exactly; so are their point lights.
TEST(RandomSoup, GridFamilies_ExactGridCoordinatesInEveryFrame) {
  for (const SoupFamily family : {SoupFamily::grid, SoupFamily::snapped}) {
    for (const SoupFrame frame : {SoupFrame{0, 0.0}, SoupFrame{-20, 0.0}, SoupFrame{7, 0.0}, SoupFrame{-20, 1e6}}) {
      for (std::uint64_t i = 0; i < 20; ++i) {
        const CampaignCase c = make_campaign_case(kSeed, i, 50, {family, LightPlacement::point, frame});
        auto on_grid = [&](double x) {
          const double unit = std::ldexp(x - frame.offset, -frame.scale_exponent);
          return unit == std::round(unit) && std::fabs(unit) <= 16.0;
        };
        for (const Vec3& p : c.soup.vertices)
          for (double x : p) ASSERT_TRUE(on_grid(x)) << family_name(family) << " case " << i << ": " << x;
        for (int k = 0; k < 3; ++k) EXPECT_TRUE(on_grid(c.light.position[k]));
      }
    }
  }
}

TEST(RandomSoup, BadArguments_Throw) {
  EXPECT_THROW((void)campaign_case(kSeed, 0, 0), std::invalid_argument);
  EXPECT_THROW((void)make_campaign_case(kSeed, 0, 10, {SoupFamily::mesh, LightPlacement::point, {21, 0.0}}),
               std::invalid_argument);
  EXPECT_THROW((void)make_campaign_case(kSeed, 0, 10, {SoupFamily::mesh, LightPlacement::point, {0, 5.0}}),
               std::invalid_argument);
}

TEST(RandomSoup, Names_OnePerFamilyAndPlacement) {
  std::set<std::string_view> names;
  for (std::size_t f = 0; f < kSoupFamilies; ++f) names.insert(family_name(static_cast<SoupFamily>(f)));
  for (std::size_t p = 0; p < kLightPlacements; ++p) names.insert(placement_name(static_cast<LightPlacement>(p)));
  EXPECT_EQ(names.size(), kSoupFamilies + kLightPlacements);
}

// A seed's cases are the same bits on every machine: soups, lights, the campaign view's floor,
// camera and the camera's pixel-ray frame, pinned. These come from core/portable_math.h, not
// libm, whose sin/cos/pow differ by CPU (CI's exact-image digests of these very cases did).
// Also run with glibc's FMA variants off (tests/CMakeLists.txt: inputs_same_without_fma).
TEST(CampaignCase, SeedsOneAndSeven_SameOnEveryMachine) {
  test::BitDigest digest;
  for (std::uint64_t seed : {1u, 7u})
    for (std::uint64_t index = 0; index < 40; ++index) {
      const CampaignCase c = campaign_case(seed, index, 24);
      digest.add(c.soup);
      digest.add(c.light);
      const CampaignView view = campaign_view(c, 48, 36);
      digest.add(view.soup);
      digest.add(view.floor);
      digest.add(view.light);
      digest.add(view.camera);
    }
  EXPECT_EQ(digest.hex(), "8b3f0e737e8182cc");
}

}  // namespace
