// The disk light's samples (reference/disk_light.h): one point for R = 0, points on the disk
// in its plane facing the given point, one per stratum, deterministic per seed; directional
// lights within the angular radius (degrees); a point light at the facing point fills the ball
// whose every projection is the uniform disk; the concentric and sphere maps; misuse.
#include "reference/disk_light.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/vector3.h"

namespace {

using namespace shadowcert;

constexpr double kPi = 3.14159265358979323846;

// Rounding of the sample construction: l + R (x e1 + y e2) with |l|, R below 10 is off the
// exact point by a few ulps of 10; 1e-12 absorbs that with a wide margin.
constexpr double kRounding = 1e-12;

Vec3 xyz(const Light& l) { return {l.position[0], l.position[1], l.position[2]}; }

TEST(DiskLightSamples, ZeroRadius_IsTheLightItselfWhateverK) {
  const Light light{{0.1, 5.0, -0.3, 1.0}};
  const std::vector<Light> samples = disk_light_samples(light, {0.0, 0.0, 0.0}, {0.0, 64, 7});
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_EQ(samples[0].position, light.position);
  const Light sun{{0.2, 1.0, 0.5, 0.0}};
  EXPECT_EQ(disk_light_samples(sun, {}, {0.0, 16, 7}).at(0).position, sun.position);
}

TEST(DiskLightSamples, PointLight_SamplesLieOnTheDiskFacingThePoint) {
  const Light light{{1.0, 6.0, 2.0, 1.0}};
  const Vec3 facing{0.0, 0.5, 0.0};
  const double radius = 0.75;
  const std::vector<Light> samples = disk_light_samples(light, facing, {radius, 64, 3});
  ASSERT_EQ(samples.size(), 64u);
  const Vec3 axis = normalized(difference(facing, xyz(light)));
  Vec3 mean{0.0, 0.0, 0.0};
  for (const Light& s : samples) {
    EXPECT_EQ(s.position[3], 1.0);
    const Vec3 offset = difference(xyz(s), xyz(light));
    EXPECT_LE(std::sqrt(dot(offset, offset)), radius + kRounding);
    EXPECT_NEAR(dot(offset, axis), 0.0, kRounding);  // in the plane facing `facing`
    for (int k = 0; k < 3; ++k) mean[k] += offset[k] / 64.0;
  }
  // One point per stratum of equal area: the mean sits near the centre (a random set of 64
  // points would be off by about R / 16; stratification does much better).
  EXPECT_LT(std::sqrt(dot(mean, mean)), radius / 32.0);
}

// The inverse of the concentric map (Shirley and Chiu 1997): the square point of a disk point.
std::array<double, 2> square_point(double x, double y) {
  const double r = std::hypot(x, y);
  if (r == 0.0) return {0.5, 0.5};
  const double theta = std::atan2(y, x);  // (-pi, pi]
  double a = 0.0, b = 0.0;
  if (theta >= -kPi / 4 && theta <= kPi / 4) {  // a = r > |b|
    a = r;
    b = a * theta * 4 / kPi;
  } else if (theta > kPi / 4 && theta < 3 * kPi / 4) {  // b = r >= |a|
    b = r;
    a = b * (kPi / 2 - theta) * 4 / kPi;
  } else if (theta >= 3 * kPi / 4 || theta <= -3 * kPi / 4) {  // a = -r: the point turned by pi
    a = -r;
    b = a * (theta > 0 ? theta - kPi : theta + kPi) * 4 / kPi;
  } else {  // b = -r
    b = -r;
    a = b * (kPi / 2 - (theta + kPi)) * 4 / kPi;
  }
  return {(a + 1) / 2, (b + 1) / 2};
}

TEST(DiskLightSamples, EachStratumOfTheSquare_HoldsOneSampleInOrder) {
  // Light straight above the facing point: the disk's basis is e1 = +z, e2 = -x exactly, so a
  // sample's disk point is ((z - l_z) / R, -(x - l_x) / R). Mapped back to the square, sample
  // j * n + i lies in stratum (i, j).
  const Light light{{0.0, 4.0, 0.0, 1.0}};
  const std::uint32_t n = 8;
  const std::vector<Light> samples = disk_light_samples(light, {0.0, 0.0, 0.0}, {1.0, n * n, 11});
  ASSERT_EQ(samples.size(), n * n);
  for (std::uint32_t k = 0; k < samples.size(); ++k) {
    EXPECT_EQ(samples[k].position[1], 4.0);  // the disk is horizontal, exactly
    const auto [u, v] = square_point(samples[k].position[2], -samples[k].position[0]);
    EXPECT_EQ(static_cast<std::uint32_t>(u * n), k % n) << "sample " << k;
    EXPECT_EQ(static_cast<std::uint32_t>(v * n), k / n) << "sample " << k;
  }
}

TEST(DiskLightSamples, SameSeed_SameSamples_OtherSeed_OtherSamples) {
  const Light light{{1.0, 6.0, 2.0, 1.0}};
  const auto a = disk_light_samples(light, {}, {0.5, 64, 5});
  const auto b = disk_light_samples(light, {}, {0.5, 64, 5});
  const auto c = disk_light_samples(light, {}, {0.5, 64, 6});
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].position, b[i].position);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ += a[i].position != c[i].position;
  EXPECT_EQ(differ, a.size());
}

