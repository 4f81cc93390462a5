// The exact image (reference/exact_image.h, docs/definitions.md#pixel-protocol): the shadow of a sphere over a floor
// against the analytic disc, a square's shadow under a directional light, invariance under
// vertex relabelling, face reversal and translation, a ray exactly through a shared edge, the
// terminator of a triangle facing away from the light, triangles that only receive, and input
// validation.
#include "reference/exact_image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "support/certificate_test_support.h"
#include "exact/count_certificate.h"
#include "core/pixel_ray.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;
using test_support::append;
using test_support::directional_light;
using test_support::point_light;

constexpr double kPi = 3.14159265358979323846;

// Where the pixel's centre ray meets the plane y = 0, in double. Only used to sort pixels
// into "well inside" / "well outside" an analytic region, never to decide at its boundary.
Vec3 floor_point(const CameraFrame& frame, std::uint32_t i, std::uint32_t r) {
  const PixelRay ray = pixel_ray(frame, i + 0.5, r + 0.5);
  const double t = -ray.origin[1] / ray.direction[1];
  return {ray.origin[0] + t * ray.direction[0], 0.0, ray.origin[2] + t * ray.direction[2]};
}

// The floor point above is computed with a relative error of a few ulps of the scene's
// coordinates (|x| < 10 here): 1e-9 absorbs it with a wide margin and is far below every band
// the tests leave around an analytic boundary.
constexpr double kFloorPointError = 1e-9;

bool floor_hit(std::uint32_t triangle) { return triangle == 0 || triangle == 1; }  // floor_quad first

std::size_t pixel(const ExactImage& image, std::uint32_t i, std::uint32_t r) { return std::size_t{r} * image.width + i; }

// --- the sphere over a floor, light straight above its centre -------------------------------

struct SphereScene {
  double height = 1.5;  // the sphere's centre above the floor y = 0
  double radius = 1.0;
  std::uint32_t slices = 64;
  std::uint32_t stacks = 32;
  double light_height = 6.0;
};

// The shadow of a ball of radius rho centred on the light's vertical: the cone from the light
// tangent to the ball has half-angle asin(rho / (H - c)) and meets the floor, H below the
// light, in a circle of radius H tan(angle).
double shadow_radius(const SphereScene& s, double rho) {
  const double distance = s.light_height - s.height;
  return s.light_height * rho / std::sqrt(distance * distance - rho * rho);
}

TEST(ExactImage, SphereOverFloor_MatchesTheAnalyticShadowDisc) {
  const SphereScene s;
  Soup soup = floor_quad(8.0);
  append(soup, uv_sphere({0.0, s.height, 0.0}, s.radius, s.slices, s.stacks));
  const std::vector<Light> lights{point_light(0.0, s.light_height, 0.0)};
  Camera camera;
  camera.eye = {0.0, 9.0, 5.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.width = 160;
  camera.height = 120;
  const ExactImage image = exact_image(soup, lights, camera);

  // The tessellated sphere lies between two balls. Its vertices are on the sphere (up to
  // rounding), so it is inside the ball of radius r. Every direction is within angle
  // pi / (2 stacks) (half a ring spacing) + pi / slices (half a slice spacing; a parallel's arc
  // is shorter than its longitude difference) of a vertex, so its support function is at least
  // r cos(that angle): it contains the ball of that radius. The shadow lies between theirs.
  const double angle = kPi / (2.0 * s.stacks) + kPi / s.slices;
  const double inner = shadow_radius(s, s.radius * std::cos(angle)) - kFloorPointError;
  const double outer = shadow_radius(s, s.radius) + kFloorPointError;

  const CameraFrame frame = camera_frame(camera);
  const ExactLightImage& light = image.lights.at(0);
  std::size_t inside = 0, outside = 0, band = 0;
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i) {
      const std::size_t p = pixel(image, i, r);
      if (!floor_hit(image.hit_triangles[p])) continue;
      const Vec3 x = floor_point(frame, i, r);
      const double rho = std::hypot(x[0], x[2]);
      if (rho < inner) {
        // The segment to the light passes through the convex closed sphere: it enters and
        // leaves it, two crossings (unless it grazes an edge: a zero sign, ambiguous).
        if (light.ambiguity[p] == 0) {
          EXPECT_EQ(light.counts[p], 2u) << "pixel " << i << "," << r << " rho " << rho;
          EXPECT_EQ(light.lit[p], 0) << "pixel " << i << "," << r;
        }
        ++inside;
      } else if (rho > outer) {
        EXPECT_EQ(light.counts[p], 0u) << "pixel " << i << "," << r << " rho " << rho;
        EXPECT_EQ(light.lit[p], 255) << "pixel " << i << "," << r;
        EXPECT_EQ(light.ambiguity[p] & kTerminator, 0) << "pixel " << i << "," << r;
        ++outside;
      } else {
        if (light.ambiguity[p] == 0) {
          EXPECT_TRUE(light.counts[p] == 0 || light.counts[p] == 2) << "pixel " << i << "," << r;
        }
        ++band;
      }
    }
  // Not vacuous: the disc (radius ~1.36) is partly hidden by the sphere from this eye, but
  // hundreds of its pixels and thousands of the floor's are seen.
  EXPECT_GT(inside, 200u);
  EXPECT_GT(outside, 5000u);
  EXPECT_EQ(image.stats.rays, std::size_t{161} * 121 + std::size_t{160} * 120);
}

// --- a square under a directional light straight down: its shadow is its own projection ----

