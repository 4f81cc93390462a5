// contour/smooth_volume.h: the shadow volumes of discrete, accurate and smooth silhouettes are
// closed, certified exactly (exact/volume_closure.h) for random point and directional lights on
// closed, open and creased casters; the smooth one carries its gap strip and contour.
#include "contour/smooth_volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

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

// The cap offset moves exactly the cut points: on a sphere lit from outside, the front-cap
// vertices that are not mesh vertices move inwards by the offset (within rounding), and the mesh
// vertices stay.
TEST(SmoothShadowVolume, CapOffset_SetsTheCutPointsBehindTheSurface) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 12, 6));
  const Light light{{0.3, 0.2, 4.0, 1.0}};
  const SmoothVolume on = smooth_shadow_volume(c, light, {.method = SilhouetteMethod::accurate});
  const SmoothVolume behind = smooth_shadow_volume(c, light, {.method = SilhouetteMethod::accurate, .cap_offset = 0.01});
  ASSERT_EQ(on.mesh.vertices.size(), behind.mesh.vertices.size());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < on.mesh.vertices.size(); ++i) {
    if (on.mesh.vertices[i][3] != 1.0f) continue;
    const auto& a = on.mesh.vertices[i];
    const auto& b = behind.mesh.vertices[i];
    const double ra = std::sqrt(double(a[0]) * a[0] + double(a[1]) * a[1] + double(a[2]) * a[2]);
    const double rb = std::sqrt(double(b[0]) * b[0] + double(b[1]) * b[1] + double(b[2]) * b[2]);
    if (a == b) continue;  // a mesh vertex
    ++moved;
    EXPECT_NEAR(ra - rb, 0.01, 1e-3) << i;  // the interpolated normal is nearly radial
  }
  EXPECT_EQ(moved, on.loops[0].points.size());  // the accurate points, nothing else
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

TEST(SmoothShadowVolume, BadArguments_ThrowNamingTheFunction) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 8, 4));
  const Light light{{0.0, 0.0, 3.0, 1.0}};
  EXPECT_THROW((void)smooth_shadow_volume(c, light, {.method = SilhouetteMethod::smooth, .epsilon = 0.0}),
               std::invalid_argument);
  EXPECT_THROW((void)smooth_shadow_volume(c, light, {.method = SilhouetteMethod::discrete}), std::invalid_argument);
  EXPECT_THROW((void)smooth_shadow_volume(c, Light{{0.0, 0.0, 0.0, 0.0}}), std::invalid_argument);
}

}  // namespace
