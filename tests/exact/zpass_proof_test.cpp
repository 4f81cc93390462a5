// exact/zpass_proof.h: z-pass is proven for a light exactly when no face of the exact chain
// meets the frustum's tip (a touch counts) and n = 0 there. A slab floating over a floor, lit
// from above by a point and a directional light; the tip looks along -z, its near rectangle a
// dyadic 1/64 ahead with half side 1/128, so every coordinate is exact and survives an exact
// translation.
#include "exact/zpass_proof.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/pixel_ray.h"
#include "core/scene.h"
#include "io/soup_file.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_file.h"
#include "support/certificate_test_support.h"

namespace shadowcert {
namespace {

using test_support::append;
using test_support::directional_light;
using test_support::point_light;

constexpr double kNear = 1.0 / 64.0;
constexpr double kHalf = 1.0 / 128.0;

// The floor [-4, 4]^2 at y = 0 and the slab [-1, 1] x [2, 2.25] x [-1, 1].
Soup slab_over_floor() {
  Soup s = floor_quad(4.0);
  s.normals.clear();
  append(s, box({-1.0, 2.0, -1.0}, {1.0, 2.25, 1.0}));
  return s;
}

const Light kAbove = point_light(0.0, 8.0, 0.0);
const Light kStraightDown = directional_light(0.0, 1.0, 0.0);  // towards the light: up
const Light kSlanted = directional_light(1.0, 4.0, 0.5);

struct Tip {
  Vec3 apex;
  std::array<Vec3, 4> corners;
};

// The tip of a camera at `eye` looking along -z.
Tip tip_at(const Vec3& eye, double half = kHalf) {
  Tip t{eye, {}};
  const std::array<std::array<double, 2>, 4> signs{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
  for (std::size_t c = 0; c < 4; ++c) t.corners[c] = {eye[0] + signs[c][0] * half, eye[1] + signs[c][1] * half, eye[2] - kNear};
  return t;
}

struct Prepared {
  Soup soup;
  EdgeTable table;
};

Prepared prepare(const Soup& soup) {
  Prepared p{canonical_soup(soup).soup, {}};
  p.table = build_edge_table(p.soup);
  return p;
}

ZPassProof prove(const Prepared& p, const Light& light, const Tip& tip) {
  return prove_zpass(p.soup, p.table, light, tip.apex, tip.corners);
}

ZPassProof prove(const Soup& soup, const Light& light, const Tip& tip) { return prove(prepare(soup), light, tip); }

// ---- both outcomes, point light --------------------------------------------------------------

TEST(ZPassProof, CameraFarFromEveryVolume_IsProven) {
  const ZPassProof p = prove(slab_over_floor(), kAbove, tip_at({0.0, 3.0, 8.0}));
  EXPECT_EQ(p.verdict, ZPassVerdict::proven);
  EXPECT_TRUE(p.proven());
  EXPECT_EQ(p.apex_count, 0u);
  EXPECT_EQ(p.face_kind, ChainFace::none);
}

TEST(ZPassProof, CameraUnderTheSlab_IsInItsVolumeAndNotProven) {
  // The segment to the light crosses the slab's bottom and top: n(eye) = 2.
  const ZPassProof p = prove(slab_over_floor(), kAbove, tip_at({0.25, 1.0, -0.125}));
  EXPECT_EQ(p.verdict, ZPassVerdict::camera_in_volume);
  EXPECT_FALSE(p.proven());
  EXPECT_EQ(p.apex_count, 2u);
}

TEST(ZPassProof, FloorCapThroughTheTipWithNZero_IsNotProven) {
  // The eye 1/256 above the floor: its near rectangle reaches below y = 0, through the floor's
  // front cap, while n(eye) = 0.
  const ZPassProof p = prove(slab_over_floor(), kAbove, tip_at({0.0, 1.0 / 256.0, 3.0}));
  EXPECT_EQ(p.verdict, ZPassVerdict::face_meets_tip);
  EXPECT_EQ(p.apex_count, 0u);
  EXPECT_EQ(p.face_kind, ChainFace::front_cap);
}

TEST(ZPassProof, SideFaceThroughTheTipWithNZero_IsNotProven) {
  // The slab's shadow boundary below its top edge x = 1 is the plane 5.75 x = 8 - y: at y = 1,
  // x = 1.2173..., between the eye (x = 1.21875, outside the shadow: n = 0) and the near
  // rectangle's left side (x = 1.2109...).
  const ZPassProof p = prove(slab_over_floor(), kAbove, tip_at({1.21875, 1.0, 0.0}));
  EXPECT_EQ(p.verdict, ZPassVerdict::face_meets_tip);
  EXPECT_EQ(p.apex_count, 0u);
  EXPECT_EQ(p.face_kind, ChainFace::side);
  EXPECT_NE(p.multiplicity, 0);
  // The same eye with a tip narrow enough to stay outside the shadow is proven.
  EXPECT_EQ(prove(slab_over_floor(), kAbove, tip_at({1.21875, 1.0, 0.0}, 1.0 / 2048.0)).verdict, ZPassVerdict::proven);
}

TEST(ZPassProof, NearCornersTouchingTheFloor_CountAsMeeting) {
  // Apex at height 1/128: the two lower corners lie exactly in the floor's plane, on the floor.
  const ZPassProof p = prove(slab_over_floor(), kAbove, tip_at({0.5, kHalf, 3.0}));
  EXPECT_EQ(p.verdict, ZPassVerdict::face_meets_tip);
  EXPECT_EQ(p.face_kind, ChainFace::front_cap);
}

TEST(ZPassProof, EyeOnAShadowBoundary_HasNoCountAndIsNotProven) {
  // The eye exactly in the side plane 5.75 x = 8 - y (y = 2.25 - 5.75 * 0.25 = 0.8125 at
  // x = 1.25): its segment to the light grazes the slab's top edge, so n(eye) is undefined,
  // and the side face passes through the apex.
  const ZPassProof p = prove(slab_over_floor(), kAbove, tip_at({1.25, 0.8125, 0.0}));
  EXPECT_EQ(p.verdict, ZPassVerdict::face_meets_tip);
  EXPECT_EQ(p.apex_count, std::nullopt);
  EXPECT_EQ(p.face_kind, ChainFace::side);
}

// ---- directional lights ------------------------------------------------------------------------

TEST(ZPassProof, DirectionalLight_ProvenFarAwayAndNotInsideTheSlabsPrism) {
  for (const Light& light : {kStraightDown, kSlanted}) {
    SCOPED_TRACE(light.position[0]);
    EXPECT_EQ(prove(slab_over_floor(), light, tip_at({0.0, 3.0, 8.0})).verdict, ZPassVerdict::proven);
  }
  const ZPassProof inside = prove(slab_over_floor(), kStraightDown, tip_at({0.25, 1.0, -0.125}));
  EXPECT_EQ(inside.verdict, ZPassVerdict::camera_in_volume);
  EXPECT_EQ(inside.apex_count, 2u);
  // Straight under the slab's centre the ray up passes through the diagonals of its bottom and
  // top faces: n(eye) is undefined, the tip meets no face, and its probes count 2.
  const ZPassProof on_diagonal = prove(slab_over_floor(), kStraightDown, tip_at({0.0, 1.0, 0.0}));
  EXPECT_EQ(on_diagonal.verdict, ZPassVerdict::camera_in_volume);
  EXPECT_EQ(on_diagonal.apex_count, std::nullopt);
}

TEST(ZPassProof, DirectionalSideThroughTheTip_IsNotProven) {
  // Straight down, the slab's shadow is the prism |x|, |z| <= 1 below it: the plane x = 1 runs
  // between the eye (x = 1 + 1/256, n = 0) and the near rectangle's left side.
  const ZPassProof p = prove(slab_over_floor(), kStraightDown, tip_at({1.0 + 1.0 / 256.0, 1.0, 0.0}));
  EXPECT_EQ(p.verdict, ZPassVerdict::face_meets_tip);
  EXPECT_EQ(p.apex_count, 0u);
  EXPECT_EQ(p.face_kind, ChainFace::side);
}

// ---- invariance ----------------------------------------------------------------------------------

struct Case {
  std::string name;
  Light light;
  Vec3 eye;
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all{{"far", kAbove, {0.0, 3.0, 8.0}},
                                     {"inside", kAbove, {0.25, 1.0, -0.125}},
                                     {"floor cap", kAbove, {0.0, 1.0 / 256.0, 3.0}},
                                     {"side", kAbove, {1.21875, 1.0, 0.0}},
                                     {"touch", kAbove, {0.5, kHalf, 3.0}},
                                     {"directional far", kSlanted, {0.0, 3.0, 8.0}},
                                     {"directional inside", kStraightDown, {0.25, 1.0, -0.125}},
                                     {"directional side", kStraightDown, {1.0 + 1.0 / 256.0, 1.0, 0.0}}};
  return all;
}

// Vertices renumbered at random, triangles shuffled and each rotated: the canonical soup, and
// so every answer, is the same.
Soup relabelled(const Soup& soup, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint32_t> to(soup.vertices.size());
  std::iota(to.begin(), to.end(), 0u);
  std::shuffle(to.begin(), to.end(), rng);
  Soup out;
  out.vertices.resize(soup.vertices.size());
  for (std::size_t i = 0; i < to.size(); ++i) out.vertices[to[i]] = soup.vertices[i];
  for (const Triangle& t : soup.triangles) {
    const std::size_t r = rng() % 3;
    out.triangles.push_back({to[t[r]], to[t[(r + 1) % 3]], to[t[(r + 2) % 3]]});
  }
  std::shuffle(out.triangles.begin(), out.triangles.end(), rng);
  return out;
}

TEST(ZPassProof, Relabelling_KeepsEveryAnswer) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const ZPassProof expected = prove(slab_over_floor(), c.light, tip_at(c.eye));
    for (std::uint32_t seed = 1; seed <= 3; ++seed) {
      const ZPassProof p = prove(relabelled(slab_over_floor(), seed), c.light, tip_at(c.eye));
      EXPECT_EQ(p.verdict, expected.verdict);
      EXPECT_EQ(p.apex_count, expected.apex_count);
      EXPECT_EQ(p.face_kind, expected.face_kind);
    }
  }
}

TEST(ZPassProof, ExactTranslation_KeepsEveryAnswer) {
  const Vec3 by{1024.0, -512.0, 256.0};  // every coordinate here stays exact
  const auto moved = [&by](Vec3 p) {
    for (std::size_t k = 0; k < 3; ++k) p[k] += by[k];
    return p;
  };
  Soup soup = slab_over_floor();
  for (Vec3& v : soup.vertices) v = moved(v);
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const ZPassProof expected = prove(slab_over_floor(), c.light, tip_at(c.eye));
    Light light = c.light;
    if (!light.directional())
      for (std::size_t k = 0; k < 3; ++k) light.position[k] += by[k];
    const ZPassProof p = prove(soup, light, tip_at(moved(c.eye)));
    EXPECT_EQ(p.verdict, expected.verdict);
    EXPECT_EQ(p.apex_count, expected.apex_count);
    EXPECT_EQ(p.face_kind, expected.face_kind);
  }
}