TEST(ExactImage, SquareUnderDirectionalLight_ShadowsItsProjection) {
  Soup soup = floor_quad(6.0);
  const double half = 1.0, height = 2.0;
  append(soup, test_support::soup_of({{-half, height, -half}, {half, height, -half}, {half, height, half},
                                      {-half, height, half}},
                                     {{0, 2, 1}, {0, 3, 2}}));
  const std::vector<Light> lights{directional_light(0.0, 1.0, 0.0)};
  Camera camera;
  camera.eye = {4.0, 7.0, 6.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.width = 96;
  camera.height = 72;
  const ExactImage image = exact_image(soup, lights, camera);
  const CameraFrame frame = camera_frame(camera);
  const ExactLightImage& light = image.lights.at(0);
  std::size_t inside = 0, outside = 0;
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i) {
      const std::size_t p = pixel(image, i, r);
      if (!floor_hit(image.hit_triangles[p])) continue;
      const Vec3 x = floor_point(frame, i, r);
      const double d = std::max(std::abs(x[0]), std::abs(x[2]));
      if (d < half - kFloorPointError && light.ambiguity[p] == 0) {
        EXPECT_EQ(light.counts[p], 1u) << "pixel " << i << "," << r;
        ++inside;
      } else if (d > half + kFloorPointError) {
        EXPECT_EQ(light.counts[p], 0u) << "pixel " << i << "," << r;
        ++outside;
      }
    }
  EXPECT_GT(inside, 50u);
  EXPECT_GT(outside, 1000u);
}

// --- invariance ------------------------------------------------------------------------------

// A soup whose coordinates are multiples of 2^-16 (|x| < 2^8): translating it by integers
// below 2^20 is exact, so the translated scene is exactly the same geometry.
Soup snapped(Soup soup) {
  for (Vec3& v : soup.vertices)
    for (double& x : v) x = std::ldexp(std::round(std::ldexp(x, 16)), -16);
  return soup;
}

struct InvarianceScene {
  Soup soup;
  std::vector<Light> lights;
  Camera camera;
};

InvarianceScene invariance_scene() {
  InvarianceScene s;
  s.soup = floor_quad(6.0);
  append(s.soup, icosphere({-1.0, 1.25, 0.5}, 0.75, 2));
  append(s.soup, box({0.75, 0.0, -1.5}, {2.0, 1.5, -0.5}));
  append(s.soup, nonmanifold_fan(6));
  s.soup = snapped(s.soup);
  s.lights = {point_light(1.0, 8.0, 2.0), directional_light(-0.5, 1.0, 0.25)};
  s.camera.eye = {0.0, 6.0, 10.0};
  s.camera.target = {0.0, 0.75, -0.5};
  s.camera.width = 64;
  s.camera.height = 48;
  return s;
}

void expect_same_images(const ExactImage& a, const ExactImage& b) {
  ASSERT_EQ(a.lights.size(), b.lights.size());
  EXPECT_EQ(a.hit_triangles, b.hit_triangles);
  for (std::size_t l = 0; l < a.lights.size(); ++l) {
    EXPECT_EQ(a.lights[l].counts, b.lights[l].counts) << "light " << l;
    EXPECT_EQ(a.lights[l].lit, b.lights[l].lit) << "light " << l;
    EXPECT_EQ(a.lights[l].ambiguity, b.lights[l].ambiguity) << "light " << l;
  }
}

TEST(ExactImage, VertexRelabelling_LeavesEveryImageUnchanged) {
  const InvarianceScene s = invariance_scene();
  const ExactImage reference = exact_image(s.soup, s.lights, s.camera);
  const std::uint64_t seed = 20240611;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  std::vector<std::uint32_t> order(s.soup.vertices.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), rng);  // new index of vertex i is order[i]
  Soup relabelled;
  relabelled.vertices.resize(s.soup.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) relabelled.vertices[order[i]] = s.soup.vertices[i];
  for (const Triangle& t : s.soup.triangles) relabelled.triangles.push_back({order[t[0]], order[t[1]], order[t[2]]});
  expect_same_images(reference, exact_image(relabelled, s.lights, s.camera));
}

TEST(ExactImage, FaceReversal_LeavesEveryImageUnchanged) {
  const InvarianceScene s = invariance_scene();
  Soup reversed = s.soup;
  for (Triangle& t : reversed.triangles) std::swap(t[1], t[2]);
  expect_same_images(exact_image(s.soup, s.lights, s.camera), exact_image(reversed, s.lights, s.camera));
}

TEST(ExactImage, Translation_WithTheCamera_LeavesEveryImageUnchanged) {
  const InvarianceScene s = invariance_scene();
  const Vec3 shift{1024.0, -512.0, 65536.0};
  InvarianceScene moved = s;
  for (Vec3& v : moved.soup.vertices)
    for (int k = 0; k < 3; ++k) v[k] += shift[k];
  for (int k = 0; k < 3; ++k) {
    moved.camera.eye[k] += shift[k];
    moved.camera.target[k] += shift[k];
    if (!moved.lights[0].directional()) moved.lights[0].position[k] += shift[k];
  }
  // Exactly the same geometry: every coordinate was a multiple of 2^-16 below 2^8.
  for (std::size_t i = 0; i < s.soup.vertices.size(); ++i)
    ASSERT_EQ(moved.soup.vertices[i][0] - shift[0], s.soup.vertices[i][0]);
  expect_same_images(exact_image(s.soup, s.lights, s.camera), exact_image(moved.soup, moved.lights, moved.camera));
}

