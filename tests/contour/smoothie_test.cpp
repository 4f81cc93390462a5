// contour/smoothie.h on hand-built silhouette edges (GL-free):
//  1. one edge of a wedge: the quad runs along the exterior bisector (world) or perpendicular to
//     the light's rays with the width scaled by the distance (light), alpha 0 on the edge and 1
//     on the rim, and the interpolated alpha grows monotonically from the edge to the rim;
//  2. a flat L-shaped caster under a light straight above: the five convex corners are linked and
//     leave no gap in the light's image (without linking they do), the concave corner is shrunk
//     by (1 + p_A . p_B) / 2 = 1/2;
//  3. degenerate edges: zero length, the light on the edge's line (point and directional), a
//     bisector of zero length, a face on the edge's line, a bisector pointing inwards;
//  4. misuse throws.
// The quads outside the shadow of convex casters, with exactly chosen edges, are in
// tests/pipeline/scene_smoothies_test.cpp.
#include "contour/smoothie.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/vector3.h"

namespace shadowcert {
namespace {

Vec3 operator-(const Vec3& a, const Vec3& b) { return difference(a, b); }
Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 operator*(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }

void expect_near(const Vec3& a, const Vec3& b, double tolerance = 1e-12) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tolerance) << "coordinate " << k;
}

// The side of the edge's occluders: sign((o - u) . ((l - w u) x (v - u))) of the first face's
// opposite vertex (exact enough for the small integer and dyadic coordinates used here).
std::int8_t occluder_side(const std::vector<Vec3>& vertices, std::uint32_t u, std::uint32_t v, std::uint32_t o,
                          const Light& light) {
  const Vec3 l{light.position[0], light.position[1], light.position[2]};
  const Vec3 ray = light.directional() ? l : l - vertices[u];
  const double value = dot(vertices[o] - vertices[u], cross(ray, vertices[v] - vertices[u]));
  return value > 0.0 ? 1 : -1;
}

// Edges with one face each (opposite vertex given), sides computed as above.
SmoothieEdges edges_with_faces(const std::vector<Vec3>& vertices,
                               const std::vector<std::array<std::uint32_t, 3>>& edge_opposite, const Light& light) {
  SmoothieEdges e;
  e.first_face.push_back(0);
  for (const auto& [u, v, o] : edge_opposite) {
    e.edges.push_back({u, v});
    e.occluder_side.push_back(occluder_side(vertices, u, v, o, light));
    e.face_opposite.push_back(o);
    e.first_face.push_back(static_cast<std::uint32_t>(e.face_opposite.size()));
  }
  return e;
}

// Barycentric coordinates of p in triangle abc (p in its plane), or nullopt outside it.
std::optional<std::array<double, 3>> barycentric(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  const Vec3 n = cross(b - a, c - a);
  const double area = dot(n, n);
  if (area == 0.0) return std::nullopt;
  const double wa = dot(cross(c - b, p - b), n) / area;
  const double wb = dot(cross(a - c, p - c), n) / area;
  const double wc = 1.0 - wa - wb;
  constexpr double kSlack = 1e-12;
  if (wa < -kSlack || wb < -kSlack || wc < -kSlack) return std::nullopt;
  return std::array<double, 3>{wa, wb, wc};
}

// The alpha interpolated at p (a point of the mesh's surface), or nullopt where no triangle holds it.
std::optional<double> interpolated_alpha(const SmoothieMesh& mesh, const Vec3& p) {
  for (const auto& t : mesh.triangles) {
    const auto w = barycentric(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], p);
    if (!w) continue;
    // In the triangle's plane?
    const Vec3 q = (*w)[0] * mesh.vertices[t[0]] + (*w)[1] * mesh.vertices[t[1]] + (*w)[2] * mesh.vertices[t[2]];
    if (norm(q - p) > 1e-9) continue;
    return (*w)[0] * mesh.alpha[t[0]] + (*w)[1] * mesh.alpha[t[1]] + (*w)[2] * mesh.alpha[t[2]];
  }
  return std::nullopt;
}

