// The Embree peer (raytrace/ray_traced_image.h, docs/ray-tracing.md) against the exact image on
// scenes whose answer is known: a quad over a floor under a point and a directional light, in both
// modes and every packet size; triangles that only receive; the first hits of the centre and
// corner rays; the soft image against the exact verdicts of the same samples; bad input.
#include "raytrace/ray_traced_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "reference/disk_light.h"
#include "reference/exact_image.h"
#include "scene/procedural_mesh.h"
#include "support/certificate_test_support.h"

namespace {

using namespace shadowcert;
using raytrace::BuildMode;
using raytrace::RayTracedImage;
using raytrace::RayTracedImageOptions;
using test_support::append;
using test_support::directional_light;
using test_support::point_light;

static_assert(raytrace::kMissed == kNoHit, "rt's and the exact image's 'no hit' are one value");

// A floor (triangles 0, 1: floor_quad) and a horizontal square of side 2 at height 1.5 over it
// (triangles 2, 3), facing up.
Soup quad_over_floor() {
  Soup soup = floor_quad(6.0);
  soup.normals.clear();  // no shading normals: the square's vertices have none
  const auto base = static_cast<std::uint32_t>(soup.vertices.size());
  soup.vertices.insert(soup.vertices.end(), {{-1.0, 1.5, -1.0}, {1.0, 1.5, -1.0}, {1.0, 1.5, 1.0}, {-1.0, 1.5, 1.0}});
  soup.triangles.push_back({base, base + 2, base + 1});
  soup.triangles.push_back({base, base + 3, base + 2});
  return soup;
}

Camera small_camera() {
  Camera camera;
  camera.eye = {0.5, 9.0, 7.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.width = 96;
  camera.height = 72;
  return camera;
}

// Pixels where the exact image's light k is unambiguous; how many of them rt gets wrong (its
// lit mask, or whether the centre ray hits, differs from the exact one).
struct Agreement {
  std::size_t unambiguous = 0;
  std::size_t wrong = 0;
  std::size_t shadowed = 0;  // unambiguous pixels the exact image shadows
};

Agreement agreement(const ExactImage& exact, const RayTracedImage& rt, std::size_t k) {
  Agreement a;
  for (std::size_t p = 0; p < exact.hit_triangles.size(); ++p) {
    if (exact.lights[k].ambiguity[p] != 0) continue;
    ++a.unambiguous;
    if (exact.hit_triangles[p] != kNoHit && exact.lights[k].lit[p] == 0) ++a.shadowed;
    if ((exact.hit_triangles[p] == kNoHit) != (rt.hit_triangles[p] == raytrace::kMissed) ||
        exact.lights[k].lit[p] != rt.lit[k][p])
      ++a.wrong;
  }
  return a;
}

TEST(RayTracedImage, QuadOverFloor_EqualsTheExactImageOnEveryUnambiguousPixel) {
  const Soup soup = quad_over_floor();
  const std::vector<Light> lights{point_light(0.3, 6.0, 0.2), directional_light(0.4, 1.0, -0.3)};
  const Camera camera = small_camera();
  const ExactImage exact = exact_image(soup, lights, camera);
  for (const BuildMode mode : {BuildMode::fast, BuildMode::robust}) {
    SCOPED_TRACE(std::string(raytrace::build_mode_name(mode)));
    RayTracedImageOptions options;
    options.mode = mode;
    const RayTracedImage rt = raytrace::ray_traced_image(soup, lights, camera, options);
    ASSERT_EQ(rt.width, camera.width);
    ASSERT_EQ(rt.height, camera.height);
    ASSERT_EQ(rt.lit.size(), lights.size());
    for (std::size_t k = 0; k < lights.size(); ++k) {
      const Agreement a = agreement(exact, rt, k);
      EXPECT_GT(a.unambiguous, 0.9 * static_cast<double>(exact.hit_triangles.size())) << "light " << k;
      EXPECT_GT(a.shadowed, 100u) << "light " << k << ": the square must shadow the floor";
      EXPECT_EQ(a.wrong, 0u) << "light " << k;
    }
    EXPECT_GT(rt.stats.build_seconds, 0.0);
    EXPECT_GT(rt.stats.trace_seconds, 0.0);
    EXPECT_EQ(rt.stats.rays, std::uint64_t{camera.width} * camera.height);
  }
}

TEST(RayTracedImage, CentreAndCornerRays_HitTheExactImagesTrianglesWhereTheFootprintSeesOne) {
  const Soup soup = quad_over_floor();
  const std::vector<Light> lights{point_light(0.3, 6.0, 0.2)};
  const Camera camera = small_camera();
  const ExactImage exact = exact_image(soup, lights, camera);
  RayTracedImageOptions options;
  options.corner_rays = true;
  const RayTracedImage rt = raytrace::ray_traced_image(soup, lights, camera, options);
  ASSERT_EQ(rt.corner_hits.size(), std::size_t{camera.width + 1} * (camera.height + 1));
  EXPECT_EQ(rt.stats.rays, std::uint64_t{camera.width} * camera.height + rt.corner_hits.size());
  std::size_t checked = 0;
  for (std::uint32_t r = 0; r < camera.height; ++r)
    for (std::uint32_t i = 0; i < camera.width; ++i) {
      const std::size_t p = std::size_t{r} * camera.width + i;
      if (exact.view_ambiguity[p] != 0) continue;  // the footprint sees one triangle (or none)
      ++checked;
      ASSERT_EQ(rt.hit_triangles[p], exact.hit_triangles[p]) << "pixel " << i << ", " << r;
      // Each corner of a pixel whose footprint sees one triangle sees it too.
      for (const std::size_t c : {std::size_t{r} * (camera.width + 1) + i, std::size_t{r + 1} * (camera.width + 1) + i + 1})
        ASSERT_EQ(rt.corner_hits[c], exact.hit_triangles[p]) << "corner of pixel " << i << ", " << r;
    }
  EXPECT_GT(checked, std::size_t{camera.width} * camera.height / 2);
}

TEST(RayTracedImage, EveryPacketSizeAndThreadCount_GivesTheSameImage) {
  const Soup soup = quad_over_floor();
  const std::vector<Light> lights{point_light(0.3, 6.0, 0.2), directional_light(0.4, 1.0, -0.3)};
  const Camera camera = small_camera();
  RayTracedImageOptions single;
  single.packet = 1;
  const RayTracedImage one = raytrace::ray_traced_image(soup, lights, camera, single);
  for (const unsigned packet : {4u, 8u, 16u})
    for (const unsigned threads : {1u, 2u}) {
      RayTracedImageOptions options;
      options.packet = packet;
      options.threads = threads;
      const RayTracedImage other = raytrace::ray_traced_image(soup, lights, camera, options);
      EXPECT_EQ(other.hit_triangles, one.hit_triangles) << "packet " << packet << ", threads " << threads;
      EXPECT_EQ(other.lit, one.lit) << "packet " << packet << ", threads " << threads;
    }
}

TEST(RayTracedImage, ReceiveOnlySquare_CastsNoShadowButIsSeen) {
  const Soup soup = quad_over_floor();
  const std::vector<Light> lights{point_light(0.3, 6.0, 0.2)};
  const Camera camera = small_camera();
  RayTracedImageOptions options;
  options.casts = {1, 1, 0, 0};  // the floor casts, the square only receives
  const RayTracedImage rt = raytrace::ray_traced_image(soup, lights, camera, options);
  ExactImageOptions exact_options;
  exact_options.casts = options.casts;
  const ExactImage exact = exact_image(soup, lights, camera, exact_options);
  std::size_t square = 0;
  for (std::size_t p = 0; p < rt.hit_triangles.size(); ++p) {
    if (rt.hit_triangles[p] == 2 || rt.hit_triangles[p] == 3) ++square;
    // Nothing casts over the floor or the square: every hit pixel is lit.
    if (rt.hit_triangles[p] != raytrace::kMissed) {
      ASSERT_EQ(rt.lit[0][p], 255) << "pixel " << p;
    }
  }
  EXPECT_GT(square, 100u);
  EXPECT_EQ(agreement(exact, rt, 0).wrong, 0u);
}

TEST(RayTracedSoftImage, DiskSamples_EqualTheExactVerdictsMeanOnPixelsEverySampleDecides) {
  const Soup soup = quad_over_floor();
  const Light light = point_light(0.3, 6.0, 0.2);
  DiskLightSampling sampling;
  sampling.radius = 1.5;
  sampling.samples = 16;
  const std::vector<Light> samples = disk_light_samples(light, scene_bounds_centre(soup), sampling);
  const Camera camera = small_camera();
  // Each sample a light of one exact image of the centre rays (as the soft reference images
  // them, reference/soft_shadow_image.h), so that every sample's verdict has its own ambiguity.
  ExactImageOptions centres;
  centres.footprints = false;
  const ExactImage exact = exact_image(soup, samples, camera, centres);
  for (const BuildMode mode : {BuildMode::fast, BuildMode::robust}) {
    RayTracedImageOptions options;
    options.mode = mode;
    const raytrace::RayTracedSoftImage rt = raytrace::ray_traced_soft_image(soup, samples, camera, options);
    ASSERT_EQ(rt.samples, samples.size());
    std::size_t decided = 0, penumbra = 0;
    double worst = 0.0;
    for (std::size_t p = 0; p < rt.light.size(); ++p) {
      bool unambiguous = true;
      std::uint32_t lit = 0;
      for (const ExactLightImage& s : exact.lights) {
        unambiguous = unambiguous && s.ambiguity[p] == 0;
        lit += s.lit[p] != 0 ? 1 : 0;
      }
      if (!unambiguous || exact.hit_triangles[p] == kNoHit) continue;
      ++decided;
      if (lit != 0 && lit != samples.size()) ++penumbra;
      const double mean = static_cast<double>(lit) / static_cast<double>(samples.size());
      worst = std::max(worst, std::abs(static_cast<double>(rt.light[p]) - mean));
    }
    // The bound: 0. On this scene no sample's shadow boundary passes within float rounding of
    // a pixel centre whose verdicts are all defined, so each shadow ray decides as the exact
    // verdict does and the means are equal to the last bit (rt's own sampling adds no noise:
    // it traces the very same sample points).
    EXPECT_EQ(worst, 0.0) << raytrace::build_mode_name(mode);
    EXPECT_GT(decided, rt.light.size() / 2);
    EXPECT_GT(penumbra, 20u) << "the disk must make a penumbra";
  }
}

TEST(RayTracedImage, BadInput_ThrowsNamingTheFunction) {
  const Soup good = quad_over_floor();
  const std::vector<Light> lights{point_light(0.3, 6.0, 0.2)};
  const Camera camera = small_camera();
  const auto expect_message = [](const auto& call, const std::string& words) {
    try {
      call();
      ADD_FAILURE() << "no throw; expected " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  Soup nan = good;
  nan.vertices[5][1] = std::numeric_limits<double>::quiet_NaN();
  expect_message([&] { (void)raytrace::ray_traced_image(nan, lights, camera); }, "ray_traced_image: vertex 5");
  Soup out_of_range = good;
  out_of_range.triangles[3][2] = 99;
  expect_message([&] { (void)raytrace::ray_traced_image(out_of_range, lights, camera); },
                 "ray_traced_image: triangle 3 has vertex index 99");
  Soup huge = good;
  huge.vertices[0][0] = 1e300;
  expect_message([&] { (void)raytrace::ray_traced_image(huge, lights, camera); }, "ray_traced_image: a vertex coordinate is beyond float");
  const std::vector<Light> bad_light{Light{{0.0, 1.0, 0.0, 0.5}}};
  expect_message([&] { (void)raytrace::ray_traced_image(good, bad_light, camera); }, "ray_traced_image: the light");
  Camera flat = camera;
  flat.target = flat.eye;
  expect_message([&] { (void)raytrace::ray_traced_image(good, lights, flat); }, "ray_traced_image: eye == target");
  RayTracedImageOptions two_flags;
  two_flags.casts = {1, 0};
  expect_message([&] { (void)raytrace::ray_traced_image(good, lights, camera, two_flags); },
                 "ray_traced_image: casts has 2 flags for 4 triangles");
  RayTracedImageOptions packet3;
  packet3.packet = 3;
  expect_message([&] { (void)raytrace::ray_traced_image(good, lights, camera, packet3); },
                 "ray_traced_image: packet must be 1, 4, 8 or 16");
  expect_message([&] { (void)raytrace::ray_traced_soft_image(good, {}, camera); }, "ray_traced_soft_image: no sample");
  expect_message([&] { (void)raytrace::ray_traced_soft_image(nan, lights, camera); }, "ray_traced_soft_image: vertex 5");
}

TEST(EmbreeScene, SelectOfTheWrongSize_ThrowsNamingTheFunction) {
  raytrace::EmbreeDevice device;
  const Soup soup = quad_over_floor();
  const std::vector<std::uint8_t> select{1, 1};
  EXPECT_THROW((void)raytrace::EmbreeScene(device, soup, BuildMode::fast, select), std::invalid_argument);
  const raytrace::EmbreeScene casters(device, soup, BuildMode::robust, std::vector<std::uint8_t>{0, 0, 1, 1});
  EXPECT_EQ(casters.size(), 2u);
  EXPECT_EQ(casters.triangle(1), 3u);
}

TEST(EmbreeDevice, ErrorReportedByEmbree_ThrowsWithEmbreesMessageOnce) {
  raytrace::EmbreeDevice device;
  EXPECT_NO_THROW(device.check("test"));
  // A geometry type Embree does not know (between USER and INSTANCE's neighbours): Embree
  // reports it through the callback ("invalid geometry type").
  RTCGeometry geometry = rtcNewGeometry(device.get(), static_cast<RTCGeometryType>(100));
  EXPECT_EQ(geometry, nullptr);
  try {
    device.check("test_function");
    ADD_FAILURE() << "no EmbreeError";
  } catch (const raytrace::EmbreeError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("test_function: RTC_ERROR_", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("invalid geometry type"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(device.check("test")) << "the error is reported once";
  raytrace::EmbreeDevice moved = std::move(device);
  EXPECT_NO_THROW(moved.check("test"));
}

}  // namespace