TEST(DiskLightSamples, DirectionalLight_DirectionsWithinTheAngularRadius) {
  const Light sun{{0.3, 1.0, -0.2, 0.0}};
  const double angle = 0.1;  // radians
  // The angle in degrees; the point lights' radius is not read for a sun.
  const std::vector<Light> samples = disk_light_samples(sun, {}, {12.0, 64, 2, angle * 180.0 / kPi});
  ASSERT_EQ(samples.size(), 64u);
  const Vec3 axis = normalized(xyz(sun));
  double widest = 0.0;
  for (const Light& s : samples) {
    EXPECT_EQ(s.position[3], 0.0);
    const Vec3 d = xyz(s);
    const double sample_angle = std::acos(std::min(1.0, dot(d, axis) / std::sqrt(dot(d, d))));
    EXPECT_LE(sample_angle, angle + kRounding);
    widest = std::max(widest, sample_angle);
  }
  EXPECT_GT(widest, 0.75 * angle);  // the outer strata reach out to the rim
}

// A point light at the point its disk faces (a lamp at the centre of the scene's bounds; threw
// before): the samples fill the ball of radius R, and seen along any axis they cover the disk
// of radius R uniformly (half of them within R / sqrt(2), a quarter within R / 2).
TEST(DiskLightSamples, PointLightAtTheFacingPoint_BallWhoseEveryProjectionIsTheUniformDisk) {
  const Light lamp{{1.0, 2.0, 3.0, 1.0}};
  const double radius = 0.5;
  const std::vector<Light> samples = disk_light_samples(lamp, xyz(lamp), {radius, 64 * 64, 5});
  ASSERT_EQ(samples.size(), 4096u);
  for (int axis = 0; axis < 3; ++axis) {
    std::size_t half = 0, quarter = 0;
    for (const Light& s : samples) {
      EXPECT_EQ(s.position[3], 1.0);
      const Vec3 d = difference(xyz(s), xyz(lamp));
      EXPECT_LE(std::sqrt(dot(d, d)), radius + kRounding);
      const double across2 = dot(d, d) - d[axis] * d[axis];  // squared distance from the axis
      half += across2 <= radius * radius / 2.0 ? 1 : 0;
      quarter += across2 <= radius * radius / 4.0 ? 1 : 0;
    }
    // Binomial standard deviations at n = 4096: 0.0078 and 0.0068; 5 of them.
    EXPECT_NEAR(static_cast<double>(half) / 4096.0, 0.5, 0.04) << "axis " << axis;
    EXPECT_NEAR(static_cast<double>(quarter) / 4096.0, 0.25, 0.035) << "axis " << axis;
  }
  // Deterministic per seed.
  EXPECT_EQ(disk_light_samples(lamp, xyz(lamp), {radius, 16, 5})[7].position,
            disk_light_samples(lamp, xyz(lamp), {radius, 16, 5})[7].position);
}