// Scaling every coordinate by 2^200 is exact and keeps every sign, so the images are the same.
// The hit points then lie far beyond float range: the per-ray point boxes must keep them exactly
// (reference/detail/hit_point_boxes.h), not as infinite float boxes.
TEST(ExactImage, ScaledByTwoTo200_WithTheCamera_LeavesEveryImageUnchanged) {
  const InvarianceScene s = invariance_scene();
  InvarianceScene scaled = s;
  const auto scale = [](double x) { return std::ldexp(x, 200); };
  for (Vec3& v : scaled.soup.vertices)
    for (double& x : v) x = scale(x);
  for (int k = 0; k < 3; ++k) {
    scaled.camera.eye[k] = scale(scaled.camera.eye[k]);
    scaled.camera.target[k] = scale(scaled.camera.target[k]);
    if (!scaled.lights[0].directional()) scaled.lights[0].position[k] = scale(scaled.lights[0].position[k]);
  }
  const ExactImage a = exact_image(s.soup, s.lights, s.camera);
  const ExactImage b = exact_image(scaled.soup, scaled.lights, scaled.camera);
  expect_same_images(a, b);
  // Not a vacuous agreement: the scene shows lit and shadowed pixels.
  const auto lit = std::count(a.lights[0].lit.begin(), a.lights[0].lit.end(), std::uint8_t{255});
  const auto shadowed = std::count_if(a.lights[0].counts.begin(), a.lights[0].counts.end(),
                                      [](std::uint32_t n) { return n != 0 && n != kNoHit && n != kUndefinedCount; });
  EXPECT_GT(lit, 0);
  EXPECT_GT(shadowed, 0);
}

// --- zero signs and the terminator -----------------------------------------------------------

// A camera straight above the origin, looking down, 3x3 pixels of equal aspect: the rays of
// the diagonal pixels (i, i) and the corners (i, i) pass exactly through the floor quad's
// shared diagonal x = z (directions (a, -1, a) with a rounded identically for x and z).
Camera top_down_camera() {
  Camera camera;
  camera.eye = {0.0, 4.0, 0.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.up = {0.0, 0.0, -1.0};  // image x is world +x, image y (down) is world +z
  camera.width = 3;
  camera.height = 3;
  return camera;
}

TEST(ExactImage, RayThroughSharedEdge_IsAZeroSignNotAGuess) {
  const Soup soup = floor_quad(4.0);
  const std::vector<Light> lights{point_light(0.5, 5.0, -0.25)};
  const Camera camera = top_down_camera();
  const CameraFrame frame = camera_frame(camera);
  for (std::uint32_t i = 0; i < 3; ++i) {  // the premise: these rays meet y = 0 on x = z exactly
    const PixelRay ray = pixel_ray(frame, i + 0.5, i + 0.5);
    ASSERT_EQ(ray.direction[0], ray.direction[2]);
    ASSERT_EQ(ray.origin[0], ray.origin[2]);
  }
  const ExactImage image = exact_image(soup, lights, camera);
  const ExactLightImage& light = image.lights.at(0);
  for (std::uint32_t i = 0; i < 3; ++i) {
    const std::size_t p = pixel(image, i, i);
    EXPECT_NE(light.ambiguity[p] & kZeroSign, 0) << "pixel " << i << "," << i;
    EXPECT_EQ(light.counts[p], kUndefinedCount);
    EXPECT_EQ(light.lit[p], 0);
    EXPECT_EQ(image.hit_triangles[p], 0u);  // the smaller index of the two triangles met
  }
  // Pixels (2, 0) and (0, 2) lie inside one triangle each, every footprint ray off the edge.
  for (const auto& [i, r, triangle] : {std::array<std::uint32_t, 3>{2, 0, 1}, std::array<std::uint32_t, 3>{0, 2, 0}}) {
    const std::size_t p = pixel(image, i, r);
    EXPECT_EQ(image.hit_triangles[p], triangle) << "pixel " << i << "," << r;
    EXPECT_EQ(light.ambiguity[p], 0) << "pixel " << i << "," << r;
    EXPECT_EQ(light.counts[p], 0u);
    EXPECT_EQ(light.lit[p], 255);
  }
}

// A tiny triangle halfway between the eye and one floor triangle, lit from straight above:
// from the eye it is seen inside pixel (2, 0)'s footprint, and its shadow falls inside pixel
// (1, 1)'s, each between the corner rays and the centre ray, which all see the bare floor.
TEST(ExactImage, FeaturesBetweenTheCornerRays_MakeTheirPixelsAmbiguous) {
  Soup soup = test_support::soup_of({{-20.0, 0.0, 20.0}, {20.0, 0.0, 20.0}, {0.0, 0.0, -20.0}}, {{0, 1, 2}});
  // Floor pixel (2, 0) spans x in [0.55, 1.66], z in [-1.66, -0.55]; the ray through the floor
  // point (0.8, 0, -0.8) passes (0.4, 2, -0.4). The light above it casts that point's shadow
  // on (0.4, 0, -0.4), inside pixel (1, 1), whose centre is the origin.
  append(soup, test_support::soup_of({{0.4, 2.0, -0.4}, {0.41, 2.0, -0.4}, {0.4, 2.0, -0.41}}, {{0, 1, 2}}));
  const std::vector<Light> lights{point_light(0.4, 10.0, -0.4)};
  const ExactImage image = exact_image(soup, lights, top_down_camera());
  const ExactLightImage& light = image.lights.at(0);
  for (std::size_t p = 0; p < image.hit_triangles.size(); ++p) {
    EXPECT_EQ(image.hit_triangles[p], 0u) << "pixel " << p;  // every centre sees the floor, lit
    EXPECT_EQ(light.counts[p], 0u) << "pixel " << p;
  }
  EXPECT_EQ(light.ambiguity[pixel(image, 2, 0)], kFootprintTriangles);
  EXPECT_EQ(light.ambiguity[pixel(image, 1, 1)], kFootprintCounts);
  EXPECT_EQ(light.ambiguity[pixel(image, 0, 2)], 0);
  EXPECT_EQ(light.ambiguity[pixel(image, 2, 2)], 0);
}

// The same tiny triangle (moved off pixel (2, 0)'s centre ray) with no floor: every ray of
// every pixel sees nothing, yet GL may draw the triangle over (2, 0)'s centre, which passes
// within a rounding of its edge (fuzz --gl seed 202 case 1706: 0.001 px, a vertex inside a
// sky pixel). The eye pyramid of a pixel whose rays all miss runs to a plane beyond the scene.
TEST(ExactImage, TriangleBetweenTheRaysOfAnEmptyPixel_MakesItAmbiguous) {
  const Soup soup = test_support::soup_of({{0.42, 2.0, -0.42}, {0.43, 2.0, -0.42}, {0.42, 2.0, -0.43}}, {{0, 1, 2}});
  const std::vector<Light> lights{point_light(0.4, 10.0, -0.4)};
  const ExactImage image = exact_image(soup, lights, top_down_camera());
  for (std::size_t p = 0; p < image.hit_triangles.size(); ++p) EXPECT_EQ(image.hit_triangles[p], kNoHit) << p;
  const ExactLightImage& light = image.lights.at(0);
  EXPECT_EQ(light.ambiguity[pixel(image, 2, 0)], kFootprintTriangles);
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i)
      if (i != 2 || r != 0) {
        EXPECT_EQ(light.ambiguity[pixel(image, i, r)], 0) << i << ", " << r;
      }
}

