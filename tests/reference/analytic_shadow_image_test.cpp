// reference/analytic_shadow_image.h: the analytic shadow of a sphere under a point light over a
// floor, pixel by pixel: floor pixels deep inside the true shadow's circle are shadowed, well
// outside lit, and every visible floor pixel that the circle passes through is ambiguous; on
// the sphere, pixels well on either side of the interpolated-normal terminator are lit or
// shadowed and those near it are in the band; a directional light; invariance under an exact
// translation of scene and camera; and input validation.
#include "reference/analytic_shadow_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/pixel_ray.h"
#include "core/vector3.h"
#include "reference/ellipsoid_shadow.h"
#include "scene/procedural_mesh.h"

namespace {

using namespace shadowcert;

constexpr std::uint32_t kFloor = 0;   // mesh indices of the scene below
constexpr std::uint32_t kSphere = 1;

// A soup whose coordinates are multiples of 2^-16 (|x| < 2^8): translating it by integers
// below 2^20 is exact.
Soup snapped(Soup soup) {
  for (Vec3& v : soup.vertices)
    for (double& x : v) x = std::ldexp(std::round(std::ldexp(x, 16)), -16);
  return soup;
}

// A 32x16 uv sphere of radius 1 at (0, 1.5, 0) over a floor y = 0, the light straight above.
Scene sphere_scene(const Light& light, std::uint32_t slices = 32, std::uint32_t stacks = 16) {
  Scene scene;
  SceneMesh floor;
  floor.name = "floor";
  floor.soup = snapped(floor_quad(8.0));
  scene.meshes.push_back(floor);
  SceneMesh sphere;
  sphere.name = "sphere";
  sphere.soup = snapped(uv_sphere({0.0, 1.5, 0.0}, 1.0, slices, stacks));
  sphere.ellipsoid = Ellipsoid{{0.0, 1.5, 0.0}, {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}};
  scene.meshes.push_back(sphere);
  scene.lights = {light};
  // Off the scene's symmetry planes: no corner ray runs exactly along a meridian edge.
  scene.camera.eye = {0.375, 7.0, 6.0};
  scene.camera.target = {0.0625, 0.0, -0.5};
  scene.camera.width = 128;
  scene.camera.height = 96;
  return scene;
}

const Light kLight{{0.0, 5.0, 0.0, 1.0}};

// The image point of world point x (in double: only used to pick pixels, never to decide).
std::array<double, 2> project(const Camera& camera, const Vec3& x) {
  const CameraFrame f = camera_frame(camera);
  const Vec3 d = difference(x, f.eye);
  const double z = dot(d, f.forward);
  const double a = dot(d, f.right) / z, b = dot(d, f.up) / z;
  return {(a / f.half_width + 1.0) * f.width / 2.0, (1.0 - b / f.half_height) * f.height / 2.0};
}

// Where the pixel's centre ray meets the floor y = 0, in double.
Vec3 floor_point(const Camera& camera, std::uint32_t i, std::uint32_t r) {
  const PixelRay ray = pixel_ray(camera_frame(camera), i + 0.5, r + 0.5);
  const double t = -ray.origin[1] / ray.direction[1];
  return {ray.origin[0] + t * ray.direction[0], 0.0, ray.origin[2] + t * ray.direction[2]};
}

// Light 5 above the floor, the sphere's centre 3.5 below it: the cone's circle on the floor has
// radius 5 / sqrt(3.5^2 - 1).
const double kShadowRadius = 5.0 / std::sqrt(3.5 * 3.5 - 1.0);

TEST(AnalyticShadowImage, SphereUnderAPointLight_FloorInsideShadowedOutsideLitBoundaryAmbiguous) {
  const Scene scene = sphere_scene(kLight);
  const AnalyticShadowImage image = analytic_shadow_image(scene);
  ASSERT_EQ(image.lights.size(), 1u);
  ASSERT_EQ(image.analytic_casters, std::vector<std::uint32_t>{kSphere});
  const std::vector<AnalyticPixel>& truth = image.lights[0];
  // The pixel size on the floor here is below 0.15: pixels whose centre is 0.3 from the circle
  // have their whole footprint on one side.
  int inside = 0, outside = 0;
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i) {
      const std::size_t p = std::size_t{r} * image.width + i;
      if (image.meshes[p] != kFloor) continue;
      const Vec3 x = floor_point(scene.camera, i, r);
      const double radius = std::hypot(x[0], x[2]);
      if (radius < kShadowRadius - 0.3) {
        // Ambiguous only where the footprint also sees the sphere (a pixel at its outline).
        EXPECT_TRUE(truth[p] == AnalyticPixel::shadowed || truth[p] == AnalyticPixel::ambiguous) << i << ", " << r;
        if (truth[p] == AnalyticPixel::shadowed) ++inside;
      } else if (radius > kShadowRadius + 0.3) {
        EXPECT_TRUE(truth[p] == AnalyticPixel::lit || truth[p] == AnalyticPixel::ambiguous) << i << ", " << r;
        if (truth[p] == AnalyticPixel::lit) ++outside;
      }
    }
  EXPECT_GT(inside, 50);
  EXPECT_GT(outside, 2000);
  // Every visible floor pixel the true boundary passes through straddles it.
  int boundary = 0;
  for (const Vec3& x : ellipsoid_shadow_boundary(*scene.meshes[kSphere].ellipsoid, kLight, Plane{}, 720)) {
    const auto [u, v] = project(scene.camera, x);
    const auto i = static_cast<std::uint32_t>(u), r = static_cast<std::uint32_t>(v);
    const std::size_t p = std::size_t{r} * image.width + i;
    if (image.meshes[p] != kFloor) continue;  // hidden behind the sphere
    EXPECT_EQ(truth[p], AnalyticPixel::ambiguous) << i << ", " << r;
    ++boundary;
  }
  EXPECT_GT(boundary, 200);
}

