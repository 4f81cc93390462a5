// contour/smooth_volume.h: the shadow volumes of discrete, accurate and smooth silhouettes are
// closed, certified exactly (exact/volume_closure.h) for random point and directional lights on
// closed, open and creased casters; the smooth one carries its gap strip and contour.
#include "contour/smooth_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <set>

#include "core/vector3.h"
#include "exact/volume_closure.h"
#include "scene/procedural_mesh.h"
#include "support/contour_test_support.h"

namespace {

using namespace shadowcert;
using test_support::caster_of;
using test_support::face_sides;
using test_support::lit_faces;

Soup open_hemisphere() {
  const Soup sphere = uv_sphere({0, 0, 0}, 1.0, 16, 8);
  Soup half = sphere;
  half.triangles.clear();
  for (const Triangle& t : sphere.triangles)
    if (sphere.vertices[t[0]][2] + sphere.vertices[t[1]][2] + sphere.vertices[t[2]][2] > 0.0) half.triangles.push_back(t);
  return half;
}

struct NamedCaster {
  const char* name;
  SmoothCaster caster;
};

std::vector<NamedCaster> casters() {
  return {{"uv sphere 12x6", caster_of(uv_sphere({0, 0, 0}, 1.0, 12, 6))},
          {"torus", caster_of(torus({0, 0, 0}, 1.0, 0.4, 16, 8))},
          {"open hemisphere", caster_of(open_hemisphere())},
          {"box (every edge a crease)", caster_of(box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}))},
          {"icosphere, computed normals", caster_of(icosphere({0, 0, 0}, 1.0, 1), {.use_file_normals = false})}};
}

// A point light 1.5 to 5 radii from the origin, or a directional light, from `random`.
Light random_light(std::mt19937_64& random, bool directional) {
  std::normal_distribution<double> normal;
  Vec3 d{normal(random), normal(random), normal(random)};
  d = normalized(d);
  if (directional) return Light{{d[0], d[1], d[2], 0.0}};
  const double r = std::uniform_real_distribution<double>(1.5, 5.0)(random);
  return Light{{r * d[0], r * d[1], r * d[2], 1.0}};
}

bool closed_caster(const SmoothCaster& c) {
  for (const auto& t : c.across)
    for (std::uint32_t a : t)
      if (a == kBorder) return false;
  return true;
}

void expect_closed(const SmoothVolume& v, const std::string& what) {
  const VolumeClosure closure = certify_volume_closure(v.mesh);
  EXPECT_TRUE(closure.certificate.closed) << what;
}

TEST(SmoothShadowVolume, ThousandRandomLightsPerCaster_EveryMethodIsClosed) {
  const std::uint64_t seed = 20261202;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 random(seed);
  for (const NamedCaster& c : casters()) {
    for (int i = 0; i < 1000; ++i) {
      const Light light = random_light(random, i % 2 == 1);
      const std::string what = std::string(c.name) + ", light " + std::to_string(i);
      const SmoothVolume smooth = smooth_shadow_volume(c.caster, light, {.method = SilhouetteMethod::smooth});
      expect_closed(smooth, what + ", smooth");
      if (closed_caster(c.caster)) {
        // X's boundary is the contour alone, twice (the lit and the unlit part): two side quads (two
        // triangles for a directional light) per contour segment, no T-junction left open.
        std::size_t segments = 0;
        for (const SmoothContour& contour : smooth.contours) segments += contour.points.size();
        EXPECT_EQ(smooth.side_triangles, 2 * (light.directional() ? 1 : 2) * segments) << what;
      }
      if (i % 10 == 0) {
        // With the cut caps set behind the surface (the GL path's depth band): still closed.
        expect_closed(smooth_shadow_volume(c.caster, light, {.method = SilhouetteMethod::smooth, .cap_offset = 0.01}),
                      what + ", smooth with a cap offset");
        expect_closed(smooth_shadow_volume(c.caster, light, {.method = SilhouetteMethod::accurate}), what + ", accurate");
        expect_closed(smooth_shadow_volume(c.caster, light, {.method = SilhouetteMethod::discrete},
                                           face_sides(c.caster, light)),
                      what + ", discrete");
      }
      if (::testing::Test::HasFailure()) return;
    }
  }
}