// With a depth band (ExactImageOptions::depth_band), surfaces and volume faces that pass within
// it of P make the pixel ambiguous; without one they do not.
TEST(ExactImage, DepthBand_MarksNearlyCoincidentSurfacesAndGrazingVolumeFaces) {
  constexpr double kBand = 1e-3;  // any fixed band: the test is about what it includes
  ExactImageOptions banded;
  banded.depth_band = [](double) { return kBand; };
  Camera camera = top_down_camera();
  camera.width = camera.height = 8;
  // A second floor 1e-6 below the first: hidden, but within the band.
  Soup doubled = floor_quad(4.0);
  Soup lower = floor_quad(4.0);
  for (Vec3& v : lower.vertices) v[1] = -1e-6;
  append(doubled, lower);
  const std::vector<Light> above{point_light(0.25, 3.0, 0.5)};
  // The light 1e-9 above the floor's plane: the floor's own side faces run just below it.
  const std::vector<Light> grazing{point_light(0.25, 1e-9, 3.0)};
  const auto count = [](const ExactImage& image, std::uint8_t bit) {
    std::size_t n = 0;
    for (std::uint8_t a : image.lights.at(0).ambiguity) n += (a & bit) != 0;
    return n;
  };
  // Off the diagonal's footprints (|i - r| >= 2: 42 of 64 pixels) nothing else is ambiguous.
  EXPECT_EQ(count(exact_image(doubled, above, camera), kDepthBand), 0u);
  EXPECT_EQ(count(exact_image(doubled, above, camera, banded), kDepthBand), 42u);
  EXPECT_EQ(count(exact_image(floor_quad(4.0), grazing, camera), kDepthBand), 0u);
  // The side face of the shared diagonal x = z runs away from the light (on the side z > x)
  // just below the floor: it passes under the triangle beyond it (x > z, triangle 1) only.
  const ExactImage grazed = exact_image(floor_quad(4.0), grazing, camera, banded);
  EXPECT_EQ(count(grazed, kDepthBand), 21u);
  for (std::uint32_t r = 0; r < 8; ++r)
    for (std::uint32_t i = 0; i < 8; ++i) {
      if (std::max(i, r) - std::min(i, r) < 2) continue;
      const std::size_t p = pixel(grazed, i, r);
      EXPECT_EQ((grazed.lights[0].ambiguity[p] & kDepthBand) != 0, grazed.hit_triangles[p] == 1) << i << "," << r;
      EXPECT_EQ(grazed.lights[0].counts[p], 0u);  // lit, exactly
    }
}

// --- triangles that only receive (ExactImageOptions::casts, a mesh's "casts": false) ----------

// A floor, a closed box high above it and, between them, a square that only receives.
TEST(ExactImage, NonCastingTriangles_AreSeenAndHideButCastNothing) {
  Soup without = floor_quad(6.0);                            // triangles 0, 1
  append(without, box({-0.5, 3.0, -0.5}, {0.5, 3.5, 0.5}));  // 2 to 13
  Soup with = without;
  append(with, test_support::soup_of({{-1.5, 2.0, -1.5}, {1.5, 2.0, -1.5}, {1.5, 2.0, 1.5}, {-1.5, 2.0, 1.5}},
                                     {{0, 2, 1}, {0, 3, 2}}));  // 14, 15: the square, last
  ASSERT_EQ(with.triangles.size(), 16u);
  ExactImageOptions receiving;
  receiving.casts.assign(16, 1);
  receiving.casts[14] = receiving.casts[15] = 0;
  const std::vector<Light> lights{point_light(0.5, 8.0, 0.3)};
  Camera camera;
  camera.eye = {4.0, 7.0, 6.0};
  camera.target = {0.0, 0.5, 0.0};
  camera.width = 96;
  camera.height = 72;
  const ExactImage image = exact_image(with, lights, camera, receiving);
  const ExactImage casting = exact_image(with, lights, camera);
  const ExactImage absent = exact_image(without, lights, camera);

  // It hides as a caster does: the same triangle seen at every pixel.
  EXPECT_EQ(image.hit_triangles, casting.hit_triangles);
  const ExactLightImage& l = image.lights.at(0);
  std::size_t unshadowed = 0, square_seen = 0, square_shadowed = 0;
  for (std::size_t p = 0; p < l.counts.size(); ++p) {
    const std::uint32_t h = image.hit_triangles[p];
    if (h == kNoHit || l.ambiguity[p] != 0) continue;
    if (h < 14) {
      // Where the floor or the box is seen, n(P) is that of the scene without the square.
      EXPECT_EQ(absent.hit_triangles[p], h) << p;
      EXPECT_EQ(l.counts[p], absent.lights[0].counts[p]) << p;
      if (casting.lights[0].ambiguity[p] == 0 && casting.lights[0].counts[p] != l.counts[p]) ++unshadowed;
    } else {
      // It still receives: the box's shadow (two crossings of the closed box) falls on it.
      ++square_seen;
      EXPECT_TRUE(l.counts[p] == 0 || l.counts[p] == 2) << p;
      square_shadowed += l.counts[p] == 2;
    }
  }
  // Not vacuous: the square casting would shadow part of the floor, and the box shadows it.
  EXPECT_GT(unshadowed, 100u);
  EXPECT_GT(square_seen, 200u);
  EXPECT_GT(square_shadowed, 20u);
}