TEST(BallRadialAngle, InvertsTheRadialDistribution) {
  EXPECT_NEAR(ball_radial_angle(0.0), 0.0, 1e-12);
  EXPECT_NEAR(ball_radial_angle(1.0), kPi / 2.0, 1e-12);
  double previous = -1.0;
  for (int i = 0; i <= 64; ++i) {
    const double w = i / 64.0, t = ball_radial_angle(w);
    EXPECT_NEAR((2.0 * t - std::sin(2.0 * t)) / kPi, w, 1e-12);
    EXPECT_GE(t, previous);
    previous = t;
  }
}

TEST(SpherePoint, UnitVectorsWithEqualAreas) {
  EXPECT_NEAR(sphere_point(0.3, 0.0)[2], 1.0, kRounding);
  EXPECT_NEAR(sphere_point(0.3, 1.0)[2], -1.0, kRounding);
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) {
      const Vec3 p = sphere_point(i / 10.0, j / 10.0);
      EXPECT_NEAR(dot(p, p), 1.0, kRounding);
      EXPECT_NEAR(p[2], 1.0 - 2.0 * j / 10.0, kRounding);  // z linear in v: equal-area bands
    }
}

TEST(ConcentricDiskPoint, MapsTheSquareOntoTheUnitDisk) {
  EXPECT_EQ(concentric_disk_point(0.5, 0.5), (std::array<double, 2>{0.0, 0.0}));
  for (const auto& [u, v] : std::vector<std::pair<double, double>>{{1.0, 0.5}, {0.0, 0.5}, {0.5, 1.0}, {1.0, 1.0}, {0.0, 0.2}}) {
    const auto [x, y] = concentric_disk_point(u, v);
    EXPECT_NEAR(x * x + y * y, 1.0, kRounding) << u << ", " << v;  // the square's border to the circle
  }
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      const auto [x, y] = concentric_disk_point(i / 20.0, j / 20.0);
      EXPECT_LE(x * x + y * y, 1.0 + kRounding);
    }
}

TEST(DiskLightSamples, Misuse_ThrowsNamingTheFunction) {
  const Light light{{0.0, 4.0, 0.0, 1.0}};
  const auto throws = [](auto call, const std::string& what) {
    try {
      call();
      ADD_FAILURE() << "no exception: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("disk_light_samples"), std::string::npos) << e.what();
    }
  };
  throws([&] { (void)disk_light_samples(light, {}, {0.5, 63, 1}); }, "not a square");
  throws([&] { (void)disk_light_samples(light, {}, {0.5, 0, 1}); }, "no sample");
  throws([&] { (void)disk_light_samples(light, {}, {-0.5, 64, 1}); }, "negative radius");
  throws([&] { (void)disk_light_samples(light, {}, {std::nan(""), 64, 1}); }, "NaN radius");
  throws([&] { (void)disk_light_samples(light, {0.0, INFINITY, 0.0}, {0.5, 64, 1}); }, "facing point not finite");
  const Light sun{{0.0, 1.0, 0.0, 0.0}};
  throws([&] { (void)disk_light_samples(sun, {}, {0.0, 64, 1, 90.0}); }, "a 90 degree sun");
  throws([&] { (void)disk_light_samples(sun, {}, {0.0, 64, 1, -1.0}); }, "negative angle");
  throws([&] { (void)disk_light_samples(sun, {}, {0.0, 64, 1, std::nan("")}); }, "NaN angle");
  throws([&] { (void)disk_light_samples(Light{{0.0, 1.0, 0.0, 0.0}}, {}, {INFINITY, 64, 1}); }, "infinite radius");
  throws([&] { (void)disk_light_samples(Light{{0.0, 0.0, 0.0, 0.0}}, {}, {0.1, 64, 1}); }, "zero direction");
}

}  // namespace