TEST(SmoothShadowVolume, SmoothSphere_HasItsStripContourAndBackCap) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 12, 6));
  const Light light{{0.3, 0.2, 4.0, 1.0}};
  const SmoothVolume smooth = smooth_shadow_volume(c, light, {.method = SilhouetteMethod::smooth, .epsilon = 0.003});
  const SmoothVolume accurate = smooth_shadow_volume(c, light, {.method = SilhouetteMethod::accurate});
  ASSERT_EQ(smooth.contours.size(), 1u);
  ASSERT_EQ(smooth.loops.size(), 1u);
  // The contour has more points than the loop; each contour segment adds its strip quad twice,
  // and X's boundary is exactly the contour twice (no T-junction left open: every partner point
  // is a vertex of its cap piece on both sides), two side quads per segment.
  const std::size_t extra = smooth.contours[0].points.size() - smooth.loops[0].points.size();
  EXPECT_GT(extra, 0u);
  EXPECT_GE(smooth.cap_triangles, accurate.cap_triangles + 4 * smooth.contours[0].points.size());
  EXPECT_EQ(smooth.side_triangles, 4 * smooth.contours[0].points.size());
  EXPECT_EQ(accurate.side_triangles, 4 * accurate.loops[0].points.size());
  // Point light: back cap = X at infinity, so the mesh has X twice plus the sides.
  EXPECT_EQ(smooth.mesh.triangles.size(), 2 * smooth.cap_triangles + smooth.side_triangles);
  for (const auto& v : smooth.mesh.vertices) EXPECT_TRUE(v[3] == 0.0f || v[3] == 1.0f);
}

// Two smooth halves of a sphere meeting at a crease (the equator's normals bent apart): the
// silhouette crosses it along crease pieces, whose partner points must be vertices of the lit
// side's front cap too, so X's boundary is still exactly the contour.
TEST(SmoothShadowVolume, CreaseCrossings_LeaveNoTJunction) {
  Soup sphere = uv_sphere({0, 0, 0}, 1.0, 24, 12);
  const std::size_t n = sphere.vertices.size();
  std::vector<std::uint32_t> twin(n, 0);
  for (std::size_t v = 0; v < n; ++v)
    if (sphere.vertices[v][1] == 0.0) {
      sphere.normals[v] = {float(sphere.vertices[v][0]), 0.3f, float(sphere.vertices[v][2])};
      twin[v] = static_cast<std::uint32_t>(sphere.vertices.size());
      sphere.vertices.push_back(sphere.vertices[v]);
      sphere.normals.push_back({float(sphere.vertices[v][0]), -0.3f, float(sphere.vertices[v][2])});
    }
  for (Triangle& t : sphere.triangles)
    if (sphere.vertices[t[0]][1] + sphere.vertices[t[1]][1] + sphere.vertices[t[2]][1] < 0.0)
      for (std::uint32_t& v : t)
        if (v < n && sphere.vertices[v][1] == 0.0) v = twin[v];
  const SmoothCaster c = caster_of(sphere);
  for (const Light& light : {Light{{1.0, 0.05, 0.3, 0.0}}, Light{{3.0, 0.2, 1.0, 1.0}}}) {
    const SmoothVolume v = smooth_shadow_volume(c, light, {.method = SilhouetteMethod::smooth, .epsilon = 0.003});
    ASSERT_EQ(v.contours.size(), 1u);
    const std::size_t per_edge = light.directional() ? 2 : 4;
    EXPECT_EQ(v.side_triangles, per_edge * v.contours[0].points.size());
    expect_closed(v, "crease sphere");
  }
}

