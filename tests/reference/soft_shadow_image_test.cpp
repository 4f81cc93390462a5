// The exact soft reference (reference/soft_shadow_image.h, docs/smoothies.md#the-exact-soft-reference):
// R = 0 is the exact hard mask; the image converges as K grows; a square over a floor has the
// umbra and penumbra that similar triangles give; invariance under an exact translation;
// batching changes nothing; the facing flag, progress and misuse.
#include "reference/soft_shadow_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/pixel_ray.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

constexpr double kPi = 3.14159265358979323846;

void append(Soup& to, const Soup& from) {
  append_soup(to, from);
  to.normals.clear();
}

// A uv sphere resting above a floor, lit from above and aside; a camera from the front.
struct SphereScene {
  Soup soup;
  Light light{{0.5, 5.0, 0.3, 1.0}};
  Camera camera;
};

SphereScene sphere_scene(std::uint32_t width, std::uint32_t height) {
  SphereScene s;
  s.soup = floor_quad(6.0);
  s.soup.normals.clear();
  append(s.soup, uv_sphere({0.0, 1.2, 0.0}, 0.8, 24, 12));
  s.camera.eye = {0.0, 6.0, 6.0};
  s.camera.target = {0.0, 0.5, 0.0};
  s.camera.width = width;
  s.camera.height = height;
  return s;
}

TEST(SoftShadowImage, ZeroRadius_IsTheExactHardMask) {
  const SphereScene s = sphere_scene(96, 72);
  const SoftShadowImage soft = disk_light_shadow_image(s.soup, s.light, {0.0, 64, 1}, s.camera);
  const std::vector<Light> lights{s.light};
  const ExactImage hard = exact_image(s.soup, lights, s.camera);
  ASSERT_EQ(soft.samples.size(), 1u);
  EXPECT_EQ(soft.samples[0].position, s.light.position);
  EXPECT_EQ(soft.hit_triangles, hard.hit_triangles);
  std::size_t lit = 0, shadowed = 0, undefined = 0;
  for (std::size_t p = 0; p < soft.pixels(); ++p) {
    const std::uint32_t n = hard.lights[0].counts[p];
    if (n == kNoHit) {
      EXPECT_EQ(soft.region(p), SoftRegion::none);
      EXPECT_EQ(soft.light[p], kNoLight);
    } else if (n == kUndefinedCount) {  // a zero sign: the one sample is left out, no light
      EXPECT_EQ(soft.region(p), SoftRegion::undefined);
      EXPECT_EQ(soft.light[p], kNoLight);
      ++undefined;
    } else {
      EXPECT_EQ(soft.light[p], n == 0 ? 1.0f : 0.0f) << "pixel " << p;
      EXPECT_EQ(soft.light[p] == 1.0f, hard.lights[0].lit[p] == 255);
      EXPECT_EQ(soft.region(p), n == 0 ? SoftRegion::lit : SoftRegion::umbra);
      (n == 0 ? lit : shadowed) += 1;
    }
  }
  EXPECT_GT(lit, 1000u);
  EXPECT_GT(shadowed, 100u);
  std::cout << "R = 0: " << lit << " lit, " << shadowed << " shadowed, " << undefined << " undefined pixels\n";
}

// Mean |a - b| over the pixels where both have a light.
double mean_difference(const SoftShadowImage& a, const SoftShadowImage& b) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t p = 0; p < a.pixels(); ++p)
    if (a.light[p] >= 0.0f && b.light[p] >= 0.0f) {
      sum += std::abs(static_cast<double>(a.light[p]) - b.light[p]);
      ++n;
    }
  return n == 0 ? 0.0 : sum / static_cast<double>(n);
}

