// pipeline/scene_smoothies.h (GL-free): the silhouette edges chosen exactly and the smoothies
// built on them.
//  1. On a closed box (an oriented manifold) the edges are the face-pair silhouette: one face
//     lit, the other not, for every light tried.
//  2. Smoothies lie outside the caster's shadow, never inwards (Chen & Tsai §2.2): on a box and
//     an icosphere (convex), for 150 lights each (a third directional), world and light space,
//     every point of every smoothie triangle (linking triangles included) away from the edge
//     itself sees the light past the caster.
//  3. Linked corners: on those convex casters every silhouette vertex joins exactly two
//     smoothies and is linked, none is shrunk (a convex caster's outline is convex).
//  4. A soup's non-manifold edge with m != 0 is kept, with every face on its occluders' side
//     (the public smoothie code drops such edges).
//  5. scene_smoothies: the default width, one mesh per light, bad widths.
#include "pipeline/scene_smoothies.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/float_rounding.h"
#include "core/vector3.h"
#include "exact/edge_multiplicity.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/procedural_mesh.h"

namespace shadowcert {
namespace {

Vec3 minus(const Vec3& a, const Vec3& b) { return difference(a, b); }
Vec3 plus_scaled(const Vec3& a, double s, const Vec3& b) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }

struct Caster {
  Soup soup;  // canonical, float-rounded (dyadic generators: unchanged)
  EdgeTable table;
};

Caster caster_of(const Soup& soup) {
  Caster c;
  c.soup = float_rounded(canonical_soup(soup).soup);
  c.table = build_edge_table(c.soup);
  return c;
}

// Whether the segment from p towards the light (to l, or along l for a directional light, far
// beyond the caster) meets the convex caster's interior shrunk by `margin` (Cyrus-Beck against
// every face plane, outward normals).
bool segment_hits_convex(const Soup& convex, const Vec3& p, const Light& light, double margin) {
  const Vec3 l{light.position[0], light.position[1], light.position[2]};
  const Vec3 d = light.directional() ? Vec3{1e6 * l[0], 1e6 * l[1], 1e6 * l[2]} : minus(l, p);
  double enter = 0.0, leave = 1.0;
  for (const Triangle& t : convex.triangles) {
    const Vec3& a = convex.vertices[t[0]];
    Vec3 n = cross(minus(convex.vertices[t[1]], a), minus(convex.vertices[t[2]], a));
    const double length = std::sqrt(dot(n, n));
    n = {n[0] / length, n[1] / length, n[2] / length};
    // Inside: (x - a) . n < -margin.
    const double start = dot(minus(p, a), n) + margin;
    const double rate = dot(d, n);
    if (rate == 0.0) {
      if (start >= 0.0) return false;
      continue;
    }
    const double t_plane = -start / rate;
    if (rate < 0.0) enter = std::max(enter, t_plane);
    else leave = std::min(leave, t_plane);
    if (enter >= leave) return false;
  }
  return enter < leave;
}

Light random_light(std::mt19937_64& random, bool directional) {
  std::normal_distribution<double> normal;
  Vec3 d{normal(random), normal(random), normal(random)};
  const double length = std::sqrt(dot(d, d));
  const double distance = directional ? 1.0 : std::uniform_real_distribution<double>(2.5, 8.0)(random);
  Light light;
  for (int k = 0; k < 3; ++k) light.position[k] = float_rounded(distance * d[k] / length);
  light.position[3] = directional ? 0.0 : 1.0;
  return light;
}

// The lit faces of a closed, outward-oriented caster: the exact light side s(t) > 0.
std::set<std::pair<std::uint32_t, std::uint32_t>> face_pair_silhouette(const Caster& c, const Light& light) {
  const EdgeMultiplicities m = exact_multiplicities(c.soup, c.table, light);
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::size_t e = 0; e < c.table.size(); ++e) {
    const std::uint32_t first = c.table.first_opposite[e];
    EXPECT_EQ(c.table.first_opposite[e + 1] - first, 2u) << "a closed manifold has two faces per edge";
    const bool lit0 = m.triangle_sign[c.table.opposite_triangle[first]] == Sign::positive;
    const bool lit1 = m.triangle_sign[c.table.opposite_triangle[first + 1]] == Sign::positive;
    if (lit0 != lit1) edges.insert({c.table.edges[e][0], c.table.edges[e][1]});
  }
  return edges;
}