TEST(SmoothShadowVolume, LightInAFloorsPlane_CastsNothing) {
  // f = 0 at every corner: lit by the fixed rule, but the light lies in the plane the normals
  // describe, so the floor casts nothing (as its exact light side 0), for every method.
  const SmoothCaster c = caster_of(floor_quad(2.0));
  const Light in_plane{{0.5, 0.0, 3.0, 1.0}};
  for (SilhouetteMethod method : {SilhouetteMethod::accurate, SilhouetteMethod::smooth}) {
    const SmoothVolume v = smooth_shadow_volume(c, in_plane, {.method = method});
    EXPECT_TRUE(v.mesh.triangles.empty());
  }
  const std::vector<Sign> zero(c.triangles.size(), Sign::zero);
  EXPECT_TRUE(smooth_shadow_volume(c, in_plane, {.method = SilhouetteMethod::discrete}, zero).mesh.triangles.empty());
}

TEST(SmoothShadowVolume, DirectionalLight_HasNoBackCapAndOneFarPoint) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 12, 6));
  const SmoothVolume v = smooth_shadow_volume(c, Light{{0.2, 1.0, 0.1, 0.0}});
  EXPECT_EQ(v.mesh.triangles.size(), v.cap_triangles + v.side_triangles);
  std::size_t far = 0;
  for (const auto& p : v.mesh.vertices) far += p[3] == 0.0f;
  EXPECT_EQ(far, 1u);
  expect_closed(v, "directional");
}

// The cap offset moves exactly the cut points of the caps: on a sphere lit from outside, every
// cap vertex that is not a mesh vertex lies the offset inside (within rounding), the mesh
// vertices stay; the sides still rise from the loop on the surface, the same as without offset,
// a strip joining them to the caps (accurate; smooth's contour is displaced anyway). Closed.
TEST(SmoothShadowVolume, CapOffset_SetsTheCutPointsBehindTheSurfaceButNotTheSides) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 12, 6));
  const Light light{{0.3, 0.2, 4.0, 1.0}};
  const SmoothVolume on = smooth_shadow_volume(c, light, {.method = SilhouetteMethod::accurate});
  const SmoothVolume behind = smooth_shadow_volume(c, light, {.method = SilhouetteMethod::accurate, .cap_offset = 0.01});
  const auto radius = [](const std::array<float, 4>& v) {
    return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
  };
  const auto finite_points = [](const SmoothVolume& v, std::size_t first, std::size_t last) {
    std::set<std::array<float, 4>> points;
    for (std::size_t t = first; t < last; ++t)
      for (std::uint32_t i : v.mesh.triangles[t])
        if (v.mesh.vertices[i][3] == 1.0f) points.insert(v.mesh.vertices[i]);
    return points;
  };
  // Caps: the on-surface volume's cap points, each either kept (a mesh vertex) or moved inwards.
  const std::set<std::array<float, 4>> cap_on = finite_points(on, 0, on.cap_triangles);
  const std::set<std::array<float, 4>> sides_on = finite_points(on, on.cap_triangles, on.cap_triangles + on.side_triangles);
  const std::set<std::array<float, 4>> sides_behind =
      finite_points(behind, behind.cap_triangles, behind.cap_triangles + behind.side_triangles);
  EXPECT_EQ(sides_on, sides_behind);  // the silhouette's extrusion did not move
  std::size_t moved = 0;
  for (const auto& p : finite_points(behind, 0, behind.cap_triangles)) {
    if (cap_on.contains(p)) continue;  // a mesh vertex, or a loop point at the strip's outer edge
    ++moved;
    EXPECT_LT(radius(p), 1.0);
  }
  EXPECT_EQ(moved, on.loops[0].points.size());  // the accurate points set behind, nothing else
  for (const auto& p : finite_points(behind, 0, behind.cap_triangles))
    if (!cap_on.contains(p)) {
      // Its loop point on the surface is the side point nearest to it, 0.01 away.
      double nearest = 1e9;
      for (const auto& q : sides_on) {
        const double dx = double(q[0]) - p[0], dy = double(q[1]) - p[1], dz = double(q[2]) - p[2];
        nearest = std::min(nearest, std::sqrt(dx * dx + dy * dy + dz * dz));
      }
      EXPECT_NEAR(nearest, 0.01, 1e-6);
    }
  EXPECT_TRUE(certify_volume_closure(behind.mesh).certificate.closed);
  EXPECT_THROW((void)smooth_shadow_volume(c, light, {.method = SilhouetteMethod::smooth, .cap_offset = -1.0}),
               std::invalid_argument);
}