TEST(AnalyticShadowImage, SphereItself_FollowsTheInterpolatedNormalTerminator) {
  // The light 3.5 above the centre of a sphere with its own (radial) normals: n . (L - P) = 0
  // where n_y = 1 / 3.5, the tangent circle 1/3.5 above the centre. Pixels whose centre ray
  // meets the sphere clearly above it are lit, clearly below shadowed, and the band holds only
  // pixels near it. Rays near the outline (whose corners may meet the floor) are left out.
  const Scene scene = sphere_scene(kLight);
  const AnalyticShadowImage image = analytic_shadow_image(scene);
  const CameraFrame f = camera_frame(scene.camera);
  constexpr double kTerminatorHeight = 1.0 / 3.5;
  int lit = 0, shadowed = 0, band = 0;
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i) {
      const std::size_t p = std::size_t{r} * image.width + i;
      const AnalyticPixel t = image.lights[0][p];
      if (image.meshes[p] != kSphere) {
        EXPECT_TRUE(t != AnalyticPixel::caster_lit && t != AnalyticPixel::caster_shadowed &&
                    t != AnalyticPixel::caster_band && t != AnalyticPixel::caster_ambiguous);
        continue;
      }
      EXPECT_NE(t, AnalyticPixel::lit);  // the sphere's pixels are judged as the caster's
      // The centre ray against the unit sphere at (0, 1.5, 0), nearest root, in double.
      const PixelRay ray = pixel_ray(f, i + 0.5, r + 0.5);
      const Vec3 o = difference(ray.origin, Vec3{0.0, 1.5, 0.0});
      const double a = dot(ray.direction, ray.direction), b = dot(o, ray.direction), c = dot(o, o) - 1.0;
      const double miss = dot(o, o) - b * b / a;  // squared distance of the ray from the centre
      if (t == AnalyticPixel::caster_band) ++band;
      if (miss > 0.8) continue;
      const double height = o[1] + (-b - std::sqrt(b * b - a * c)) / a * ray.direction[1] - kTerminatorHeight;
      if (height > 0.2) {
        EXPECT_EQ(t, AnalyticPixel::caster_lit) << i << ", " << r;
        ++lit;
      } else if (height < -0.2) {
        EXPECT_EQ(t, AnalyticPixel::caster_shadowed) << i << ", " << r;
        ++shadowed;
      }
    }
  EXPECT_GT(lit, 200);
  EXPECT_GT(shadowed, 20);
  EXPECT_GT(band, 10);
}