// ---- the bundled scenes -------------------------------------------------------------------------

// A tip of `camera`'s frame (core/pixel_ray.h) at near distance 0.01, in doubles.
Tip camera_tip(const Camera& camera) {
  const CameraFrame f = camera_frame(camera);
  Tip t{f.eye, {}};
  const std::array<std::array<double, 2>, 4> signs{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
  for (std::size_t c = 0; c < 4; ++c)
    for (std::size_t k = 0; k < 3; ++k)
      t.corners[c][k] = f.eye[k] + 0.01 * (f.forward[k] + signs[c][0] * f.half_width * f.right[k] +
                                           signs[c][1] * f.half_height * f.up[k]);
  return t;
}

Scene load(const std::string& relative) {
  return load_scene(std::filesystem::path(SHADOWCERT_SOURCE_DIR) / relative,
                    [](const std::filesystem::path& f) { return read_soup(f); });
}

TEST(ZPassProof, CameraInsideVolumeHardScene_BothLightsCountTwoAtTheEye) {
  const Scene scene = load("data/scenes/hard/camera_inside_volume.json");
  const Prepared p = prepare(merged_soup(scene));
  ASSERT_EQ(scene.lights.size(), 2u);
  for (const Light& light : scene.lights) {
    const ZPassProof proof = prove(p, light, camera_tip(scene.camera));
    EXPECT_EQ(proof.verdict, ZPassVerdict::camera_in_volume);
    EXPECT_EQ(proof.apex_count, 2u);
  }
}

TEST(ZPassProof, DefaultScene_IsProven) {
  const Scene scene = load("data/scenes/default.json");
  const Prepared p = prepare(merged_soup(scene));
  EXPECT_EQ(prove(p, scene.lights.at(0), camera_tip(scene.camera)).verdict, ZPassVerdict::proven);
}

// ---- misuse ---------------------------------------------------------------------------------------

TEST(ZPassProof, DegenerateTipOrBadLight_Throws) {
  const Prepared p = prepare(slab_over_floor());
  Tip flat = tip_at({0.0, 3.0, 8.0});
  flat.corners[2] = flat.corners[0];  // (apex, c0, c1, c2) has no volume
  EXPECT_THROW((void)prove(p, kAbove, flat), std::invalid_argument);
  Tip crossed = tip_at({0.0, 3.0, 8.0});
  std::swap(crossed.corners[1], crossed.corners[2]);  // not cyclic: the two tetrahedra disagree
  EXPECT_THROW((void)prove(p, kAbove, crossed), std::invalid_argument);
  EXPECT_THROW((void)prove(p, directional_light(0.0, 0.0, 0.0), tip_at({0.0, 3.0, 8.0})), std::invalid_argument);
  Tip infinite = tip_at({0.0, 3.0, 8.0});
  infinite.apex[0] = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)prove(p, kAbove, infinite), std::invalid_argument);
  EXPECT_THROW((void)prove_zpass(p.soup, EdgeTable{}, kAbove, {0.0, 3.0, 8.0}, tip_at({0.0, 3.0, 8.0}).corners),
               std::invalid_argument);
}

TEST(ZPassProof, VerdictNames) {
  EXPECT_EQ(zpass_verdict_name(ZPassVerdict::proven), "proven");
  EXPECT_EQ(zpass_verdict_name(ZPassVerdict::camera_in_volume), "camera_in_volume");
  EXPECT_EQ(zpass_verdict_name(ZPassVerdict::face_meets_tip), "face_meets_tip");
  EXPECT_EQ(zpass_verdict_name(ZPassVerdict::count_undefined), "count_undefined");
}

}  // namespace
}  // namespace shadowcert