// The area of X's triangles (the front cap: the lit part and the unlit part reversed) without
// the strip, in double from the float vertices.
double cap_area(const SmoothVolume& v, std::size_t cap_triangles) {
  double area = 0.0;
  for (std::size_t i = 0; i < cap_triangles; ++i) {
    const auto& t = v.mesh.triangles[i];
    const auto point = [&](std::uint32_t k) {
      const auto& p = v.mesh.vertices[k];
      return Vec3{p[0], p[1], p[2]};
    };
    const Vec3 a = point(t[0]);
    const Vec3 n = cross(difference(point(t[1]), a), difference(point(t[2]), a));
    area += 0.5 * std::sqrt(dot(n, n));
  }
  return area;
}

double soup_area(const SmoothCaster& c) {
  double area = 0.0;
  for (const Triangle& t : c.triangles) {
    const Vec3& a = c.vertices[t[0]];
    const Vec3 n = cross(difference(c.vertices[t[1]], a), difference(c.vertices[t[2]], a));
    area += 0.5 * std::sqrt(dot(n, n));
  }
  return area;
}

// The lit part and the unlit part together cover every triangle once, also where the
// silhouette passes exactly through a vertex (f = 0 there, lit by the fixed rule): the triangles
// around it whose other corners are unlit are wholly unlit and cast with their unlit part.
// Regression: such a triangle's unlit polygon lost the vertex and cast nothing.
TEST(SmoothShadowVolume, SilhouetteThroughAVertex_CapsCoverEveryTriangleOnce) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 12, 6));
  // The sphere's normals are its unit positions: f = v . l - 1 is 0 exactly at the equator
  // vertex (1, 0, 0) for any light with l_x = 1.
  for (const Light& light : {Light{{1.0, 3.0, 0.5, 1.0}}, Light{{1.0, -2.0, -0.25, 1.0}}}) {
    const SmoothVolume v = smooth_shadow_volume(c, light, {.method = SilhouetteMethod::accurate});
    EXPECT_NEAR(cap_area(v, v.cap_triangles), soup_area(c), 1e-5);
    expect_closed(v, "through a vertex");
  }
  const SmoothVolume away = smooth_shadow_volume(c, Light{{0.3, 0.2, 4.0, 1.0}}, {.method = SilhouetteMethod::accurate});
  EXPECT_NEAR(cap_area(away, away.cap_triangles), soup_area(c), 1e-5);
}

