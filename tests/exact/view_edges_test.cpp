// The edge classes of exact/view_edges.h on hand-built meshes (a cube seen from several eyes, an
// open box, fans), the crease threshold at an exact tie, the bend and incidence angles of
// exact/normal_angle.h, and invariance under vertex relabelling and face reversal.
#include "exact/view_edges.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <utility>

#include "exact/edge_multiplicity.h"
#include "exact/normal_angle.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

struct Classified {
  Soup soup;  // canonical
  EdgeTable table;
  ViewEdges edges;

  // The classes of edge {a, b} given by positions.
  std::uint8_t at(const Vec3& a, const Vec3& b) const {
    for (std::size_t e = 0; e < table.size(); ++e) {
      const Vec3& u = soup.vertices[table.edges[e][0]];
      const Vec3& v = soup.vertices[table.edges[e][1]];
      if ((u == a && v == b) || (u == b && v == a)) return edges.classes[e];
    }
    ADD_FAILURE() << "no such edge";
    return 0;
  }
};

Classified classify(const Soup& input, const Vec3& eye, double crease_degrees = kDefaultCreaseDegrees) {
  Classified c{canonical_soup(input).soup, {}, {}};
  c.table = build_edge_table(c.soup);
  c.edges = view_edges(c.soup, c.table, eye, angle_cosine(crease_degrees));
  return c;
}

Soup unit_cube() { return box({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}); }

// The classes keyed by the edge's positions, so that soups numbered differently compare.
std::map<std::pair<Vec3, Vec3>, std::uint8_t> by_position(const Classified& c) {
  std::map<std::pair<Vec3, Vec3>, std::uint8_t> out;
  for (std::size_t e = 0; e < c.table.size(); ++e)
    out[{c.soup.vertices[c.table.edges[e][0]], c.soup.vertices[c.table.edges[e][1]]}] = c.edges.classes[e];
  return out;
}

TEST(NormalAngle, CosinesOfSpecialAnglesAreExact) {
  EXPECT_EQ(angle_cosine(0.0), 1.0);
  EXPECT_EQ(angle_cosine(60.0), 0.5);
  EXPECT_EQ(angle_cosine(90.0), 0.0);
  EXPECT_EQ(angle_cosine(120.0), -0.5);
  EXPECT_EQ(angle_cosine(180.0), -1.0);
  EXPECT_NEAR(angle_cosine(30.0), std::sqrt(3.0) / 2.0, 1e-15);
  EXPECT_THROW((void)angle_cosine(-1.0), std::invalid_argument);
  EXPECT_THROW((void)angle_cosine(181.0), std::invalid_argument);
  EXPECT_THROW((void)angle_cosine(std::nan("")), std::invalid_argument);
}

TEST(NormalAngle, BendAngleTiesAreZero) {
  const Vec3 u{0, 0, 0}, v{1, 0, 0}, up{0, 1, 0}, side{0, 0, 1}, flat{0, -1, 0};
  // A right angle: exactly 90 degrees, whichever threshold side.
  EXPECT_EQ(bend_angle_sign(u, v, up, side, 0.0), Sign::zero);
  EXPECT_EQ(bend_angle_sign(u, v, up, side, angle_cosine(89.999)), Sign::positive);
  EXPECT_EQ(bend_angle_sign(u, v, up, side, angle_cosine(90.001)), Sign::negative);
  // Flat (0 degrees) and folded back (180 degrees).
  EXPECT_EQ(bend_angle_sign(u, v, up, flat, 1.0), Sign::zero);
  EXPECT_EQ(bend_angle_sign(u, v, up, flat, angle_cosine(1e-6)), Sign::negative);
  EXPECT_EQ(bend_angle_sign(u, v, up, up, -1.0), Sign::zero);
  EXPECT_EQ(bend_angle_sign(u, v, up, up, angle_cosine(179.0)), Sign::positive);
  // 45 degrees against 30 and 60.
  const Vec3 diagonal{0, -1, 1};
  EXPECT_EQ(bend_angle_sign(u, v, up, diagonal, angle_cosine(30.0)), Sign::positive);
  EXPECT_EQ(bend_angle_sign(u, v, up, diagonal, angle_cosine(60.0)), Sign::negative);
  // The same bend for either winding of either triangle: only positions enter.
  EXPECT_EQ(bend_angle_sign(v, u, side, up, 0.0), Sign::zero);
  // The smallest tilt off the right angle is decided exactly: towards the first triangle
  // folds more (above 90 degrees), away from it opens the bend (below).
  const Vec3 tilted_in{0, std::nextafter(0.0, 1.0), 1};
  EXPECT_EQ(bend_angle_sign(u, v, up, tilted_in, 0.0), Sign::positive);
  const Vec3 tilted_out{0, -std::nextafter(0.0, 1.0), 1};
  EXPECT_EQ(bend_angle_sign(u, v, up, tilted_out, 0.0), Sign::negative);
  // A collinear triangle has no normal.
  EXPECT_THROW((void)bend_angle_sign(u, v, Vec3{2, 0, 0}, up, 0.0), std::invalid_argument);
  EXPECT_THROW((void)bend_angle_sign(u, v, up, side, 1.5), std::invalid_argument);
}

