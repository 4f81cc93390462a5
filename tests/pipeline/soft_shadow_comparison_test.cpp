// The soft-shadow error measures (pipeline/soft_shadow_comparison.h) on synthetic light images,
// the contact pixels and the scene-level reference (pipeline/soft_reference.h), and the pictures
// (pipeline/soft_shadow_pictures.h). No GL: the method images are made here.
#include "pipeline/soft_shadow_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "core/pixel_ray.h"
#include "pipeline/soft_reference.h"
#include "pipeline/soft_shadow_pictures.h"
#include "reference/exact_image.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

// A box standing on a floor that only receives, a light above and aside, a camera from the
// front: the box's shadow starts at its foot.
Scene box_scene(double gap, std::uint32_t width = 96, std::uint32_t height = 72) {
  Scene scene;
  SceneMesh floor;
  floor.name = "floor";
  floor.soup = floor_quad(6.0);
  floor.casts = false;
  SceneMesh block;
  block.name = "box";
  block.soup = box({-0.5, gap, -0.5}, {0.5, gap + 1.0, 0.5});
  scene.meshes = {floor, block};
  scene.lights = {Light{{-1.5, 5.0, -2.0, 1.0}}};  // the shadow falls towards the camera
  scene.camera.eye = {-1.0, 5.0, 6.0};
  scene.camera.target = {0.5, 0.0, 0.5};
  scene.camera.width = width;
  scene.camera.height = height;
  return scene;
}

// The exact image's first-light mask as a method's light image: 1 lit, 0 shadowed, -1 where
// the centre ray misses; a pixel whose count is undefined is given 0.5 (any value: the
// reference has no light there, so it is a coverage difference).
std::vector<float> hard_light(const ExactImage& image) {
  std::vector<float> light(image.hit_triangles.size());
  for (std::size_t p = 0; p < light.size(); ++p) {
    const std::uint32_t n = image.lights[0].counts[p];
    light[p] = n == kNoHit ? -1.0f : n == kUndefinedCount ? 0.5f : n == 0 ? 1.0f : 0.0f;
  }
  return light;
}

TEST(CompareSoftShadow, ExactHardMask_AgainstTheZeroRadiusReference_HasNoError) {
  const Scene scene = box_scene(0.0);
  const SoftReference reference = soft_reference(scene, 0, {{0.0, 64, 1}});
  ExactImageOptions options;
  options.casts = casting_triangles(scene);
  const ExactImage hard = exact_image(merged_soup(scene), scene.lights, scene.camera, options);
  const std::vector<float> light = hard_light(hard);
  const SoftShadowErrors e = compare_soft_shadow(reference, light);
  EXPECT_EQ(e.mean_error, 0.0);
  EXPECT_EQ(e.max_error, 0.0);
  EXPECT_EQ(e.leaks, 0u);
  EXPECT_EQ(e.acne, 0u);
  EXPECT_EQ(e.penumbra, 0u);  // one sample: no penumbra
  EXPECT_EQ(e.reference_only, 0u);
  std::size_t undefined = 0;
  for (std::uint32_t n : hard.lights[0].counts) undefined += n == kUndefinedCount;
  EXPECT_EQ(e.method_only, undefined);
  EXPECT_GT(e.umbra, 100u);
  EXPECT_GT(e.contact, 10u);  // the box stands on the floor
  EXPECT_GT(e.lit_facing, 1000u);
  EXPECT_EQ(e.compared, e.outside_penumbra);
}

TEST(CompareSoftShadow, BlurredHardMask_ErrsByItsBlurAndLeaksAtTheFoot) {
  const Scene scene = box_scene(0.0);
  const SoftReference reference = soft_reference(scene, 0, {{0.0, 64, 1}});
  const SoftShadowImage& r = reference.image;
  // A 3x3 box blur of the reference's own 0/1 light over the pixels that have one.
  std::vector<float> blurred(r.pixels(), -1.0f);
  double sum = 0.0, largest = 0.0;
  std::size_t compared = 0;
  for (std::uint32_t y = 0; y < r.height; ++y)
    for (std::uint32_t x = 0; x < r.width; ++x) {
      const std::size_t p = std::size_t{y} * r.width + x;
      if (r.light[p] < 0.0f) continue;
      double total = 0.0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const long xx = static_cast<long>(x) + dx, yy = static_cast<long>(y) + dy;
          if (xx < 0 || yy < 0 || xx >= r.width || yy >= r.height) continue;
          const float v = r.light[static_cast<std::size_t>(yy) * r.width + static_cast<std::size_t>(xx)];
          if (v < 0.0f) continue;
          total += v;
          ++n;
        }
      blurred[p] = static_cast<float>(total / n);
      const double error = std::abs(static_cast<double>(blurred[p]) - r.light[p]);
      sum += error;
      largest = std::max(largest, error);
      ++compared;
    }
  const SoftShadowErrors e = compare_soft_shadow(reference, blurred);
  EXPECT_EQ(e.compared, compared);
  EXPECT_NEAR(e.mean_error, sum / static_cast<double>(compared), 1e-12);
  EXPECT_EQ(e.max_error, largest);
  EXPECT_GT(e.mean_error, 0.0);
  EXPECT_GT(e.leaks, 0u);  // the blur lights the umbra next to the foot's lit edge
  EXPECT_LE(e.leaks, e.contact);
  EXPECT_GT(e.acne, 0u);   // and darkens the lit floor next to the shadow
  std::cout << "3x3 blur of the hard mask: mean " << e.mean_error << ", max " << e.max_error << ", leaks " << e.leaks
            << " of " << e.contact << " contact pixels, acne " << e.acne << " of " << e.lit_facing << '\n';
}