// The smooth contour follows the caster: relabelling its vertices, reversing the order of its
// triangles, or moving caster and light together by a rigid motion (a rotation about a skew axis,
// then a translation) moves every contour point with it, up to rounding; the volume keeps its
// size and stays closed. Checked on a sphere and on the crease box, point and directional light.
TEST(SmoothShadowVolume, RelabellingAndRigidMotion_MoveTheContourWithTheCaster) {
  // Rotation by 0.7 rad about the unit axis (1, 2, 2) / 3 (Rodrigues), then a translation.
  const Vec3 axis{1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0};
  const double c = std::cos(0.7), sn = std::sin(0.7);
  const auto rotate = [&](const Vec3& v) {
    const Vec3 k_cross_v = cross(axis, v);
    const double k_dot_v = dot(axis, v);
    Vec3 r{};
    for (std::size_t i = 0; i < 3; ++i) r[i] = v[i] * c + k_cross_v[i] * sn + axis[i] * k_dot_v * (1.0 - c);
    return r;
  };
  const Vec3 shift{3.25, -1.5, 0.75};
  const auto move = [&](const Vec3& v) {
    Vec3 r = rotate(v);
    for (std::size_t i = 0; i < 3; ++i) r[i] += shift[i];
    return r;
  };
  const auto moved_light = [&](const Light& l) {
    const Vec3 p{l.position[0], l.position[1], l.position[2]};
    const Vec3 q = l.directional() ? rotate(p) : move(p);
    return Light{{q[0], q[1], q[2], l.position[3]}};
  };
  const auto contour_points = [](const SmoothVolume& v) {
    std::vector<Vec3> points;
    for (const SmoothContour& contour : v.contours)
      for (const ContourPoint& p : contour.points) points.push_back(p.position);
    std::sort(points.begin(), points.end());
    return points;
  };
  const auto expect_same_points = [](std::vector<Vec3> a, std::vector<Vec3> b, const std::string& what) {
    ASSERT_EQ(a.size(), b.size()) << what;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(a[i][k], b[i][k], 1e-9) << what << ", point " << i;
  };
  for (const bool crease_box : {false, true}) {
    const Soup soup = crease_box ? box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}) : uv_sphere({0, 0, 0}, 1.0, 12, 6);
    for (const Light& light : {Light{{0.3, 0.2, 4.0, 1.0}}, Light{{0.4, 1.0, -0.3, 0.0}}}) {
      const std::string what = std::string(crease_box ? "box" : "sphere") + (light.directional() ? ", sun" : ", point");
      const SmoothVolume original = smooth_shadow_volume(caster_of(soup), light, {.epsilon = 0.003});
      ASSERT_FALSE(original.contours.empty()) << what;

      // Relabelled vertices, triangles in reverse order (each keeps its orientation).
      Soup relabelled = soup;
      const std::size_t n = soup.vertices.size();
      for (std::size_t i = 0; i < n; ++i) {
        relabelled.vertices[n - 1 - i] = soup.vertices[i];
        if (!soup.normals.empty()) relabelled.normals[n - 1 - i] = soup.normals[i];
      }
      for (Triangle& t : relabelled.triangles)
        for (std::uint32_t& v : t) v = static_cast<std::uint32_t>(n - 1 - v);
      std::reverse(relabelled.triangles.begin(), relabelled.triangles.end());
      const SmoothVolume r = smooth_shadow_volume(caster_of(relabelled), light, {.epsilon = 0.003});
      expect_same_points(contour_points(original), contour_points(r), what + ", relabelled");
      EXPECT_EQ(r.mesh.triangles.size(), original.mesh.triangles.size()) << what;

      // Rigid motion of caster, normals and light.
      Soup moved = soup;
      for (Vec3& v : moved.vertices) v = move(v);
      for (auto& nrm : moved.normals) {
        const Vec3 q = rotate(Vec3{nrm[0], nrm[1], nrm[2]});
        nrm = {float(q[0]), float(q[1]), float(q[2])};
      }
      const SmoothVolume m = smooth_shadow_volume(caster_of(moved), moved_light(light), {.epsilon = 0.003});
      std::vector<Vec3> expected;
      for (const Vec3& p : contour_points(original)) expected.push_back(move(p));
      // Float normals rotated and rounded move the Hermite curves by a float ulp: 1e-6 bounds it.
      std::vector<Vec3> got = contour_points(m);
      ASSERT_EQ(got.size(), expected.size()) << what << ", moved";
      std::sort(expected.begin(), expected.end());
      std::sort(got.begin(), got.end());
      for (const Vec3& p : got) {
        double nearest = 1e9;
        for (const Vec3& q : expected) nearest = std::min(nearest, std::sqrt(dot(difference(p, q), difference(p, q))));
        EXPECT_LT(nearest, 1e-6) << what << ", moved";
      }
      EXPECT_EQ(m.mesh.triangles.size(), original.mesh.triangles.size()) << what;
      expect_closed(m, what + ", moved");
    }
  }
}

TEST(SmoothShadowVolume, BadArguments_ThrowNamingTheFunction) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 8, 4));
  const Light light{{0.0, 0.0, 3.0, 1.0}};
  EXPECT_THROW((void)smooth_shadow_volume(c, light, {.method = SilhouetteMethod::smooth, .epsilon = 0.0}),
               std::invalid_argument);
  EXPECT_THROW((void)smooth_shadow_volume(c, light, {.method = SilhouetteMethod::discrete}), std::invalid_argument);
  EXPECT_THROW((void)smooth_shadow_volume(c, Light{{0.0, 0.0, 0.0, 0.0}}), std::invalid_argument);
}

}  // namespace