TEST(NormalAngle, IncidenceAngle) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 0, 1};  // the plane y = 0
  EXPECT_EQ(incidence_angle_sign(a, b, c, Vec3{0, -1, 0}, angle_cosine(80.0)), Sign::negative);  // head on
  EXPECT_EQ(incidence_angle_sign(a, b, c, Vec3{0, 1, 0}, angle_cosine(80.0)), Sign::negative);   // either side
  EXPECT_EQ(incidence_angle_sign(a, b, c, Vec3{1, 0, 0}, 0.0), Sign::zero);                      // in the plane
  EXPECT_EQ(incidence_angle_sign(a, b, c, Vec3{1, 0, 0}, angle_cosine(80.0)), Sign::positive);
  // 85 degrees from the normal: tan(5 deg) ~ 0.0875.
  EXPECT_EQ(incidence_angle_sign(a, b, c, Vec3{1, -0.0875, 0}, angle_cosine(80.0)), Sign::positive);
  EXPECT_EQ(incidence_angle_sign(a, b, c, Vec3{1, -0.2, 0}, angle_cosine(80.0)), Sign::negative);  // ~78.7
  // 45 degrees exactly: cos^2 = 1/2, against a threshold just off it.
  EXPECT_EQ(incidence_angle_sign(a, b, c, Vec3{1, 1, 0}, angle_cosine(44.9)), Sign::positive);
  EXPECT_EQ(incidence_angle_sign(a, b, c, Vec3{1, 1, 0}, angle_cosine(45.1)), Sign::negative);
  EXPECT_THROW((void)incidence_angle_sign(a, b, c, Vec3{0, 0, 0}, 0.5), std::invalid_argument);
}

TEST(ViewEdges, CubeHasTwelveCreasesAndNoDiagonal) {
  // Three faces in view from a corner direction: the six edges of the hexagon outline are
  // silhouettes, the three edges between visible faces and the three between hidden faces
  // creases; the six face diagonals are flat.
  const Classified c = classify(unit_cube(), {5.0, 4.0, 6.0});
  ASSERT_EQ(c.table.size(), 18u);
  EXPECT_EQ(c.edges.count(kSilhouetteEdge), 6u);
  EXPECT_EQ(c.edges.count(kCreaseEdge), 6u);
  EXPECT_EQ(c.edges.count(kBorderEdge), 0u);
  EXPECT_EQ(c.edges.count(kSilhouetteEdge | kCreaseEdge), 12u);
  // The edges at the corner nearest the eye (1, 1, 1) join visible faces: creases.
  EXPECT_EQ(c.at({1, 1, 1}, {0, 1, 1}), kCreaseEdge);
  EXPECT_EQ(c.at({1, 1, 1}, {1, 0, 1}), kCreaseEdge);
  EXPECT_EQ(c.at({1, 1, 1}, {1, 1, 0}), kCreaseEdge);
  // And those at the far corner (0, 0, 0) join hidden faces: creases too (both away).
  EXPECT_EQ(c.at({0, 0, 0}, {1, 0, 0}), kCreaseEdge);
  EXPECT_EQ(c.at({0, 1, 0}, {1, 1, 0}), kSilhouetteEdge);
  for (std::size_t e = 0; e < c.table.size(); ++e) {
    EXPECT_EQ(c.edges.proper_faces[e], 2u);
    EXPECT_EQ(c.edges.classes[e] == kSilhouetteEdge, std::abs(c.edges.multiplicity[e]) == 2);
  }
}

