// pipeline/contour_error.h: a smooth-silhouette method's shadow boundary against the analytic
// conic (docs/smooth-silhouettes.md's table). Each figure is held to something computed
// independently of the method:
//   - discrete, to a closed form: a uv sphere's polygon lies between the sphere and the ball
//     inscribed in its faces, so its shadow's boundary lies between the two balls' conics, and
//     its error is at most their distance (support/chord_sag_bound.h);
//   - smooth-gpu, measured on the triangles its GPU build drew, to smooth's CPU figure within
//     the float rounding the GPU's arithmetic adds, and both to that closed form;
//   - the volume reading (volume_contour_error), to the loops' figure on the CPU's own volume.
#include "pipeline/contour_error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>

#include "contour/smooth_volume.h"
#include "pipeline/bench_suite.h"
#include "scene/framed_scene.h"
#include "scene/procedural_mesh.h"
#include "support/chord_sag_bound.h"
#include "support/gl_test_support.h"

namespace shadowcert {
namespace {

const Plane kFloor{{0.0, kAnalyticFloorHeight, 0.0}, {0.0, 1.0, 0.0}};

// analytic_shapes(): the uv spheres' slices x stacks, in order, then the ellipsoid (index 7).
constexpr std::array<std::array<unsigned, 2>, 7> kSphereSizes{
    {{8, 4}, {12, 6}, {16, 8}, {32, 16}, {64, 32}, {128, 64}, {256, 128}}};
constexpr std::size_t kEllipsoid = 7;

Scene shape(std::size_t index, const Light& light) {
  return analytic_shape_scene(analytic_shapes().at(index), light, 64, 48);
}

// The closed-form bound of support/chord_sag_bound.h, on the analytic scenes' floor.
using test_support::chord_sag_bound;
using test_support::inscribed_radius;

double sphere_bound(std::size_t index, const Light& light) {
  const auto [slices, stacks] = kSphereSizes.at(index);
  return chord_sag_bound(light, 1.0, inscribed_radius(1.0, slices, stacks), kAnalyticFloorHeight);
}

// The ellipsoid x = A u, A's columns (1.4, 0, 0.2), (0, 0.8, 0), (-0.3, 0, 1): its Frobenius
// norm bounds |A|.
double ellipsoid_bound(const Light& light) {
  const double frobenius = std::sqrt(1.4 * 1.4 + 0.2 * 0.2 + 0.8 * 0.8 + 0.3 * 0.3 + 1.0);
  return chord_sag_bound(light, 1.0, inscribed_radius(1.0, 32, 16), kAnalyticFloorHeight, frobenius);
}

// What the GPU's float arithmetic moves a contour by, seen on the floor: the GPU computes the
// accurate points, their Hermite displacement and up to 8 halvings in float (the CPU in
// double), a few float ulps of each contour point near the unit caster, about doubled by the
// projection onto the floor (twice as far from the light). Measured: at most 7.6e-8 on the
// shapes below on llvmpipe, 7.1e-8 on an NVIDIA H200 (the test prints it). 1e-5 is some 40
// ulps of a floor coordinate near 2 (2.4e-7 each), room for another driver's rounding, and
// still 8 times below the smallest figure compared (smooth on the 256x128 sphere under the
// sun, 7.9e-5).
constexpr double kGpuFloatRounding = 1e-5;

// Rounding the CPU's double volume to the float HomogeneousMesh moves each point by at most
// half a float ulp of a coordinate near 1 (6e-8), doubled by the projection.
constexpr double kVolumeFloatRounding = 1e-6;

TEST(ContourError, DiscreteSpheres_WithinTheChordSagBound) {
  for (const Light& light : {kAnalyticPointLight, kAnalyticSun})
    for (std::size_t i = 0; i < kSphereSizes.size(); ++i) {
      const std::optional<ContourError> e =
          contour_error(shape(i, light), 0, gpu::ShadowMethod::discrete, 0.01, kFloor);
      ASSERT_TRUE(e);
      const double bound = sphere_bound(i, light);
      SCOPED_TRACE(analytic_shapes()[i].name + (light.position[3] == 0.0 ? " sun" : " point"));
      std::cout << analytic_shapes()[i].name << (light.position[3] == 0.0 ? " sun" : " point") << ": discrete max "
                << e->max << ", chord-sag bound " << bound << '\n';
      EXPECT_LE(e->max, bound);
      EXPECT_LE(e->mean, e->max);
      EXPECT_EQ(e->casters, 1u);
    }
  // The ellipsoid under the sun (the cone argument above needs a sphere).
  const std::optional<ContourError> e =
      contour_error(shape(kEllipsoid, kAnalyticSun), 0, gpu::ShadowMethod::discrete, 0.01, kFloor);
  ASSERT_TRUE(e);
  EXPECT_LE(e->max, ellipsoid_bound(kAnalyticSun));
}

TEST(ContourError, Sphere8x4PointLight_SnapshotBesideTheBound) {
  const Scene scene = shape(0, kAnalyticPointLight);
  const std::optional<ContourError> discrete = contour_error(scene, 0, gpu::ShadowMethod::discrete, 0.01, kFloor);
  const std::optional<ContourError> smooth = contour_error(scene, 0, gpu::ShadowMethod::smooth, 0.01, kFloor);
  ASSERT_TRUE(discrete && smooth);
  // The independent bound (closed form, support/chord_sag_bound.h): 0.2787 on the 8x4 sphere under the point light.
  const double bound = sphere_bound(0, kAnalyticPointLight);
  EXPECT_NEAR(bound, 0.2787, 1e-4);
  EXPECT_LE(discrete->max, bound);
  EXPECT_LE(smooth->max, bound);
  // Snapshot of the code's output on 2026-12-04 (docs/smooth-silhouettes.md's table, from
  // `shadowcert bench --suite analytic`; here `build/tests/contour_error_test
  // --gtest_filter='*Snapshot*'`): it catches a change of the figures, not an error in them.
  EXPECT_NEAR(discrete->max, 0.1951, 5e-4);
  EXPECT_NEAR(discrete->mean, 0.0978, 5e-4);
  EXPECT_NEAR(smooth->max, 0.0259, 5e-4);
  EXPECT_NEAR(smooth->mean, 0.0112, 5e-4);
  EXPECT_EQ(discrete->casters, 1u);
  EXPECT_GT(smooth->points, discrete->points);
}

TEST(ContourError, FinerSphere_SmallerError) {
  const double coarse = contour_error(shape(0, kAnalyticSun), 0, gpu::ShadowMethod::discrete, 0.01, kFloor)->max;
  const double fine = contour_error(shape(3, kAnalyticSun), 0, gpu::ShadowMethod::discrete, 0.01, kFloor)->max;
  EXPECT_LT(fine, coarse / 5);
}

TEST(ContourError, NoEllipsoidCaster_Nullopt) {
  Scene scene = shape(0, kAnalyticPointLight);
  scene.meshes[1].ellipsoid.reset();
  EXPECT_FALSE(contour_error(scene, 0, gpu::ShadowMethod::smooth, 0.01, kFloor).has_value());
}

TEST(ContourError, BadArguments_Throw) {
  const Scene scene = shape(0, kAnalyticPointLight);
  EXPECT_THROW((void)contour_error(scene, 0, gpu::ShadowMethod::cs, 0.01, kFloor), std::invalid_argument);
  EXPECT_THROW((void)contour_error(scene, 1, gpu::ShadowMethod::smooth, 0.01, kFloor), std::invalid_argument);
  EXPECT_THROW((void)contour_error(scene, 0, gpu::ShadowMethod::smooth, 0.0, kFloor), std::invalid_argument);
  const std::vector<CasterVolume> none;
  EXPECT_THROW((void)volume_contour_error(scene, 1, none, kFloor), std::invalid_argument);
  const std::vector<CasterVolume> out_of_range{{5, {}}};
  EXPECT_THROW((void)volume_contour_error(scene, 0, out_of_range, kFloor), std::invalid_argument);
  const std::vector<CasterVolume> the_floor{{0, {}}};  // no ellipsoid
  EXPECT_THROW((void)volume_contour_error(scene, 0, the_floor, kFloor), std::invalid_argument);
}

// The regression: smooth-gpu's error was smooth's CPU contour under another name (contour_error
// mapped smooth-gpu to smooth, and the test compared it with itself). Now asking contour_error
// for it is an error; its figure is its GPU's (below).
TEST(ContourError, SmoothGpu_IsNotMeasuredOnTheCpuContour) {
  const Scene scene = shape(0, kAnalyticPointLight);
  EXPECT_THROW((void)contour_error(scene, 0, gpu::ShadowMethod::smooth_gpu, 0.01, kFloor), std::invalid_argument);
}

// volume_contour_error reads X's boundary off the volume's side faces; on the CPU's own smooth
// volume those are the contour's points, so it gives the loops' figure, but for the float
// rounding of the volume.
TEST(ContourError, CpuVolume_GivesTheContoursFigure) {
  for (const Light& light : {kAnalyticPointLight, kAnalyticSun})
    for (const std::size_t i : {std::size_t{0}, std::size_t{3}, kEllipsoid}) {
      const Scene scene = shape(i, light);
      SCOPED_TRACE(scene.meshes[1].name);
      const SmoothCaster caster = *smooth_caster(scene.meshes[1].soup).caster;
      const std::vector<CasterVolume> built{{1, smooth_shadow_volume(caster, light, {SilhouetteMethod::smooth, 0.01, 0.0}).mesh}};
      const std::optional<ContourError> read = volume_contour_error(scene, 0, built, kFloor);
      const std::optional<ContourError> loops = contour_error(scene, 0, gpu::ShadowMethod::smooth, 0.01, kFloor);
      ASSERT_TRUE(read && loops);
      EXPECT_NEAR(read->max, loops->max, kVolumeFloatRounding);
      EXPECT_NEAR(read->mean, loops->mean, kVolumeFloatRounding);
      EXPECT_EQ(read->points, loops->points);  // one closed loop, each point once
      EXPECT_EQ(read->casters, 1u);
    }
  // A volume with no side face (no segment) measures nothing.
  const Scene scene = shape(0, kAnalyticPointLight);
  EXPECT_FALSE(volume_contour_error(scene, 0, std::vector<CasterVolume>{{1, {}}}, kFloor).has_value());
}

// Two side quads drawn both ways over the same segment cancel (they bound nothing); one drawn
// twice the same way is one segment.
TEST(ContourError, VolumeSides_OppositeCancelAndTwinsCountOnce) {
  const Scene scene = shape(0, kAnalyticPointLight);
  HomogeneousMesh twins;
  twins.vertices = {{0.9f, 0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.9f, 1.0f}, {0.0f, -1.0f, 0.0f, 0.0f}};
  twins.triangles = {{0, 1, 2}, {0, 1, 2}};
  const std::optional<ContourError> e = volume_contour_error(scene, 0, std::vector<CasterVolume>{{1, twins}}, kFloor);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->points, 2u);
  HomogeneousMesh opposite = twins;
  opposite.triangles = {{0, 1, 2}, {1, 0, 2}};
  EXPECT_FALSE(volume_contour_error(scene, 0, std::vector<CasterVolume>{{1, opposite}}, kFloor).has_value());
}

class ContourErrorGl : public gpu::test::GlTest {};

// smooth-gpu's figure from the triangles its GPU drew, against smooth's from the CPU's contour:
// two builds of one contour (float on the GPU, double on the CPU), equal within the GPU's
// rounding; and each within the tessellation's chord-sag bound (the paper's claim, not a
// theorem: the smooth contour is no farther from the conic than the polygon is bound to be).
TEST_F(ContourErrorGl, SmoothGpu_MeasuredOnItsGpuVolume_EqualsSmoothWithinFloatRounding) {
  double largest = 0.0;
  for (const Light& light : {kAnalyticPointLight, kAnalyticSun})
    for (std::size_t i = 0; i <= kEllipsoid; ++i) {
      const Scene scene = shape(i, light);
      SCOPED_TRACE(scene.meshes[1].name + (light.position[3] == 0.0 ? " sun" : " point"));
      const std::vector<CasterVolume> built = smooth_gpu_caster_volumes(scene, 0, 0.01);
      ASSERT_EQ(built.size(), 1u);
      EXPECT_EQ(built[0].mesh, 1u);
      EXPECT_FALSE(built[0].volume.triangles.empty());
      const std::optional<ContourError> gpu = volume_contour_error(scene, 0, built, kFloor);
      const std::optional<ContourError> cpu = contour_error(scene, 0, gpu::ShadowMethod::smooth, 0.01, kFloor);
      ASSERT_TRUE(gpu && cpu);
      EXPECT_NEAR(gpu->max, cpu->max, kGpuFloatRounding);
      EXPECT_NEAR(gpu->mean, cpu->mean, kGpuFloatRounding);
      largest = std::max({largest, std::abs(gpu->max - cpu->max), std::abs(gpu->mean - cpu->mean)});
      const double bound = i == kEllipsoid ? (light.position[3] == 0.0 ? ellipsoid_bound(light) : INFINITY)
                                           : sphere_bound(i, light);
      EXPECT_LE(gpu->max, bound);
      EXPECT_LE(cpu->max, bound);
      std::cout << scene.meshes[1].name << (light.position[3] == 0.0 ? " sun" : " point") << ": smooth-gpu "
                << gpu->max << " / " << gpu->mean << " (" << gpu->points << " points), smooth " << cpu->max << " / "
                << cpu->mean << " (" << cpu->points << "), bound " << bound << '\n';
    }
  std::cout << "largest smooth-gpu - smooth difference: " << largest << '\n';
  // Bad arguments.
  const Scene scene = shape(0, kAnalyticPointLight);
  EXPECT_THROW((void)smooth_gpu_caster_volumes(scene, 1, 0.01), std::invalid_argument);
  EXPECT_THROW((void)smooth_gpu_caster_volumes(scene, 0, 0.0), std::invalid_argument);
}

// The bench's smooth-gpu run (pipeline/bench_suite.cpp) reports its GPU's figure: the one read
// off the volumes its GPU builds, next to smooth's from the CPU's contour.
TEST_F(ContourErrorGl, BenchSmoothGpuRun_ReportsItsGpusFigure) {
  const BenchSceneSpec spec = bench_suite("analytic", {SHADOWCERT_SOURCE_DIR, SHADOWCERT_SHARED_DATA}).front();
  ASSERT_EQ(spec.name, "sphere8x4-point");
  const Scene scene = load_bench_scene(spec, 32, 24);
  BenchOptions options;
  options.warm_up_frames = 0;
  options.frames = 1;
  options.images = false;
  const BenchSceneResult r = bench_scene(scene, spec, select_bench_variants("smooth/0.01,smooth-gpu/0.01"), options);
  ASSERT_EQ(r.runs.size(), 2u);
  ASSERT_EQ(r.runs[1].variant.method, gpu::ShadowMethod::smooth_gpu);
  const std::optional<ContourError>& smooth = r.runs[0].contour;
  const std::optional<ContourError>& gpu = r.runs[1].contour;
  ASSERT_TRUE(smooth && gpu);
  const std::optional<ContourError> expected =
      volume_contour_error(scene, 0, smooth_gpu_caster_volumes(scene, 0, 0.01), *spec.receiver_plane);
  ASSERT_TRUE(expected);
  EXPECT_DOUBLE_EQ(gpu->max, expected->max);  // the same GPU build, summed in the same order
  EXPECT_DOUBLE_EQ(gpu->mean, expected->mean);
  EXPECT_NEAR(gpu->max, smooth->max, kGpuFloatRounding);
  EXPECT_LE(gpu->max, sphere_bound(0, kAnalyticPointLight));
}

}  // namespace
}  // namespace shadowcert