TEST(SceneSmoothies, Box_EdgesAreTheFacePairSilhouette) {
  const Caster box = caster_of(shadowcert::box({-1.0, -0.5, -0.75}, {1.0, 0.5, 0.75}));
  std::mt19937_64 random(7);
  for (int i = 0; i < 100; ++i) {
    const Light light = random_light(random, i % 3 == 0);
    const SmoothieEdges edges = smoothie_edges(box.soup, box.table, light);
    std::set<std::pair<std::uint32_t, std::uint32_t>> got;
    for (const auto& [u, v] : edges.edges) got.insert({u, v});
    EXPECT_EQ(got, face_pair_silhouette(box, light)) << "light " << i;
    for (std::size_t e = 0; e < edges.edges.size(); ++e)
      EXPECT_EQ(edges.first_face[e + 1] - edges.first_face[e], 2u) << "both faces of a manifold edge";
  }
}

TEST(SceneSmoothies, ConvexCasters_SmoothiesLieOutsideTheShadow_CornersLinked) {
  // Every interior point of a smoothie triangle at least this alpha away from its edge: points on
  // the edge itself touch the caster.
  constexpr double kMinAlpha = 0.02;
  // The caster is shrunk by this (world units) for the hit test: it absorbs the double rounding
  // of the points and planes (about 1e-15 here), far below the smallest clearance of a sampled
  // point (kMinAlpha * width * kMinBisectorOutwardCosine = 1e-4).
  constexpr double kMargin = 1e-9;
  std::mt19937_64 random(11);
  for (const Soup& soup : {shadowcert::box({-1.0, -0.5, -0.75}, {1.0, 0.5, 0.75}), icosphere({0.0, 0.0, 0.0}, 1.0, 1)}) {
    const Caster c = caster_of(soup);
    for (SmoothieSpace space : {SmoothieSpace::world, SmoothieSpace::light}) {
      for (int i = 0; i < 150; ++i) {
        const Light light = random_light(random, i % 3 == 0);
        SCOPED_TRACE("light " + std::to_string(i) + ", " + std::string(smoothie_space_name(space)));
        SmoothieOptions options;
        options.width = 0.1;
        options.space = space;
        options.reference_distance = 4.0;
        const SmoothieEdges edges = smoothie_edges(c.soup, c.table, light);
        const Smoothies s = build_smoothies(c.soup.vertices, edges, light, options);
        ASSERT_GT(s.stats.smoothies, 2u);
        // A convex caster's silhouette is one convex loop: every vertex on it joins two
        // smoothies and is linked.
        std::set<std::uint32_t> loop_vertices;
        for (const auto& [u, v] : edges.edges) loop_vertices.insert({u, v});
        EXPECT_EQ(s.stats.linked_corners, loop_vertices.size());
        EXPECT_EQ(s.stats.shrunk_corners, 0u);
        for (const auto& t : s.mesh.triangles) {
          for (int a = 0; a <= 10; ++a) {
            for (int b = 0; a + b <= 10; ++b) {
              const double wa = a / 10.0, wb = b / 10.0, wc = 1.0 - wa - wb;
              const double alpha = wa * s.mesh.alpha[t[0]] + wb * s.mesh.alpha[t[1]] + wc * s.mesh.alpha[t[2]];
              if (alpha < kMinAlpha) continue;
              Vec3 p{0.0, 0.0, 0.0};
              p = plus_scaled(p, wa, s.mesh.vertices[t[0]]);
              p = plus_scaled(p, wb, s.mesh.vertices[t[1]]);
              p = plus_scaled(p, wc, s.mesh.vertices[t[2]]);
              ASSERT_FALSE(segment_hits_convex(c.soup, p, light, kMargin))
                  << "a smoothie point (" << p[0] << ", " << p[1] << ", " << p[2] << ") at alpha " << alpha
                  << " is in the caster's shadow";
            }
          }
        }
      }
    }
  }
}