// The floor of DepthBand_MarksNearlyCoincidentSurfacesAndGrazingVolumeFaces with the light 1e-9
// above it: its diagonal's side face grazes it. A floor that only receives has no volume face.
TEST(ExactImage, NonCastingFloor_HasNoVolumeFaceInTheDepthBandAndIsStillItsOwnTerminator) {
  ExactImageOptions banded;
  banded.depth_band = [](double) { return 1e-3; };
  Camera camera = top_down_camera();
  camera.width = camera.height = 8;
  const std::vector<Light> grazing{point_light(0.25, 1e-9, 3.0)};
  const ExactImage cast = exact_image(floor_quad(4.0), grazing, camera, banded);
  banded.casts = {0, 0};
  const ExactImage received = exact_image(floor_quad(4.0), grazing, camera, banded);
  std::size_t band_pixels = 0;
  for (std::size_t p = 0; p < received.hit_triangles.size(); ++p) {
    band_pixels += (cast.lights[0].ambiguity[p] & kDepthBand) != 0;
    EXPECT_EQ(received.lights[0].ambiguity[p] & kDepthBand, 0) << p;
    EXPECT_EQ(received.lights[0].ambiguity[p], cast.lights[0].ambiguity[p] & ~kDepthBand) << p;
    EXPECT_EQ(received.lights[0].counts[p], cast.lights[0].counts[p]) << p;
  }
  EXPECT_GT(band_pixels, 0u);
  // Lit from below, it is its own terminator whether it casts or not.
  const std::vector<Light> below{point_light(0.25, -3.0, 0.5)};
  const ExactImage from_below = exact_image(floor_quad(4.0), below, camera, banded);
  for (std::uint8_t a : from_below.lights[0].ambiguity)
    EXPECT_TRUE((a & kTerminator) != 0 || (a & kZeroSign) != 0);  // a centre on the diagonal: no hit to judge
}

TEST(ExactImage, TriangleFacingAwayFromTheLight_IsTerminatorAmbiguous) {
  const Soup soup = floor_quad(4.0);
  // One light below the floor (the floor faces away from it, seen from above), one above.
  const std::vector<Light> lights{point_light(0.25, -3.0, 0.5), point_light(0.25, 3.0, 0.5)};
  Camera camera = top_down_camera();
  camera.width = 8;
  camera.height = 8;
  const ExactImage image = exact_image(soup, lights, camera);
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i) {
      const std::size_t p = pixel(image, i, r);
      ASSERT_NE(image.hit_triangles[p], kNoHit);  // the floor fills this view
      // Footprints that reach the diagonal (|i - r| < 2) have rays exactly on the shared edge.
      if (std::max(i, r) - std::min(i, r) < 2) continue;
      EXPECT_EQ(image.lights[0].ambiguity[p], kTerminator) << "pixel " << i << "," << r;
      EXPECT_EQ(image.lights[1].ambiguity[p], 0) << "pixel " << i << "," << r;
    }
}

TEST(ExactImage, DirectionalLightInTheHitPlane_IsTerminatorAmbiguous) {
  const Soup soup = floor_quad(4.0);
  const std::vector<Light> lights{directional_light(1.0, 0.0, 0.0)};  // grazing: s = 0 for the floor
  Camera camera = top_down_camera();
  camera.width = 4;
  camera.height = 4;
  const ExactImage image = exact_image(soup, lights, camera);
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i) {
      if (std::max(i, r) - std::min(i, r) < 2) continue;  // footprints on the diagonal edge
      const std::size_t p = pixel(image, i, r);
      EXPECT_EQ(image.lights[0].ambiguity[p], kTerminator) << "pixel " << i << "," << r;
      EXPECT_EQ(image.lights[0].lit[p], 255) << "pixel " << i << "," << r;  // n(P) = 0: nothing else casts
    }
}

// --- independent references: a float ray caster for hits, OccluderCounter for counts --------

// The nearest triangle along the ray in double (Moller-Trumbore), for pixels whose whole
// footprint sees one triangle: their centre is far from every edge in the image, so rounding
// cannot change the answer there.
std::uint32_t float_first_hit(const Soup& soup, const PixelRay& ray) {
  std::uint32_t best = kNoHit;
  double best_t = std::numeric_limits<double>::infinity();
  for (std::uint32_t id = 0; id < soup.triangles.size(); ++id) {
    const Vec3& a = soup.vertices[soup.triangles[id][0]];
    const Vec3& b = soup.vertices[soup.triangles[id][1]];
    const Vec3& c = soup.vertices[soup.triangles[id][2]];
    const Vec3 e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Vec3 p = cross(ray.direction, e2);
    const double det = dot(e1, p);
    if (det == 0.0) continue;
    const Vec3 s{ray.origin[0] - a[0], ray.origin[1] - a[1], ray.origin[2] - a[2]};
    const double u = dot(s, p) / det;
    const Vec3 q = cross(s, e1);
    const double v = dot(ray.direction, q) / det;
    const double t = dot(e2, q) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0 || t <= 0.0 || t >= best_t) continue;
    best_t = t;
    best = id;
  }
  return best;
}

