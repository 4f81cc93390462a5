// contour/silhouette_edge_graph.h: every edge once with its faces, the edges around each
// vertex, the concave and border lists, and the float light side, held to the exact one.
#include "contour/silhouette_edge_graph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <set>

#include "core/vector3.h"
#include "exact/edge_multiplicity.h"
#include "exact/light_orientation.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/procedural_mesh.h"
#include "support/contour_test_support.h"

namespace {

using namespace shadowcert;
using test_support::caster_of;

SilhouetteEdgeGraph graph_of(const Soup& soup) { return silhouette_edge_graph(caster_of(soup)); }

// The distance of a point from the y axis.
double from_axis(const Vec3& p) { return std::sqrt(p[0] * p[0] + p[2] * p[2]); }

TEST(SilhouetteEdgeGraph, Box_EighteenEdgesTwoFacesEachNoneConcaveNoBorder) {
  const SilhouetteEdgeGraph g = graph_of(box({0, 0, 0}, {1, 1, 1}));
  EXPECT_EQ(g.edge_count(), 18u);
  EXPECT_EQ(g.face_count(), 12u);
  EXPECT_TRUE(g.concave_edges.empty());
  EXPECT_TRUE(g.border_edges.empty());
  std::set<std::array<std::uint32_t, 2>> distinct;
  for (std::uint32_t e = 0; e < g.edge_count(); ++e) {
    const auto [a, b] = g.edge_vertices[e];
    EXPECT_LT(a, b);
    EXPECT_TRUE(distinct.insert(g.edge_vertices[e]).second) << "edge " << e << " twice";
    EXPECT_NE(g.edge_faces[e][1], kBorder);
    EXPECT_NE(g.edge_faces[e][0], g.edge_faces[e][1]);
    // Listed around both its ends, and nowhere else.
    for (std::uint32_t v = 0; v < g.vertices.size(); ++v) {
      const auto around = g.edges_at(v);
      const bool listed = std::find(around.begin(), around.end(), e) != around.end();
      EXPECT_EQ(listed, v == a || v == b) << "edge " << e << " vertex " << v;
    }
  }
  std::size_t incidences = 0;
  for (std::uint32_t v = 0; v < g.vertices.size(); ++v) incidences += g.edges_at(v).size();
  EXPECT_EQ(incidences, 2 * g.edge_count());
}

TEST(SilhouetteEdgeGraph, Floor_FourBorderEdgesAndTheDiagonal) {
  const SilhouetteEdgeGraph g = graph_of(floor_quad(1.0));
  EXPECT_EQ(g.edge_count(), 5u);
  ASSERT_EQ(g.border_edges.size(), 4u);
  for (const std::uint32_t e : g.border_edges) EXPECT_EQ(g.edge_faces[e][1], kBorder);
  EXPECT_TRUE(g.concave_edges.empty());  // the diagonal is flat
}

// A uv sphere's quads are exactly planar, split along a diagonal: the rounding of the double
// determinant there must not list the diagonal as concave (it listed half of them, and the
// tracker then tested a third of the sphere's edges every frame).
TEST(SilhouetteEdgeGraph, ConvexSpheres_HaveNoConcaveEdge) {
  for (const auto& [slices, stacks] : {std::pair{8u, 4u}, {48u, 24u}, {200u, 100u}}) {
    const SilhouetteEdgeGraph g = graph_of(uv_sphere({0.3, -0.2, 0.1}, 1.7, slices, stacks));
    EXPECT_TRUE(g.concave_edges.empty()) << slices << "x" << stacks << ": " << g.concave_edges.size();
  }
  EXPECT_TRUE(graph_of(icosphere({0, 0, 0}, 1.0, 3)).concave_edges.empty());
}

// On a torus the surface is saddle-shaped on its inner half: the edges running around the axis
// there are concave, and no edge of the outer half is.
TEST(SilhouetteEdgeGraph, Torus_ConcaveEdgesLieOnTheInnerHalf) {
  const SilhouetteEdgeGraph g = graph_of(torus({0, 0, 0}, 1.0, 0.3, 32, 16));
  EXPECT_TRUE(g.border_edges.empty());
  EXPECT_GT(g.concave_edges.size(), g.edge_count() / 8);
  for (const std::uint32_t e : g.concave_edges) {
    const Vec3& a = g.vertices[g.edge_vertices[e][0]];
    const Vec3& b = g.vertices[g.edge_vertices[e][1]];
    EXPECT_LE(from_axis({0.5 * (a[0] + b[0]), 0.0, 0.5 * (a[2] + b[2])}), 1.0 + 1e-12) << "edge " << e;
  }
}

// The side is evaluated on the sorted vertices: a face's labelling, wherever it starts, gives the
// same bits, even with the light within rounding of the face's plane.
TEST(FaceLightSide, RotatedLabelling_SameSignEvenOnTheFacePlane) {
  const std::uint64_t seed = 20261213;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 a{u(random), u(random), u(random)}, b{u(random), u(random), u(random)}, c{u(random), u(random), u(random)};
    // A light on the plane, up to rounding: a + s (b - a) + t (c - a).
    const double s = u(random), t = u(random);
    const Light light{{a[0] + s * (b[0] - a[0]) + t * (c[0] - a[0]), a[1] + s * (b[1] - a[1]) + t * (c[1] - a[1]),
                       a[2] + s * (b[2] - a[2]) + t * (c[2] - a[2]), 1.0}};
    Sign first = Sign::zero;
    for (int r = 0; r < 3; ++r) {
      Soup soup;
      soup.vertices = {a, b, c};
      soup.triangles = {{static_cast<std::uint32_t>(r), static_cast<std::uint32_t>((r + 1) % 3),
                         static_cast<std::uint32_t>((r + 2) % 3)}};
      const Sign side = face_light_side(graph_of(soup), 0, light);
      if (r == 0) first = side;
      EXPECT_EQ(side, first) << "trial " << trial << " rotation " << r;
    }
  }
}