// A 4 x 2 reference written by hand: pixels 0..7 are umbra (contact), umbra, penumbra
// (1 of 4 lit), lit (facing), lit (not facing), no hit, undefined, lit (facing).
SoftReference hand_reference() {
  SoftReference r;
  SoftShadowImage& s = r.image;
  s.width = 4;
  s.height = 2;
  s.hit_triangles = {0, 0, 0, 0, 0, kNoHit, 0, 0};
  s.defined_samples = {4, 4, 4, 4, 4, 0, 0, 4};
  s.lit_samples = {0, 0, 1, 4, 4, 0, 0, 4};
  s.light = {0.0f, 0.0f, 0.25f, 1.0f, 1.0f, kNoLight, kNoLight, 1.0f};
  s.faces_light = {1, 1, 1, 1, 0, 0, 0, 1};
  r.contact = {1, 0, 0, 0, 0, 0, 0, 0};
  return r;
}

TEST(CompareSoftShadow, HandMadeImages_GiveTheFiguresByHand) {
  const SoftReference r = hand_reference();
  ASSERT_EQ(r.image.region(0), SoftRegion::umbra);
  ASSERT_EQ(r.image.region(2), SoftRegion::penumbra);
  ASSERT_EQ(r.image.region(5), SoftRegion::none);
  ASSERT_EQ(r.image.region(6), SoftRegion::undefined);
  // umbra +0.5 (a leak at the contact), umbra +0.0, penumbra +0.25, lit -0.5 (acne), lit -0.5
  // (not facing: no acne), nothing where nothing is, a method light where the reference has
  // none, and an uncovered lit pixel.
  const std::vector<float> light{0.5f, 0.0f, 0.5f, 0.5f, 0.5f, -1.0f, 0.75f, -1.0f};
  const SoftShadowErrors e = compare_soft_shadow(r, light);
  EXPECT_EQ(e.compared, 5u);
  EXPECT_EQ(e.reference_only, 1u);
  EXPECT_EQ(e.method_only, 1u);
  EXPECT_DOUBLE_EQ(e.mean_error, (0.5 + 0.0 + 0.25 + 0.5 + 0.5) / 5);
  EXPECT_DOUBLE_EQ(e.mean_signed_error, (0.5 + 0.0 + 0.25 - 0.5 - 0.5) / 5);
  EXPECT_EQ(e.max_error, 0.5);
  EXPECT_EQ(e.umbra, 2u);
  EXPECT_DOUBLE_EQ(e.umbra_mean_error, 0.25);
  EXPECT_EQ(e.penumbra, 1u);
  EXPECT_DOUBLE_EQ(e.penumbra_mean_error, 0.25);
  EXPECT_EQ(e.outside_penumbra, 4u);
  EXPECT_DOUBLE_EQ(e.outside_penumbra_mean_error, (0.5 + 0.0 + 0.5 + 0.5) / 4);
  EXPECT_EQ(e.contact, 1u);
  EXPECT_EQ(e.leaks, 1u);
  EXPECT_EQ(e.lit_facing, 1u);
  EXPECT_EQ(e.acne, 1u);
  EXPECT_EQ(e.turned_away, 1u);  // pixel 4
  EXPECT_DOUBLE_EQ(e.turned_away_mean_error, 0.5);
  // The reference's noise: K = 4 at every compared pixel, a pixel's 95% half-width
  // sqrt(ln 40 / 8) whatever its light; only the penumbra pixel (1 of 4 lit) has a spread.
  EXPECT_DOUBLE_EQ(e.reference_ci95, std::sqrt(std::log(40.0) / 8.0));
  EXPECT_DOUBLE_EQ(e.reference_noise, std::sqrt(0.25 * 0.75 / 4.0) / 5.0);
  // A light without size: its one sample is the light, every pixel exact.
  SoftReference hard = r;
  hard.hard = true;
  EXPECT_EQ(compare_soft_shadow(hard, light).reference_ci95, 0.0);
  EXPECT_EQ(compare_soft_shadow(hard, light).reference_noise, 0.0);
  // Within the tolerances: no leak, no acne.
  const std::vector<float> close{kLeakTolerance, 0.0f, 0.25f, 1.0f - kAcneTolerance, 1.0f, -1.0f, -1.0f, 1.0f};
  const SoftShadowErrors c = compare_soft_shadow(r, close);
  EXPECT_EQ(c.leaks, 0u);
  EXPECT_EQ(c.acne, 0u);
}