TEST(ExactImage, UnambiguousPixels_AgreeWithAFloatRayCasterAndTheOccluderCounter) {
  const InvarianceScene s = invariance_scene();
  const ExactImage image = exact_image(s.soup, s.lights, s.camera);
  const CameraFrame frame = camera_frame(s.camera);
  std::vector<OccluderCounter> counters;
  for (const Light& light : s.lights) counters.emplace_back(s.soup, light);
  std::size_t hits_checked = 0, counts_checked = 0;
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i) {
      const std::size_t p = pixel(image, i, r);
      if ((image.lights[0].ambiguity[p] & (kFootprintTriangles | kZeroSign)) != 0) continue;
      EXPECT_EQ(image.hit_triangles[p], float_first_hit(s.soup, pixel_ray(frame, i + 0.5, r + 0.5)))
          << "pixel " << i << "," << r;
      ++hits_checked;
      if (!floor_hit(image.hit_triangles[p])) continue;
      // On the floor (y = 0, facing the lights): the double floor point lifted by 2^-30 sees
      // the same occluders as P unless a shadow boundary passes within ~1e-9 of the pixel
      // centre, which the pixel's agreeing corners make implausible; the lift keeps the
      // floor itself out of the count, as P's own triangle is (docs/definitions.md#pixel-protocol).
      Vec3 x = floor_point(frame, i, r);
      x[1] = std::ldexp(1.0, -30);
      for (std::size_t l = 0; l < s.lights.size(); ++l) {
        if (image.lights[l].ambiguity[p] != 0) continue;
        const std::optional<std::uint32_t> n = counters[l].count(x);
        ASSERT_TRUE(n.has_value()) << "pixel " << i << "," << r;
        EXPECT_EQ(image.lights[l].counts[p], *n) << "pixel " << i << "," << r << " light " << l;
        ++counts_checked;
      }
    }
  EXPECT_GT(hits_checked, 1500u);
  EXPECT_GT(counts_checked, 1500u);
}

// --- count groups whose candidates are the light grid's wide triangles alone ------------------

// A floor under a wide tilted awning, both wide enough for the light grid to list them apart
// (LightGrid::big()), and a small icosphere above one corner of the awning, whose triangles the
// grid's cells list. Most count groups' cells then list nothing nearer to the light than their
// points, which count against big() alone: the floor's other half (in the point's plane,
// passed by) and the awning above (counted where its shadow falls). Every unambiguous floor
// pixel's count must be OccluderCounter's, in the awning's shadow and beside it; a group that
// took the awning for a triangle of the floor's plane would count 0 under it.
TEST(ExactImage, FloorUnderAWideAwning_CountsFromTheGridsWideTrianglesAgreeWithTheOccluderCounter) {
  Soup soup = floor_quad(6.0);  // triangles 0 and 1 (floor_hit)
  const auto awning = static_cast<std::uint32_t>(soup.vertices.size());
  soup.vertices.push_back({-3.0, 2.0, -2.0});
  soup.vertices.push_back({3.0, 2.25, -2.0});
  soup.vertices.push_back({0.0, 2.125, 2.5});
  soup.triangles.push_back({awning, awning + 1, awning + 2});
  append(soup, icosphere({2.0, 3.5, 1.5}, 0.25, 2));
  soup = snapped(soup);
  const std::vector<Light> lights{point_light(0.5, 7.0, 0.25)};
  Camera camera;
  camera.eye = {0.0, 1.0, 4.5};  // below the awning, looking down at the floor under it
  camera.target = {0.0, 0.0, 0.0};
  camera.width = 64;
  camera.height = 48;
  const ExactImage image = exact_image(soup, lights, camera);
  const CameraFrame frame = camera_frame(camera);
  const OccluderCounter counter(soup, lights[0]);
  std::size_t shadowed = 0, lit = 0;
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i) {
      const std::size_t p = pixel(image, i, r);
      if (!floor_hit(image.hit_triangles[p]) || image.lights[0].ambiguity[p] != 0) continue;
      // As in UnambiguousPixels_AgreeWithAFloatRayCasterAndTheOccluderCounter: the double floor
      // point lifted by 2^-30 sees the occluders P sees.
      Vec3 x = floor_point(frame, i, r);
      x[1] = std::ldexp(1.0, -30);
      const std::optional<std::uint32_t> n = counter.count(x);
      ASSERT_TRUE(n.has_value()) << "pixel " << i << "," << r;
      EXPECT_EQ(image.lights[0].counts[p], *n) << "pixel " << i << "," << r;
      (*n == 0 ? lit : shadowed) += 1;
    }
  EXPECT_GT(shadowed, 300u) << "floor pixels in the awning's shadow";
  EXPECT_GT(lit, 100u) << "floor pixels beside it";
}

// --- tiles too dense to list: their quarters list their own ----------------------------------

// A tile whose cone holds more than the list's cap has its rays traced by quarters, each with
// the list of its own narrower cone (or, still too many, by walks of the tree). Here most 8x8
// tiles see too many of the icosphere's 5,120 triangles to list them (51 of 60 in the two
// images), and about half of their quarters few enough (98 of 204; counted while writing the
// test, which fails when a quarter's list or its corners are cut short): the centre hits must be those of a float ray
// caster, and a window whose tiles are cut elsewhere (offset by 3 and 5 pixels, so every ray
// lands in another tile and quarter) must give every pixel the same answers.
TEST(ExactImage, DenseTiles_TracedByQuarters_AgreeWithAFloatRayCasterAndAShiftedWindow) {
  Soup soup = floor_quad(6.0);
  append(soup, icosphere({0.0, 1.0, 0.0}, 1.0, 4));
  soup = snapped(soup);
  const std::vector<Light> lights{point_light(1.0, 8.0, 2.0)};
  Camera camera;
  camera.eye = {0.0, 1.4, 2.6};
  camera.target = {0.0, 1.0, 0.0};
  camera.width = 48;
  camera.height = 40;
  const ExactImage full = exact_image(soup, lights, camera);
  const CameraFrame frame = camera_frame(camera);
  std::size_t sphere_hits = 0;
  for (std::uint32_t r = 0; r < camera.height; ++r)
    for (std::uint32_t i = 0; i < camera.width; ++i) {
      const std::size_t p = pixel(full, i, r);
      if ((full.view_ambiguity[p] & kZeroSign) != 0) continue;
      EXPECT_EQ(full.hit_triangles[p], float_first_hit(soup, pixel_ray(frame, i + 0.5, r + 0.5)))
          << "pixel " << i << "," << r;
      sphere_hits += full.hit_triangles[p] != kNoHit && !floor_hit(full.hit_triangles[p]) ? 1 : 0;
    }
  EXPECT_GT(sphere_hits, camera.width * camera.height / 2);
  ExactImageOptions shifted;
  shifted.window = PixelWindow{3, 5, camera.width - 3, camera.height - 5};
  const ExactImage part = exact_image(soup, lights, camera, shifted);
  for (std::uint32_t r = 5; r < camera.height; ++r)
    for (std::uint32_t i = 3; i < camera.width; ++i) {
      const std::size_t p = pixel(full, i, r);
      ASSERT_EQ(part.hit_triangles[p], full.hit_triangles[p]) << i << "," << r;
      ASSERT_EQ(part.view_ambiguity[p], full.view_ambiguity[p]) << i << "," << r;
      ASSERT_EQ(part.lights[0].counts[p], full.lights[0].counts[p]) << i << "," << r;
      ASSERT_EQ(part.lights[0].ambiguity[p], full.lights[0].ambiguity[p]) << i << "," << r;
    }
}