TEST(ViewEdges, CubeSilhouettesFollowTheView) {
  // One face head on: its four edges are the outline; the other eight edges are creases
  // between hidden faces.
  const Classified front = classify(unit_cube(), {0.5, 0.5, 5.0});
  EXPECT_EQ(front.edges.count(kSilhouetteEdge), 4u);
  EXPECT_EQ(front.edges.count(kCreaseEdge), 8u);
  EXPECT_EQ(front.at({0, 0, 1}, {1, 0, 1}), kSilhouetteEdge);
  EXPECT_EQ(front.at({0, 0, 0}, {0, 0, 1}), kCreaseEdge);
  // Two faces in view, top and front: the x faces are seen from behind.
  const Classified two = classify(unit_cube(), {0.5, 3.0, 5.0});
  EXPECT_EQ(two.edges.count(kSilhouetteEdge), 6u);
  EXPECT_EQ(two.edges.count(kCreaseEdge), 6u);
  EXPECT_EQ(two.at({0, 1, 1}, {1, 1, 1}), kCreaseEdge);  // between the visible top and front
  // The eye in the top face's plane: the top is seen edge-on and adds nothing, so the edge
  // between it and the visible front face is a silhouette (m = +-1), and the top's other
  // edges separate it from hidden faces: silhouettes too.
  const Classified edge_on = classify(unit_cube(), {0.5, 1.0, 5.0});
  EXPECT_EQ(edge_on.at({0, 1, 1}, {1, 1, 1}), kSilhouetteEdge);
  // Inside the cube every face is seen from its back: no outline at all, twelve creases.
  const Classified inside = classify(unit_cube(), {0.5, 0.25, 0.75});
  EXPECT_EQ(inside.edges.count(kSilhouetteEdge), 0u);
  EXPECT_EQ(inside.edges.count(kCreaseEdge), 12u);
}

TEST(ViewEdges, CreaseThresholdTieIsExact) {
  // A cube's bends are exactly 90 degrees: cos = 0 is an exact double, and a bend equal to the
  // threshold is not above it.
  const Vec3 eye{5.0, 4.0, 6.0};
  EXPECT_EQ(classify(unit_cube(), eye, 90.0).edges.count(kCreaseEdge), 0u);
  EXPECT_EQ(classify(unit_cube(), eye, 89.999).edges.count(kCreaseEdge), 6u);
  EXPECT_EQ(classify(unit_cube(), eye, 0.0).edges.count(kCreaseEdge), 6u);  // diagonals: exactly 0, no crease
  EXPECT_EQ(classify(unit_cube(), eye, 90.001).edges.count(kCreaseEdge), 0u);
  // Silhouettes do not depend on the threshold.
  EXPECT_EQ(classify(unit_cube(), eye, 90.0).edges.count(kSilhouetteEdge), 6u);
}

TEST(ViewEdges, OpenBoxHasBorders) {
  Soup open = unit_cube();
  open.triangles.erase(open.triangles.begin() + 6, open.triangles.begin() + 8);  // no +y face
  // From above, looking in: the four rim edges are borders (and, each on one triangle seen
  // from the eye, silhouettes); the bottom's edges are creases between faces seen from inside.
  const Classified above = classify(open, {0.3, 4.0, 0.6});
  EXPECT_EQ(above.edges.count(kBorderEdge), 4u);
  EXPECT_EQ(above.edges.count(kBorderEdge | kSilhouetteEdge), 4u);
  EXPECT_EQ(above.at({0, 1, 0}, {1, 1, 0}), kBorderEdge | kSilhouetteEdge);
  for (std::size_t e = 0; e < above.table.size(); ++e)
    if (above.edges.classes[e] & kBorderEdge) {
      EXPECT_EQ(std::abs(above.edges.multiplicity[e]), 1);
    }
  EXPECT_EQ(above.at({0, 0, 0}, {1, 0, 0}), kCreaseEdge);
  // A rim edge seen edge-on (the eye in its one triangle's plane): still a border, no silhouette.
  const Classified in_plane = classify(open, {0.25, 3.0, 0.0});  // in the plane z = 0 of the -z face
  EXPECT_EQ(in_plane.at({0, 1, 0}, {1, 1, 0}), kBorderEdge);
  EXPECT_EQ(in_plane.edges.count(kBorderEdge), 4u);
}