// Hoeffding's bound for K independent verdicts in [0, 1]: P(|r - p| >= t) <= 2 exp(-2 K t^2),
// so t = sqrt(ln(2 / 0.05) / (2 K)) at 95%: 1.358 / sqrt(K), 0.170 at the reference's K = 64.
TEST(ReferenceHalfWidth, HoeffdingsBoundSolvedForTheConfidence) {
  EXPECT_NEAR(reference_half_width(64), 0.16977, 1e-5);
  for (std::uint32_t k : {1u, 16u, 64u, 256u, 1024u}) {
    EXPECT_DOUBLE_EQ(reference_half_width(k), std::sqrt(std::log(40.0) / (2.0 * k))) << k;
    EXPECT_NEAR(reference_half_width(k) * std::sqrt(static_cast<double>(k)), 1.3581, 1e-4) << k;
    // Both tails at that width are at most 5%: 2 exp(-2 K t^2) = 0.05.
    const double t = reference_half_width(k);
    EXPECT_NEAR(2.0 * std::exp(-2.0 * k * t * t), 0.05, 1e-12) << k;
  }
  EXPECT_DOUBLE_EQ(reference_half_width(64, 0.99), std::sqrt(std::log(200.0) / 128.0));
  EXPECT_THROW((void)reference_half_width(0), std::invalid_argument);
  EXPECT_THROW((void)reference_half_width(64, 1.0), std::invalid_argument);
  EXPECT_THROW((void)reference_half_width(64, 0.0), std::invalid_argument);
}

TEST(CompareSoftShadow, Misuse_Throws) {
  const SoftReference r = hand_reference();
  EXPECT_THROW((void)compare_soft_shadow(r, std::vector<float>(7, 0.0f)), std::invalid_argument);
  EXPECT_THROW((void)compare_soft_shadow(r, std::vector<float>(8, 1.5f)), std::invalid_argument);
  EXPECT_THROW((void)compare_soft_shadow(r, std::vector<float>(8, std::nanf(""))), std::invalid_argument);
}

TEST(SoftFlicker, ChangesOfMethodAndReference_AreComparedPixelByPixel) {
  SoftShadowImage a = hand_reference().image, b = a, c = a;
  b.light[2] = 0.5f;   // the reference's penumbra pixel brightens by 0.25, then goes back
  const std::vector<SoftShadowImage> references{a, b, c};
  // The method: pixel 0 flickers 0 -> 1 -> 0, pixel 2 follows the reference, the rest stay.
  std::vector<float> m0{0.0f, 0.0f, 0.25f, 1.0f, 1.0f, -1.0f, -1.0f, 1.0f}, m1 = m0, m2 = m0;
  m1[0] = 1.0f;
  m1[2] = 0.5f;
  const std::vector<std::vector<float>> frames{m0, m1, m2};
  const SoftFlicker f = soft_flicker(references, frames);
  EXPECT_EQ(f.frame_pairs, 2u);
  EXPECT_EQ(f.pixels, 2u * 6u);  // pixels 5 and 6 have no light
  EXPECT_DOUBLE_EQ(f.method_change, (1.0 + 0.25) * 2 / 12);
  EXPECT_DOUBLE_EQ(f.reference_change, 0.25 * 2 / 12);
  EXPECT_DOUBLE_EQ(f.excess, 2.0 / 12);
  EXPECT_DOUBLE_EQ(f.change_error, 2.0 / 12);
  EXPECT_EQ(soft_flicker(std::vector<SoftShadowImage>{a}, std::vector<std::vector<float>>{m0}).frame_pairs, 0u);
  EXPECT_THROW((void)soft_flicker(references, std::vector<std::vector<float>>{m0, m1}), std::invalid_argument);
}

// --- contact ---------------------------------------------------------------------------------