TEST(SoftShadowImage, GrowingK_Converges) {
  const SphereScene s = sphere_scene(64, 48);
  const std::uint64_t seed = 20240613;
  std::cout << "seed " << seed << '\n';
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::vector<SoftShadowImage> images;
  for (std::uint32_t k : {4u, 16u, 64u, 256u}) images.push_back(disk_light_shadow_image(s.soup, s.light, {1.0, k, seed}, s.camera));
  // Mean change of light from K to 4K: it shrinks as K grows (stratified: roughly by half per
  // quadrupling on the penumbra's edges), and the penumbra is really there.
  std::vector<double> change;
  for (std::size_t i = 0; i + 1 < images.size(); ++i) change.push_back(mean_difference(images[i], images[i + 1]));
  std::cout << "mean |L_K - L_4K|: K=4 " << change[0] << ", K=16 " << change[1] << ", K=64 " << change[2] << '\n';
  EXPECT_GT(change[0], 0.0);
  EXPECT_LT(change[1], change[0]);
  EXPECT_LT(change[2], change[1]);
  std::size_t penumbra = 0;
  for (std::size_t p = 0; p < images.back().pixels(); ++p) penumbra += images.back().region(p) == SoftRegion::penumbra;
  EXPECT_GT(penumbra, 100u);
}

// --- a square over a floor, seen from below ---------------------------------------------------

// The square [-a, a]^2 at height h over the floor y = 0 (which only receives), the light at
// height H straight above the centre: the disk is horizontal (it faces the centre of the
// bounds, straight below), so along the floor line z = 0 a point x is shadowed by sample
// (s_x, H, s_z) iff |x (1 - k) + s_x k| < a with k = h / H (|s_z| k < a for every sample).
// Hence, similar triangles: umbra |x| < (a - max s_x k) / (1 - k), fully lit |x| > (a - min s_x
// k) / (1 - k), the penumbra between, (max s_x - min s_x) k / (1 - k) wide. The camera looks up
// at the floor from below, so the square hides none of its shadow (a verdict does not depend
// on where the eye is).
struct SquareScene {
  double a = 1.0, h = 1.0, light_height = 4.0, radius = 0.75;
  Soup soup;
  std::vector<std::uint8_t> casts;
  Camera camera;
};

SquareScene square_scene() {
  SquareScene s;
  s.soup = floor_quad(8.0);
  s.soup.normals.clear();
  Soup square;
  square.vertices = {{-s.a, s.h, -s.a}, {s.a, s.h, -s.a}, {s.a, s.h, s.a}, {-s.a, s.h, s.a}};
  square.triangles = {{0, 2, 1}, {0, 3, 2}};
  append(s.soup, square);
  s.casts = {0, 0, 1, 1};
  s.camera.eye = {0.0, -10.0, 0.0};
  s.camera.target = {0.0, 0.0, 0.0};
  s.camera.up = {0.0, 0.0, -1.0};
  s.camera.fov_y_degrees = 2.0 * std::atan(2.4 / 10.0) * 180.0 / kPi;  // the floor's [-2.4, 2.4]^2
  s.camera.width = 200;
  s.camera.height = 200;
  return s;
}

// Where pixel (i, r)'s centre ray meets the floor y = 0, in double (to place pixels against the
// analytic edges, which the test allows a pixel either way).
Vec3 floor_point(const CameraFrame& frame, std::uint32_t i, std::uint32_t r) {
  const PixelRay ray = pixel_ray(frame, i + 0.5, r + 0.5);
  const double t = -ray.origin[1] / ray.direction[1];
  return {ray.origin[0] + t * ray.direction[0], 0.0, ray.origin[2] + t * ray.direction[2]};
}