TEST(ViewEdges, FanEdgesAreNonManifoldSilhouettes) {
  // nonmanifold_fan(k): k blades on the edge (0,0,0)-(0,1,0). Odd k: m is odd, never zero, so
  // the shared edge is a silhouette from any eye off every blade's plane; it is never a border
  // or a crease. The blades' outer edges are borders.
  for (const std::uint32_t k : {1u, 3u, 5u, 16u}) {
    const Vec3 eye{2.0, 0.7, 3.1};
    const Classified c = classify(nonmanifold_fan(k), eye);
    const std::uint8_t shared = c.at({0, 0, 0}, {0, 1, 0});
    const Light light{{eye[0], eye[1], eye[2], 1.0}};
    const EdgeMultiplicities m = exact_multiplicities(c.soup, c.table, light);
    for (std::size_t e = 0; e < c.table.size(); ++e) {
      EXPECT_EQ((c.edges.classes[e] & kSilhouetteEdge) != 0, m.multiplicity[e] != 0);
      EXPECT_EQ(c.edges.multiplicity[e], m.multiplicity[e]);
    }
    if (k % 2 == 1) {
      EXPECT_TRUE(shared & kSilhouetteEdge) << k;
    }
    EXPECT_FALSE(shared & kCreaseEdge) << k;
    if (k >= 2) {
      EXPECT_FALSE(shared & kBorderEdge) << k;
    }
    EXPECT_EQ(c.edges.count(kBorderEdge), k == 1 ? 3u : 2u * k);
  }
}

TEST(ViewEdges, DegenerateTrianglesCountForNothing) {
  // A square of two triangles plus a zero-area triangle on its diagonal: the diagonal has two
  // proper triangles (flat: no crease) and the sliver's other edges carry no proper triangle.
  Soup s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  s.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 2, 4}};
  const Classified c = classify(s, {0.3, 0.2, 4.0}, 0.0);
  EXPECT_EQ(c.at({0, 0, 0}, {1, 1, 0}), 0);
  EXPECT_EQ(c.at({0, 0, 0}, {0.5, 0.5, 0}), 0);
  EXPECT_EQ(c.at({1, 0, 0}, {1, 1, 0}), kBorderEdge | kSilhouetteEdge);
}

TEST(ViewEdges, InvariantUnderRelabellingAndReversal) {
  std::mt19937_64 random(14);
  Soup soup = uv_sphere({0.1, 0.2, -0.3}, 1.0, 9, 6);
  const Soup box_soup = box({1.5, -0.5, -0.5}, {2.5, 0.5, 0.25});
  for (const Triangle& t : box_soup.triangles)
    soup.triangles.push_back({t[0] + static_cast<std::uint32_t>(soup.vertices.size()),
                              t[1] + static_cast<std::uint32_t>(soup.vertices.size()),
                              t[2] + static_cast<std::uint32_t>(soup.vertices.size())});
  soup.vertices.insert(soup.vertices.end(), box_soup.vertices.begin(), box_soup.vertices.end());
  soup.triangles.erase(soup.triangles.begin() + 5);  // a hole: borders
  soup.normals.clear();
  const Vec3 eye{3.0, 1.7, 4.2};
  const auto reference = by_position(classify(soup, eye, 20.0));
  EXPECT_GT(std::count_if(reference.begin(), reference.end(), [](const auto& kv) { return kv.second & kBorderEdge; }), 0);
  EXPECT_GT(std::count_if(reference.begin(), reference.end(), [](const auto& kv) { return kv.second & kCreaseEdge; }), 0);

  // Relabel the vertices.
  std::vector<std::uint32_t> order(soup.vertices.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), random);
  Soup relabelled;
  relabelled.vertices.resize(soup.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) relabelled.vertices[order[i]] = soup.vertices[i];
  for (const Triangle& t : soup.triangles) relabelled.triangles.push_back({order[t[0]], order[t[1]], order[t[2]]});
  EXPECT_EQ(by_position(classify(relabelled, eye, 20.0)), reference);

  // Reverse every other face.
  Soup reversed = soup;
  for (std::size_t i = 0; i < reversed.triangles.size(); i += 2) std::swap(reversed.triangles[i][1], reversed.triangles[i][2]);
  EXPECT_EQ(by_position(classify(reversed, eye, 20.0)), reference);
}

TEST(ViewEdges, RejectsBadInput) {
  const Soup cube = canonical_soup(unit_cube()).soup;
  const EdgeTable table = build_edge_table(cube);
  EXPECT_THROW((void)view_edges(cube, table, {std::nan(""), 0, 0}, 0.5), std::invalid_argument);
  EXPECT_THROW((void)view_edges(cube, table, {5, 5, 5}, 1.5), std::invalid_argument);
  EXPECT_THROW((void)view_edges(cube, EdgeTable{}, {5, 5, 5}, 0.5), std::invalid_argument);
}

}  // namespace