// --- one light at a time gives the same images as all together --------------------------------

TEST(ExactImage, EachLightsImage_IsIndependentOfTheOthers) {
  const InvarianceScene s = invariance_scene();
  const ExactImage both = exact_image(s.soup, s.lights, s.camera);
  for (std::size_t l = 0; l < s.lights.size(); ++l) {
    const ExactImage one = exact_image(s.soup, std::vector<Light>{s.lights[l]}, s.camera);
    EXPECT_EQ(one.lights.at(0).counts, both.lights.at(l).counts);
    EXPECT_EQ(one.lights.at(0).ambiguity, both.lights.at(l).ambiguity);
  }
  // The scene casts real shadows and has unambiguous pixels of both kinds.
  const ExactLightImage& first = both.lights.at(0);
  std::size_t lit = 0, shadowed = 0;
  for (std::size_t p = 0; p < first.counts.size(); ++p) {
    if (first.ambiguity[p] != 0 || first.counts[p] == kNoHit) continue;
    (first.counts[p] == 0 ? lit : shadowed) += 1;
  }
  EXPECT_GT(lit, 100u);
  EXPECT_GT(shadowed, 10u);
}

// ExactImageOptions::footprints = false (the soft reference's mode): the centres' answers
// unchanged, only the ambiguity bits the centre decides, no corner ray traced.
TEST(ExactImage, WithoutFootprints_CentreAnswersUnchanged) {
  const InvarianceScene s = invariance_scene();
  const ExactImage full = exact_image(s.soup, s.lights, s.camera);
  ExactImageOptions centres;
  centres.footprints = false;
  centres.depth_band = [](double) { return 1.0; };  // not read
  const ExactImage centre = exact_image(s.soup, s.lights, s.camera, centres);
  EXPECT_EQ(centre.hit_triangles, full.hit_triangles);
  EXPECT_EQ(centre.stats.rays, std::uint64_t{s.camera.width} * s.camera.height);
  for (std::size_t l = 0; l < s.lights.size(); ++l) {
    EXPECT_EQ(centre.lights[l].counts, full.lights[l].counts) << "light " << l;
    EXPECT_EQ(centre.lights[l].lit, full.lights[l].lit) << "light " << l;
    for (std::size_t p = 0; p < full.hit_triangles.size(); ++p) {
      const std::uint8_t kept = full.lights[l].ambiguity[p] & (kZeroSign | kTerminator);
      const bool zero_at_centre = full.lights[l].counts[p] == kUndefinedCount;
      EXPECT_EQ(centre.lights[l].ambiguity[p] & ~kTerminator, zero_at_centre ? kZeroSign : 0) << "pixel " << p;
      EXPECT_EQ(centre.lights[l].ambiguity[p] & kTerminator, kept & kTerminator) << "pixel " << p;
    }
  }
}

// ExactImageOptions::light_images = false where the light images are made one at a time (the
// footprints on): no light image kept, and per pixel the sums of the images the lights get.
TEST(ExactImage, WithoutLightImages_TallyIsTheLightImagesSummed) {
  const InvarianceScene s = invariance_scene();
  ASSERT_GE(s.lights.size(), 2u);
  const ExactImage full = exact_image(s.soup, s.lights, s.camera);
  ExactImageOptions sums_only;
  sums_only.light_images = false;
  const ExactImage tallied = exact_image(s.soup, s.lights, s.camera, sums_only);
  EXPECT_TRUE(tallied.lights.empty());
  EXPECT_TRUE(full.tally.defined.empty());
  EXPECT_EQ(tallied.hit_triangles, full.hit_triangles);
  EXPECT_EQ(tallied.view_ambiguity, full.view_ambiguity);
  std::size_t some_defined = 0, some_terminator = 0;
  for (std::size_t p = 0; p < full.hit_triangles.size(); ++p) {
    std::uint32_t defined = 0, lit = 0;
    std::uint8_t terminator = 0;
    for (const ExactLightImage& l : full.lights) {
      defined += l.counts[p] != kNoHit && l.counts[p] != kUndefinedCount ? 1 : 0;
      lit += l.lit[p] != 0 ? 1 : 0;
      if ((l.ambiguity[p] & kTerminator) != 0) terminator = 1;
    }
    EXPECT_EQ(tallied.tally.defined[p], defined) << "pixel " << p;
    EXPECT_EQ(tallied.tally.lit[p], lit) << "pixel " << p;
    EXPECT_EQ(tallied.tally.terminator[p], terminator) << "pixel " << p;
    some_defined += defined > 0 && lit < defined ? 1 : 0;
    some_terminator += terminator;
  }
  EXPECT_GT(some_defined, 10u);  // shadowed samples among them
  EXPECT_GT(some_terminator, 10u);
}