// The wedge: edge (0,0,0)-(0,0,1), faces towards (-1, 1, 0.5) and (-1, -1, 0.5); its exterior
// bisector is +x. Lit from above, the upper face is lit and the lower one not.
std::vector<Vec3> wedge() { return {{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {-1.0, 1.0, 0.5}, {-1.0, -1.0, 0.5}}; }

SmoothieEdges wedge_edge(const Light& light) {
  const std::vector<Vec3> v = wedge();
  SmoothieEdges e;
  e.edges = {{0, 1}};
  e.occluder_side = {occluder_side(v, 0, 1, 2, light)};
  e.first_face = {0, 2};
  e.face_opposite = {2, 3};
  return e;
}

TEST(Smoothie, OneEdgeInWorldSpace_RunsAlongTheExteriorBisector) {
  const std::vector<Vec3> v = wedge();
  const Light light{{0.0, 10.0, 0.5, 1.0}};
  SmoothieOptions options;
  options.width = 0.25;
  const Smoothies s = build_smoothies(v, wedge_edge(light), light, options);
  ASSERT_EQ(s.stats.smoothies, 1u);
  EXPECT_EQ(s.stats.bisector_fallbacks, 0u);
  ASSERT_EQ(s.mesh.vertices.size(), 4u);
  EXPECT_EQ(s.mesh.alpha, (std::vector<float>{0.0f, 0.0f, 1.0f, 1.0f}));
  expect_near(s.mesh.vertices[0], v[0]);
  expect_near(s.mesh.vertices[1], v[1]);
  expect_near(s.mesh.vertices[2], {0.25, 0.0, 1.0});  // v' = v + D B, B = +x
  expect_near(s.mesh.vertices[3], {0.25, 0.0, 0.0});
  EXPECT_EQ(s.mesh.triangles.size(), 2u);
}

TEST(Smoothie, OneEdgeInLightSpace_PerpendicularToTheRaysWithTheWidthScaledByDistance) {
  const std::vector<Vec3> v = wedge();
  const Light light{{0.0, 10.0, 0.5, 1.0}};
  SmoothieOptions options;
  options.width = 0.25;
  options.space = SmoothieSpace::light;
  options.reference_distance = 5.0;
  const Smoothies s = build_smoothies(v, wedge_edge(light), light, options);
  ASSERT_EQ(s.stats.smoothies, 1u);
  // p = (10, 0, 0) normalised... of (l - u) x (v - u) = (0, 10, 0.5) x (0, 0, 1) = (10, 0, 0),
  // the occluders below it: p = +x, perpendicular to both rays; widths D |x - l| / 5.
  const double distance = std::sqrt(100.0 + 0.25);
  expect_near(s.mesh.vertices[2], {0.25 * distance / 5.0, 0.0, 1.0});
  expect_near(s.mesh.vertices[3], {0.25 * distance / 5.0, 0.0, 0.0});
  // A directional light: an orthographic image, the width D everywhere.
  const Light sun{{0.0, 1.0, 0.0, 0.0}};
  const Smoothies d = build_smoothies(v, wedge_edge(sun), sun, options);
  expect_near(d.mesh.vertices[2], {0.25, 0.0, 1.0});
}

TEST(Smoothie, AlphaGrowsMonotonicallyFromTheEdgeToTheRim) {
  const std::vector<Vec3> v = wedge();
  const Light light{{0.0, 10.0, 0.5, 1.0}};
  for (SmoothieSpace space : {SmoothieSpace::world, SmoothieSpace::light}) {
    SmoothieOptions options;
    options.width = 0.4;
    options.space = space;
    options.reference_distance = 10.0;
    const Smoothies s = build_smoothies(v, wedge_edge(light), light, options);
    // From a point of the edge to the rim point straight across (the quad is a parallelogram
    // in world space, a trapezoid in light space).
    for (double along : {0.1, 0.5, 0.9}) {
      const Vec3 from = (1.0 - along) * s.mesh.vertices[0] + along * s.mesh.vertices[1];
      const Vec3 to = (1.0 - along) * s.mesh.vertices[3] + along * s.mesh.vertices[2];
      double previous = -1.0;
      for (int k = 0; k <= 20; ++k) {
        const double t = k / 20.0;
        const std::optional<double> alpha = interpolated_alpha(s.mesh, (1.0 - t) * from + t * to);
        ASSERT_TRUE(alpha.has_value()) << "t " << t;
        EXPECT_NEAR(*alpha, t, 1e-9);  // linear from 0 at the edge to 1 at the rim
        EXPECT_GT(*alpha, previous);
        previous = *alpha;
      }
    }
  }
}

// A flat L in the plane y = 0 ((x, z): (0,0) (2,0) (2,1) (1,1) (1,2) (0,2)), triangulated, its six
// border edges as silhouette edges with their faces' opposite vertices; (1, 1) is its concave
// corner. Lit from straight above, the light's image is the plane y = 0 itself.
std::vector<Vec3> l_shape() {
  return {{0.0, 0.0, 0.0}, {2.0, 0.0, 0.0}, {2.0, 0.0, 1.0}, {1.0, 0.0, 1.0}, {1.0, 0.0, 2.0}, {0.0, 0.0, 2.0}};
}
// Triangles (0,1,2), (0,2,3), (0,3,5), (3,4,5): each border edge with its face's third vertex.
const std::vector<std::array<std::uint32_t, 3>> kLBorder{{0, 1, 2}, {1, 2, 0}, {2, 3, 0},
                                                         {3, 4, 5}, {4, 5, 3}, {5, 0, 3}};

// Whether (x, z) lies in some smoothie triangle projected along y.
bool covered_from_above(const SmoothieMesh& mesh, double x, double z) {
  for (const auto& t : mesh.triangles) {
    const auto flat = [&](std::uint32_t i) { return Vec3{mesh.vertices[i][0], 0.0, mesh.vertices[i][2]}; };
    if (barycentric(flat(t[0]), flat(t[1]), flat(t[2]), {x, 0.0, z})) return true;
  }
  return false;
}

TEST(Smoothie, LShape_ConvexCornersLinkedWithoutGap_ConcaveCornerShrunk) {
  const std::vector<Vec3> v = l_shape();
  const Light sun{{0.0, 1.0, 0.0, 0.0}};
  constexpr double kWidth = 0.2;
  for (SmoothieSpace space : {SmoothieSpace::world, SmoothieSpace::light}) {
    SCOPED_TRACE(std::string(smoothie_space_name(space)));
    SmoothieOptions options;
    options.width = kWidth;
    options.space = space;
    const Smoothies s = build_smoothies(v, edges_with_faces(v, kLBorder, sun), sun, options);
    EXPECT_EQ(s.stats.smoothies, 6u);
    EXPECT_EQ(s.stats.linked_corners, 5u);
    EXPECT_EQ(s.stats.shrunk_corners, 1u);
    EXPECT_EQ(s.mesh.triangles.size(), 12u + 5u);
    // The concave corner (1, 1): both smoothies' outer vertices there at half the width
    // (p_A . p_B = 0 at a right angle).
    for (std::size_t i = 0; i < s.mesh.vertices.size(); ++i) {
      if (s.mesh.alpha[i] != 0.0f || s.mesh.vertices[i] != v[3]) continue;
      const std::size_t smoothie = i / 4, end = i % 4;  // u, v, v', u'
      const std::size_t outer = 4 * smoothie + (end == 0 ? 3 : 2);
      EXPECT_NEAR(norm(s.mesh.vertices[outer] - v[3]), 0.5 * kWidth, 1e-12);
    }
    // No gap at a convex corner: points just outside it, along its exterior bisector, are
    // covered in the light's image. (0, 0): bisector (-1, -1); (2, 0): (1, -1); (2, 1): (1, 1);
    // (1, 2): (1, 1); (0, 2): (-1, 1).
    const std::array<std::array<double, 4>, 5> corners{{{0, 0, -1, -1}, {2, 0, 1, -1}, {2, 1, 1, 1},
                                                        {1, 2, 1, 1}, {0, 2, -1, 1}}};
    for (const auto& [x, z, dx, dz] : corners) {
      const double step = 0.5 * kWidth / std::sqrt(2.0);
      EXPECT_TRUE(covered_from_above(s.mesh, x + step * dx, z + step * dz)) << "corner " << x << ", " << z;
    }
    // Without linking, the same points fall in the gaps.
    options.link_corners = false;
    const Smoothies unlinked = build_smoothies(v, edges_with_faces(v, kLBorder, sun), sun, options);
    EXPECT_EQ(unlinked.stats.linked_corners, 0u);
    for (const auto& [x, z, dx, dz] : corners) {
      const double step = 0.5 * kWidth / std::sqrt(2.0);
      EXPECT_FALSE(covered_from_above(unlinked.mesh, x + step * dx, z + step * dz)) << "corner " << x << ", " << z;
    }
  }
}

TEST(Smoothie, DegenerateEdges_ZeroLengthAndEdgeOn_MakeNoSmoothie) {
  // Vertex 4 repeats vertex 1's position.
  std::vector<Vec3> v = wedge();
  v.push_back(v[1]);
  SmoothieEdges e;
  e.edges = {{1, 1}, {1, 4}};
  e.occluder_side = {1, -1};
  e.first_face = {0, 1, 2};
  e.face_opposite = {2, 2};
  SmoothieOptions options;
  options.width = 0.1;
  const Light light{{3.0, 4.0, 5.0, 1.0}};
  Smoothies s = build_smoothies(v, e, light, options);
  EXPECT_EQ(s.stats.zero_length_edges, 2u);
  EXPECT_EQ(s.stats.smoothies, 0u);
  EXPECT_TRUE(s.mesh.triangles.empty());
  // The light on the edge's line (beyond its end), point and directional: seen edge-on.
  for (const Light& on_line : {Light{{0.0, 0.0, 7.0, 1.0}}, Light{{0.0, 0.0, -1.0, 0.0}}}) {
    const SmoothieEdges edge{{{0, 1}}, {1}, {0, 1}, {2}};
    s = build_smoothies(v, edge, on_line, options);
    EXPECT_EQ(s.stats.edge_on_edges, 1u);
    EXPECT_EQ(s.stats.smoothies, 0u);
  }
}

TEST(Smoothie, DegenerateBisectors_FallBackToTheLightImageDirection) {
  const Light light{{0.0, 10.0, 0.5, 1.0}};
  SmoothieOptions options;
  options.width = 0.5;
  // p for the wedge's edge under this light: +x (OneEdgeInLightSpace above).
  const auto direction = [&](const std::vector<Vec3>& v, std::vector<std::uint32_t> opposites, std::int8_t side) {
    SmoothieEdges e;
    e.edges = {{0, 1}};
    e.occluder_side = {side};
    e.first_face = {0, static_cast<std::uint32_t>(opposites.size())};
    e.face_opposite = opposites;
    const Smoothies s = build_smoothies(v, e, light, options);
    EXPECT_EQ(s.stats.smoothies, 1u);
    return std::pair{(1.0 / options.width) * (s.mesh.vertices[3] - s.mesh.vertices[0]), s.stats.bisector_fallbacks};
  };
  std::vector<Vec3> v = wedge();
  v.push_back({1.0, 1.0, 0.5});   // 4: mirrors vertex 3 through the edge: faces 4 and 3 continue each other
  v.push_back({0.0, 0.0, 3.0});   // 5: on the edge's line
  v.push_back({1.0, 0.2, 0.5});   // 6: a face on the far side of the side plane, bisector inwards
  // A flat continuation: the in-face directions cancel, no bisector.
  auto [d, fallbacks] = direction(v, {4, 3}, -1);
  EXPECT_EQ(fallbacks, 1u);
  expect_near(d, {1.0, 0.0, 0.0});
  // A face on the edge's line adds nothing; alone, it leaves no bisector.
  std::tie(d, fallbacks) = direction(v, {5}, -1);
  EXPECT_EQ(fallbacks, 1u);
  expect_near(d, {1.0, 0.0, 0.0});
  std::tie(d, fallbacks) = direction(v, {2, 5}, -1);
  EXPECT_EQ(fallbacks, 0u);
  expect_near(d, normalized(Vec3{1.0, -1.0, 0.0}));  // -w of face 2 alone
  // A face whose bisector points into the occluders' side (a soup's stray face): p instead.
  std::tie(d, fallbacks) = direction(v, {6}, -1);
  EXPECT_EQ(fallbacks, 1u);
  expect_near(d, {1.0, 0.0, 0.0});
}

TEST(Smoothie, Misuse_Throws) {
  const std::vector<Vec3> v = wedge();
  const Light light{{0.0, 10.0, 0.5, 1.0}};
  const SmoothieEdges e = wedge_edge(light);
  SmoothieOptions options;
  for (double width : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    options.width = width;
    EXPECT_THROW((void)build_smoothies(v, e, light, options), std::invalid_argument) << width;
  }
  options.width = 0.1;
  options.space = SmoothieSpace::light;  // a point light needs the reference distance
  EXPECT_THROW((void)build_smoothies(v, e, light, options), std::invalid_argument);
  options.space = SmoothieSpace::world;
  EXPECT_THROW((void)build_smoothies(v, e, Light{{0.0, 0.0, 0.0, 0.0}}, options), std::invalid_argument);
  SmoothieEdges bad = e;
  bad.occluder_side = {0};
  EXPECT_THROW((void)build_smoothies(v, bad, light, options), std::invalid_argument);
  bad = e;
  bad.edges = {{0, 9}};
  EXPECT_THROW((void)build_smoothies(v, bad, light, options), std::invalid_argument);
  bad = e;
  bad.first_face = {0, 3};
  EXPECT_THROW((void)build_smoothies(v, bad, light, options), std::invalid_argument);
  std::vector<Vec3> nan_vertices = v;
  nan_vertices[1][0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)build_smoothies(nan_vertices, e, light, options), std::invalid_argument);
  EXPECT_EQ(parse_smoothie_space("light"), SmoothieSpace::light);
  EXPECT_EQ(parse_smoothie_space("world"), SmoothieSpace::world);
  EXPECT_FALSE(parse_smoothie_space("image").has_value());
}

}  // namespace
}  // namespace shadowcert