TEST(SceneSmoothies, NonManifoldSoupEdge_KeptWithItsOccluderFaces) {
  // nonmanifold_fan(k): k triangles on the edge (0,0,0)-(0,1,0), alternate ones flipped. From a
  // light far out along +x, blades on both sides of the side plane: m is the imbalance.
  const Caster fan = caster_of(nonmanifold_fan(5));
  const Light light{{10.0, 0.5, 0.25, 1.0}};
  const EdgeMultiplicities m = exact_multiplicities(fan.soup, fan.table, light);
  const std::vector<Sign> signs =
      edge_entry_signs(MultiplicityMethod::exact, fan.soup, fan.table, light, Precision::float64);
  const SmoothieEdges edges = smoothie_edges(fan.soup, fan.table, light);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> index;
  for (std::size_t e = 0; e < edges.edges.size(); ++e) index[{edges.edges[e][0], edges.edges[e][1]}] = e;
  std::size_t hinges = 0;
  for (std::size_t e = 0; e < fan.table.size(); ++e) {
    const std::pair<std::uint32_t, std::uint32_t> key{fan.table.edges[e][0], fan.table.edges[e][1]};
    EXPECT_EQ(index.count(key) == 1, m.multiplicity[e] != 0) << "edge " << key.first << "-" << key.second;
    if (m.multiplicity[e] == 0 || fan.table.first_opposite[e + 1] - fan.table.first_opposite[e] < 3) continue;
    ++hinges;
    const std::size_t s = index[key];
    const int side = edges.occluder_side[s];
    EXPECT_EQ(side, m.multiplicity[e] > 0 ? -1 : 1);  // the majority: -sign(m)
    std::size_t on_side = 0;
    for (std::uint32_t k = fan.table.first_opposite[e]; k < fan.table.first_opposite[e + 1]; ++k)
      on_side += to_int(signs[k]) == side ? 1 : 0;
    EXPECT_EQ(edges.first_face[s + 1] - edges.first_face[s], on_side);
  }
  EXPECT_EQ(hinges, 1u) << "the hinge of five blades has m != 0 from this light";
}

TEST(SceneSmoothies, SceneSmoothies_DefaultWidthOneMeshPerLight_BadWidthsThrow) {
  const Caster box = caster_of(shadowcert::box({0.0, 0.0, 0.0}, {3.0, 4.0, 12.0}));  // diagonal 13
  const gpu::SceneBounds bounds{{0.0, 0.0, 0.0}, {3.0, 4.0, 12.0}};
  const std::array lights{Light{{10.0, 20.0, 5.0, 1.0}}, Light{{0.2, 1.0, 0.1, 0.0}}};
  SceneSmoothies s = scene_smoothies(box.soup, box.table, lights, bounds);
  EXPECT_DOUBLE_EQ(s.width, kDefaultSmoothieWidthFraction * 13.0);
  ASSERT_EQ(s.per_light.size(), 2u);
  ASSERT_EQ(s.stats.size(), 2u);
  EXPECT_GT(s.stats[0].smoothies, 0u);
  EXPECT_EQ(s.per_light[0].vertices.size(), 4 * s.stats[0].smoothies);
  SceneSmoothieOptions options;
  options.width = 0.5;
  options.space = SmoothieSpace::light;
  s = scene_smoothies(box.soup, box.table, lights, bounds, options);
  EXPECT_EQ(s.width, 0.5);
  EXPECT_EQ(s.space, SmoothieSpace::light);
  for (double width : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    options.width = width;
    EXPECT_THROW((void)scene_smoothies(box.soup, box.table, lights, bounds, options), std::invalid_argument);
  }
}

// Light space with a point light at the bounds' centre (a lamp in a room: drawn with a cube map,
// aimed at no point; threw before): the reference distance is half the bounds' diagonal.
TEST(SceneSmoothies, LightSpaceLightAtTheBoundsCentre_HalfTheDiagonalIsTheReference) {
  const Caster box = caster_of(shadowcert::box({0.0, 0.0, 0.0}, {3.0, 4.0, 12.0}));
  const gpu::SceneBounds around{{0.0, 0.0, 0.0}, {20.0, 40.0, 10.0}};  // centre (10, 20, 5), outside the box
  const std::array centre{Light{{10.0, 20.0, 5.0, 1.0}}};
  SceneSmoothieOptions options;
  options.width = 0.5;
  options.space = SmoothieSpace::light;
  const SceneSmoothies at_centre = scene_smoothies(box.soup, box.table, centre, around, options);
  SmoothieOptions by_hand;
  by_hand.width = 0.5;
  by_hand.space = SmoothieSpace::light;
  by_hand.reference_distance = 0.5 * std::sqrt(20.0 * 20.0 + 40.0 * 40.0 + 10.0 * 10.0);
  const Soup rounded = float_rounded(box.soup);
  const Smoothies expected =
      build_smoothies(rounded.vertices, smoothie_edges(rounded, box.table, centre[0]), centre[0], by_hand);
  ASSERT_GT(expected.stats.smoothies, 0u);
  ASSERT_EQ(at_centre.per_light.size(), 1u);
  EXPECT_EQ(at_centre.per_light[0].vertices, expected.mesh.vertices);
  EXPECT_EQ(at_centre.per_light[0].alpha, expected.mesh.alpha);
}

}  // namespace
}  // namespace shadowcert