TEST(ExactImage, Window_ImagesItsPixelsAsTheWholeImageAndMarksTheRestOutside) {
  const InvarianceScene s = invariance_scene();
  ExactImageOptions banded;
  banded.depth_band = [](double view_depth) { return 1e-4 * view_depth; };
  const ExactImage full = exact_image(s.soup, s.lights, s.camera, banded);
  // Windows at the image's corners and inside it, one pixel wide and wider.
  for (const PixelWindow w : {PixelWindow{0, 0, 7, 5}, PixelWindow{20, 11, 1, 1}, PixelWindow{45, 30, 19, 18}}) {
    SCOPED_TRACE(std::to_string(w.x) + "," + std::to_string(w.y) + " " + std::to_string(w.width) + "x" +
                 std::to_string(w.height));
    ExactImageOptions options = banded;
    options.window = w;
    const ExactImage part = exact_image(s.soup, s.lights, s.camera, options);
    EXPECT_EQ(part.stats.rays, std::uint64_t{w.width} * w.height + std::uint64_t{w.width + 1} * (w.height + 1));
    std::size_t inside = 0;
    for (std::uint32_t r = 0; r < s.camera.height; ++r)
      for (std::uint32_t i = 0; i < s.camera.width; ++i) {
        const std::size_t p = pixel(full, i, r);
        const bool in = i >= w.x && i < w.x + w.width && r >= w.y && r < w.y + w.height;
        inside += in ? 1 : 0;
        EXPECT_EQ(part.hit_triangles[p], in ? full.hit_triangles[p] : kNoHit) << i << "," << r;
        EXPECT_EQ(part.view_ambiguity[p], in ? full.view_ambiguity[p] : std::uint8_t{kOutsideWindow});
        for (std::size_t l = 0; l < s.lights.size(); ++l) {
          EXPECT_EQ(part.lights[l].counts[p], in ? full.lights[l].counts[p] : kNoHit);
          EXPECT_EQ(part.lights[l].lit[p], in ? full.lights[l].lit[p] : 0);
          EXPECT_EQ(part.lights[l].ambiguity[p], in ? full.lights[l].ambiguity[p] : std::uint8_t{kOutsideWindow});
        }
      }
    EXPECT_EQ(inside, std::size_t{w.width} * w.height);
  }
  ExactImageOptions outside;
  outside.window = PixelWindow{60, 0, 5, 1};  // one column past the 64-wide image
  EXPECT_THROW((void)exact_image(s.soup, s.lights, s.camera, outside), std::invalid_argument);
  outside.window = PixelWindow{3, 3, 0, 1};  // empty
  EXPECT_THROW((void)exact_image(s.soup, s.lights, s.camera, outside), std::invalid_argument);
}

TEST(ExactImage, ProgressReports_CoverEachStage) {
  const InvarianceScene s = invariance_scene();
  ExactImageOptions options;
  std::uint64_t hits_done = 0, hits_total = 0, reports = 0;
  options.progress = [&](std::string_view stage, std::uint64_t done, std::uint64_t total) {
    ++reports;
    if (stage == "hits") {
      hits_done = std::max(hits_done, done);
      hits_total = total;
    }
  };
  const ExactImage image = exact_image(s.soup, s.lights, s.camera, options);
  EXPECT_EQ(hits_total, image.stats.rays);
  EXPECT_EQ(hits_done, hits_total);
  EXPECT_LE(reports, 4u * 102u);  // hits, footprints, then counts for each of two lights
}

// Every stage's reports rise and end at its total, whichever thread reports last: two threads
// that take their shares in one order may reach the report in the other (the sanitizer suite
// once saw a soft reference's samples go from 9216 back to 6706). Many runs of a small image
// give the threads many chances to cross.
TEST(ExactImage, ProgressReports_RiseAndEndAtTheTotalOnEveryRun) {
  const InvarianceScene s = invariance_scene();
  for (int run = 0; run < 20; ++run) {
    SCOPED_TRACE("run " + std::to_string(run));
    ExactImageOptions options;
    std::string stage_now;
    std::uint64_t last = 0, total_now = 0;
    std::size_t stages = 0;
    const auto stage_ends = [&] {
      if (!stage_now.empty()) EXPECT_EQ(last, total_now) << "stage " << stage_now;
    };
    options.progress = [&](std::string_view stage, std::uint64_t done, std::uint64_t total) {
      // A stage begins with a report of 0 (each light's counts are a stage of their own).
      if (stage != stage_now || done == 0) {
        stage_ends();
        stage_now = std::string(stage);
        last = 0;
        ++stages;
      }
      EXPECT_GE(done, last) << "stage " << stage_now;
      EXPECT_LE(done, total) << "stage " << stage_now;
      last = done;
      total_now = total;
    };
    (void)exact_image(s.soup, s.lights, s.camera, options);
    stage_ends();
    EXPECT_GE(stages, 3u);
  }
}

TEST(ExactImage, BadInput_ThrowsNamingTheFunction) {
  Soup soup = floor_quad(1.0);
  soup.triangles.push_back({0, 1, 9});
  Camera camera = top_down_camera();
  try {
    (void)exact_image(soup, std::vector<Light>{point_light(0, 1, 0)}, camera);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("exact_image"), std::string::npos);
  }
  EXPECT_THROW((void)exact_image(floor_quad(1.0), std::vector<Light>{Light{{0, 0, 0, 0}}}, camera),
               std::invalid_argument);
  ExactImageOptions one_flag;
  one_flag.casts = {1};  // the floor has two triangles
  EXPECT_THROW((void)exact_image(floor_quad(1.0), std::vector<Light>{point_light(0, 1, 0)}, camera, one_flag),
               std::invalid_argument);
  camera.target = camera.eye;
  EXPECT_THROW((void)exact_image(floor_quad(1.0), std::vector<Light>{}, camera), std::invalid_argument);
}

}  // namespace