TEST(SoftShadowImage, SquareOverFloor_UmbraAndPenumbraFollowSimilarTriangles) {
  const SquareScene s = square_scene();
  SoftShadowOptions options;
  options.casts = s.casts;
  const SoftShadowImage image = disk_light_shadow_image(s.soup, Light{{0.0, s.light_height, 0.0, 1.0}},
                                                        {s.radius, 64, 5}, s.camera, options);
  ASSERT_EQ(image.samples.size(), 64u);
  double lo = INFINITY, hi = -INFINITY;
  for (const Light& sample : image.samples) {
    ASSERT_EQ(sample.position[1], s.light_height);  // a horizontal disk
    lo = std::min(lo, sample.position[0]);
    hi = std::max(hi, sample.position[0]);
  }
  const double k = s.h / s.light_height;
  const double umbra_edge = (s.a - hi * k) / (1 - k), lit_edge = (s.a - lo * k) / (1 - k);
  const double left_umbra_edge = (-s.a - lo * k) / (1 - k), left_lit_edge = (-s.a - hi * k) / (1 - k);

  // The row whose centre ray meets the floor nearest z = 0.
  const CameraFrame frame = camera_frame(s.camera);
  std::uint32_t row = 0;
  for (std::uint32_t r = 0; r < s.camera.height; ++r)
    if (std::abs(floor_point(frame, 0, r)[2]) < std::abs(floor_point(frame, 0, row)[2])) row = r;
  const double pixel = 4.8 / s.camera.width;  // a pixel's side on the floor
  // Each edge: the midpoint between the last pixel of one region and the first of the next,
  // scanning x upwards (image x runs along world -x here: scan the row backwards).
  double found_umbra_right = NAN, found_lit_right = NAN, found_umbra_left = NAN, found_lit_left = NAN;
  SoftRegion previous = SoftRegion::none;
  double previous_x = 0.0;
  for (std::uint32_t c = s.camera.width; c-- > 0;) {
    const std::size_t p = std::size_t{row} * s.camera.width + c;
    const double x = floor_point(frame, c, row)[0];
    const SoftRegion region = image.region(p);
    ASSERT_NE(region, SoftRegion::none);
    ASSERT_NE(region, SoftRegion::undefined);
    const double mid = (x + previous_x) / 2;
    if (previous == SoftRegion::lit && region == SoftRegion::penumbra) found_lit_left = mid;
    if (previous == SoftRegion::penumbra && region == SoftRegion::umbra) found_umbra_left = mid;
    if (previous == SoftRegion::umbra && region == SoftRegion::penumbra) found_umbra_right = mid;
    if (previous == SoftRegion::penumbra && region == SoftRegion::lit) found_lit_right = mid;
    EXPECT_EQ(image.light[p], static_cast<float>(image.lit_samples[p]) / 64.0f);
    EXPECT_EQ(image.faces_light[p], 0);  // seen from below: the light is behind the floor
    previous = region;
    previous_x = x;
  }
  std::cout << "umbra [" << left_umbra_edge << ", " << umbra_edge << "], found [" << found_umbra_left << ", "
            << found_umbra_right << "]; lit beyond [" << left_lit_edge << ", " << lit_edge << "], found ["
            << found_lit_left << ", " << found_lit_right << "]; pixel " << pixel << '\n';
  EXPECT_NEAR(found_umbra_right, umbra_edge, pixel);
  EXPECT_NEAR(found_umbra_left, left_umbra_edge, pixel);
  EXPECT_NEAR(found_lit_right, lit_edge, pixel);
  EXPECT_NEAR(found_lit_left, left_lit_edge, pixel);
  // The sampled disk against the whole disk: the outer strata reach within 2R/n of the rim
  // (concentric map), so each edge is within 2R/n * k / (1 - k) of the continuous one.
  const double sampling = 2 * s.radius / 8 * k / (1 - k);
  EXPECT_NEAR(umbra_edge, (s.a - s.radius * k) / (1 - k), sampling);
  EXPECT_NEAR(lit_edge, (s.a + s.radius * k) / (1 - k), sampling);
}

// --- invariance, batching, facing, progress, misuse -------------------------------------------

// Coordinates multiples of 2^-16 below 2^8: an integer translation below 2^20 is exact.
double snap(double x) { return std::ldexp(std::round(std::ldexp(x, 16)), -16); }

TEST(SoftShadowImage, Translation_OfSceneCameraAndSamples_LeavesTheImageUnchanged) {
  SphereScene s = sphere_scene(64, 48);
  for (Vec3& v : s.soup.vertices)
    for (double& x : v) x = snap(x);
  std::vector<Light> samples = disk_light_samples(s.light, scene_bounds_centre(s.soup), {1.0, 16, 9});
  for (Light& l : samples)
    for (int k = 0; k < 3; ++k) l.position[k] = snap(l.position[k]);
  const Vec3 shift{1024.0, -512.0, 65536.0};
  SphereScene moved = s;
  std::vector<Light> moved_samples = samples;
  for (Vec3& v : moved.soup.vertices)
    for (int k = 0; k < 3; ++k) v[k] += shift[k];
  for (Light& l : moved_samples)
    for (int k = 0; k < 3; ++k) l.position[k] += shift[k];
  for (int k = 0; k < 3; ++k) {
    moved.camera.eye[k] += shift[k];
    moved.camera.target[k] += shift[k];
  }
  const SoftShadowImage a = soft_shadow_image(s.soup, samples, s.camera);
  const SoftShadowImage b = soft_shadow_image(moved.soup, moved_samples, moved.camera);
  EXPECT_EQ(a.hit_triangles, b.hit_triangles);
  EXPECT_EQ(a.defined_samples, b.defined_samples);
  EXPECT_EQ(a.lit_samples, b.lit_samples);
  EXPECT_EQ(a.light, b.light);
  EXPECT_EQ(a.faces_light, b.faces_light);
}