// Where pixel p's centre ray meets the floor y = 0, in double.
Vec3 floor_point(const Camera& camera, std::size_t p) {
  const CameraFrame frame = camera_frame(camera);
  const PixelRay ray = pixel_ray(frame, static_cast<double>(p % camera.width) + 0.5,
                                 static_cast<double>(p / camera.width) + 0.5);
  const double t = -ray.origin[1] / ray.direction[1];
  return {ray.origin[0] + t * ray.direction[0], 0.0, ray.origin[2] + t * ray.direction[2]};
}

TEST(ContactPixels, AtTheFootOfAStandingBox_NoneUnderAFloatingOne) {
  const Scene standing = box_scene(0.0, 128, 96);
  const SoftReference on_floor = soft_reference(standing, 0, {{0.3, 16, 1}});
  std::size_t contact = 0;
  for (std::size_t p = 0; p < on_floor.contact.size(); ++p) {
    if (on_floor.contact[p] == 0) continue;
    ++contact;
    EXPECT_EQ(on_floor.image.region(p), SoftRegion::umbra);
    // On the floor, next to the box's footprint [-0.5, 0.5]^2: within the contact distance
    // (4 pixels of at most 0.1 here) of it.
    const Vec3 x = floor_point(standing.camera, p);
    const double dx = std::max(0.0, std::abs(x[0]) - 0.5), dz = std::max(0.0, std::abs(x[2]) - 0.5);
    EXPECT_LT(std::sqrt(dx * dx + dz * dz), 0.4) << "pixel " << p;
  }
  EXPECT_GT(contact, 10u);
  // The same box 1 above the floor: its shadow lies far from it.
  const SoftReference floating = soft_reference(box_scene(1.0, 128, 96), 0, {{0.3, 16, 1}});
  std::size_t umbra = 0, far_contact = 0;
  for (std::size_t p = 0; p < floating.contact.size(); ++p) {
    umbra += floating.image.region(p) == SoftRegion::umbra;
    far_contact += floating.contact[p];
  }
  EXPECT_GT(umbra, 100u);
  EXPECT_EQ(far_contact, 0u);
}

TEST(SoftReference, Misuse_ThrowsNamingTheFunction) {
  const Scene scene = box_scene(0.0, 8, 6);
  try {
    (void)soft_reference(scene, 1, {});
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("soft_reference"), std::string::npos) << e.what();
  }
  const SoftReference r = soft_reference(scene, 0, {});
  EXPECT_THROW((void)contact_pixels(merged_soup(scene), {}, scene.camera, r.image, -1.0), std::invalid_argument);
  Camera other = scene.camera;
  other.width = 9;
  EXPECT_THROW((void)contact_pixels(merged_soup(scene), {}, other, r.image), std::invalid_argument);
}

// --- pictures --------------------------------------------------------------------------------

TEST(SoftShadowPictures, ColoursAndCoverage) {
  EXPECT_EQ(diverging_colour(0.0), (std::array<std::uint8_t, 3>{247, 247, 247}));
  EXPECT_EQ(diverging_colour(-1.0), (std::array<std::uint8_t, 3>{5, 48, 97}));
  EXPECT_EQ(diverging_colour(2.0), (std::array<std::uint8_t, 3>{103, 0, 31}));
  EXPECT_GT(diverging_colour(-0.5)[2], diverging_colour(-0.5)[0]);  // too dark: blue
  EXPECT_GT(diverging_colour(0.5)[0], diverging_colour(0.5)[2]);    // too bright: red
  const SoftReference r = hand_reference();
  const std::vector<float> light{0.5f, 0.0f, 0.5f, 0.5f, 0.5f, -1.0f, 0.75f, -1.0f};
  const gpu::RgbaImage error = soft_error_image(r.image, light);
  const auto rgba = [&](std::size_t p) {
    return std::array<std::uint8_t, 4>{error.pixels[4 * p], error.pixels[4 * p + 1], error.pixels[4 * p + 2],
                                       error.pixels[4 * p + 3]};
  };
  EXPECT_EQ(rgba(1), (std::array<std::uint8_t, 4>{247, 247, 247, 255}));  // no error
  EXPECT_EQ(rgba(5), (std::array<std::uint8_t, 4>{0, 0, 0, 0}));          // nothing anywhere
  EXPECT_EQ(rgba(6), (std::array<std::uint8_t, 4>{0, 160, 0, 255}));      // coverage differs
  EXPECT_EQ(rgba(7), (std::array<std::uint8_t, 4>{0, 160, 0, 255}));
  const gpu::RgbaImage regions = soft_region_image(r);
  EXPECT_EQ(regions.pixels[0], 255);  // contact: red
  EXPECT_EQ(regions.pixels[4 * 2], 128);
  EXPECT_EQ(diverging_colour_bar(11, 2).pixels[4 * 5], 247);
}

}  // namespace