TEST(AnalyticShadowImage, DirectionalLight_ShadowIsTheUnitDiscUnderTheSphere) {
  const Light sun{{0.0, 1.0, 0.0, 0.0}};
  const Scene scene = sphere_scene(sun);
  const AnalyticShadowImage image = analytic_shadow_image(scene);
  int inside = 0, outside = 0;
  for (std::uint32_t r = 0; r < image.height; ++r)
    for (std::uint32_t i = 0; i < image.width; ++i) {
      const std::size_t p = std::size_t{r} * image.width + i;
      if (image.meshes[p] != kFloor) continue;
      const Vec3 x = floor_point(scene.camera, i, r);
      const double radius = std::hypot(x[0], x[2]);
      if (radius < 0.7) {
        // Ambiguous only where the footprint also sees the sphere (a pixel at its outline).
        EXPECT_TRUE(image.lights[0][p] == AnalyticPixel::shadowed || image.lights[0][p] == AnalyticPixel::ambiguous);
        if (image.lights[0][p] == AnalyticPixel::shadowed) ++inside;
      } else if (radius > 1.3) {
        // Ambiguous only at the floor's far edge, where corner rays miss it.
        EXPECT_TRUE(image.lights[0][p] == AnalyticPixel::lit || image.lights[0][p] == AnalyticPixel::ambiguous);
        if (image.lights[0][p] == AnalyticPixel::lit) ++outside;
      }
    }
  EXPECT_GT(inside, 5);
  EXPECT_GT(outside, 2000);
}

TEST(AnalyticShadowImage, ExactTranslationWithTheCamera_LeavesTheImageUnchanged) {
  const Scene scene = sphere_scene(kLight);
  const Vec3 shift{1024.0, -512.0, 2048.0};
  Scene moved = scene;
  for (SceneMesh& mesh : moved.meshes) {
    for (Vec3& v : mesh.soup.vertices)
      for (int k = 0; k < 3; ++k) v[k] += shift[k];
    if (mesh.ellipsoid)
      for (int k = 0; k < 3; ++k) mesh.ellipsoid->centre[k] += shift[k];
  }
  for (int k = 0; k < 3; ++k) {
    moved.camera.eye[k] += shift[k];
    moved.camera.target[k] += shift[k];
    moved.lights[0].position[k] += shift[k];
  }
  for (std::size_t i = 0; i < scene.meshes[kSphere].soup.vertices.size(); ++i)
    ASSERT_EQ(moved.meshes[kSphere].soup.vertices[i][0] - shift[0], scene.meshes[kSphere].soup.vertices[i][0]);
  const AnalyticShadowImage a = analytic_shadow_image(scene);
  const AnalyticShadowImage b = analytic_shadow_image(moved);
  EXPECT_EQ(a.meshes, b.meshes);
  ASSERT_EQ(a.lights.size(), b.lights.size());
  // Receiver pixels are decided by exact signs: identical. The terminator is evaluated in double
  // on P, whose rounding moves with the shift: a pixel whose cosine lies within rounding of the
  // band's edge could move between the band and a side (none does here).
  EXPECT_EQ(a.lights[0], b.lights[0]);
}

TEST(AnalyticShadowImage, NonCastingEllipsoidMesh_IsAReceiver) {
  Scene scene = sphere_scene(kLight);
  scene.meshes[kSphere].casts = false;
  const AnalyticShadowImage image = analytic_shadow_image(scene);
  EXPECT_TRUE(image.analytic_casters.empty());
  for (std::size_t p = 0; p < image.meshes.size(); ++p) {
    if (image.meshes[p] == kFloor) {
      EXPECT_NE(image.lights[0][p], AnalyticPixel::shadowed);
    }
  }
}

TEST(AnalyticShadowImage, BadInput_Throws) {
  Scene scene = sphere_scene(kLight);
  scene.meshes[kSphere].soup.normals.clear();  // no normals, none given
  EXPECT_THROW((void)analytic_shadow_image(scene), std::invalid_argument);
  AnalyticImageOptions wrong;
  wrong.corner_normals.resize(2);
  wrong.corner_normals[kSphere].resize(3);  // not one per triangle
  EXPECT_THROW((void)analytic_shadow_image(sphere_scene(kLight), wrong), std::invalid_argument);
  AnalyticImageOptions band;
  band.terminator_band = 1.0;
  EXPECT_THROW((void)analytic_shadow_image(sphere_scene(kLight), band), std::invalid_argument);
  Scene flat = sphere_scene(kLight);
  flat.meshes[kSphere].ellipsoid->axes[2] = {1, 1, 0};
  EXPECT_THROW((void)analytic_shadow_image(flat), std::invalid_argument);
}

}  // namespace