// Away from every plane the float side is the exact one, and the silhouette edges (sides
// different, or a border with a side) are the edges with exact multiplicity m != 0.
TEST(FaceLightSide, RandomLights_EqualTheExactSideAndTheSilhouetteIsMNonzero) {
  const std::uint64_t seed = 1302;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  for (const Soup& soup : {torus({0, 0, 0}, 1.0, 0.3, 24, 12), torus_knot({0, 0, 0}, 2, 3, 1.0, 0.4, 0.12, 64, 8),
                           uv_sphere({0, 0, 0}, 1.0, 16, 8)}) {
    const SilhouetteEdgeGraph g = graph_of(soup);
    const Soup canonical = canonical_soup(soup).soup;
    const EdgeTable table = build_edge_table(canonical);
    ASSERT_EQ(table.size(), g.edge_count());
    for (int trial = 0; trial < 50; ++trial) {
      const Light light{{u(random), u(random), u(random), trial % 5 == 0 ? 0.0 : 1.0}};
      std::size_t float_silhouette = 0;
      for (std::uint32_t e = 0; e < g.edge_count(); ++e) {
        const auto [f0, f1] = g.edge_faces[e];
        const Sign s0 = face_light_side(g, f0, light);
        const Sign s1 = f1 == kBorder ? Sign::zero : face_light_side(g, f1, light);
        float_silhouette += silhouette_sides(s0, s1, f1 == kBorder) ? 1 : 0;
      }
      const EdgeMultiplicities exact = exact_multiplicities(canonical, table, light);
      const auto exact_silhouette = static_cast<std::size_t>(
          std::count_if(exact.multiplicity.begin(), exact.multiplicity.end(), [](std::int32_t m) { return m != 0; }));
      EXPECT_EQ(float_silhouette, exact_silhouette) << "trial " << trial;
      for (std::uint32_t t = 0; t < g.face_count(); ++t) {
        const Triangle& s = g.sorted_faces[t].vertices;
        const Sign orientation = light_orientation(g.vertices[s[0]], g.vertices[s[1]], g.vertices[s[2]], light);
        EXPECT_EQ(face_light_side(g, t, light), g.sorted_faces[t].parity > 0 ? orientation : -orientation) << "face " << t;
      }
    }
  }
}

}  // namespace