TEST(SoftShadowImage, Batches_GiveTheSameImage) {
  const SphereScene s = sphere_scene(48, 36);
  SoftShadowOptions one_by_one;
  one_by_one.batch_bytes = 1;  // one sample per exact image
  const SoftShadowImage a = disk_light_shadow_image(s.soup, s.light, {1.0, 9, 4}, s.camera);
  const SoftShadowImage b = disk_light_shadow_image(s.soup, s.light, {1.0, 9, 4}, s.camera, one_by_one);
  EXPECT_EQ(a.stats.exact_images, 1u);
  EXPECT_EQ(b.stats.exact_images, 9u);
  EXPECT_EQ(a.lit_samples, b.lit_samples);
  EXPECT_EQ(a.defined_samples, b.defined_samples);
  EXPECT_EQ(a.faces_light, b.faces_light);
}

TEST(SoftShadowImage, FacesLight_OnTheLitFloorNotOnTheSpheresFarSide) {
  const SphereScene s = sphere_scene(64, 48);
  const SoftShadowImage image = disk_light_shadow_image(s.soup, s.light, {0.5, 16, 2}, s.camera);
  std::size_t floor_facing = 0, sphere_away = 0;
  for (std::size_t p = 0; p < image.pixels(); ++p) {
    if (image.hit_triangles[p] == kNoHit || image.defined_samples[p] == 0) {
      EXPECT_EQ(image.faces_light[p], 0);
      continue;
    }
    const bool floor = image.hit_triangles[p] < 2;
    if (floor) {
      EXPECT_EQ(image.faces_light[p], 1) << "pixel " << p;  // the floor faces every sample above it
      ++floor_facing;
    } else if (image.faces_light[p] == 0) {
      ++sphere_away;  // the sphere's side turned away from some sample: all of those are in umbra
      EXPECT_LT(image.light[p], 1.0f);
    }
  }
  EXPECT_GT(floor_facing, 1000u);
  EXPECT_GT(sphere_away, 10u);
}

TEST(SoftShadowImage, ProgressReports_EndWithEverySample) {
  const SphereScene s = sphere_scene(32, 24);
  std::vector<std::string> stages;
  std::uint64_t last_done = 0, last_total = 0;
  SoftShadowOptions options;
  options.batch_bytes = kBatchBytesPerSampleAndTriangle * s.soup.triangles.size() * 3;  // three samples per call: three calls
  options.progress = [&](std::string_view stage, std::uint64_t done, std::uint64_t total) {
    if (stages.empty() || stages.back() != stage) stages.emplace_back(stage);
    if (stage == "samples") {
      EXPECT_GE(done, last_done);
      last_done = done;
      last_total = total;
    }
  };
  const SoftShadowImage image = disk_light_shadow_image(s.soup, s.light, {0.5, 9, 2}, s.camera, options);
  EXPECT_EQ(image.stats.exact_images, 3u);
  EXPECT_EQ(stages, (std::vector<std::string>{"hits", "samples"}));  // only the first call's hits
  EXPECT_EQ(last_total, 9u * 1024u);
  EXPECT_EQ(last_done, last_total);
}

TEST(SoftShadowImage, Misuse_ThrowsNamingTheFunction) {
  const SphereScene s = sphere_scene(8, 6);
  try {
    (void)soft_shadow_image(s.soup, std::vector<Light>{}, s.camera);
    ADD_FAILURE() << "no exception for no sample";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("soft_shadow_image"), std::string::npos) << e.what();
  }
  SoftShadowOptions bad_casts;
  bad_casts.casts = {1, 0};
  EXPECT_THROW((void)soft_shadow_image(s.soup, std::vector<Light>{s.light}, s.camera, bad_casts), std::invalid_argument);
  EXPECT_THROW((void)disk_light_shadow_image(s.soup, s.light, {1.0, 10, 1}, s.camera), std::invalid_argument);
}

}  // namespace
