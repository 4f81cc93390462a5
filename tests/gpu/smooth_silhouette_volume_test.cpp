// The `smooth-gpu` volume (gpu/smooth_silhouette_volume.h) on llvmpipe or any EGL device:
//  1. it equals contour/smooth_volume.h's CPU build up to float rounding: the same triangles,
//     matched one to one within a few float ulps of the caster's size (the GPU computes in float,
//     the CPU in double);
//  2. as captured, its closure is certified exactly (exact/volume_closure.h) for 1,000 random
//     lights, point and directional, on each of a uv sphere, a torus, an open hemisphere, a box
//     whose every edge is a crease, an icosphere with computed normals and a sphere creased along
//     its equator, with and without a cap offset.
#include "gpu/smooth_silhouette_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "contour/smooth_volume.h"
#include "core/vector3.h"
#include "exact/volume_closure.h"
#include "pipeline/smooth_caster_arrays.h"
#include "scene/procedural_mesh.h"
#include "support/contour_test_support.h"
#include "support/gl_test_support.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;
using test_support::caster_of;

class SmoothSilhouetteVolumeTest : public GlTest {};

Soup open_hemisphere() {
  const Soup sphere = uv_sphere({0, 0, 0}, 1.0, 16, 8);
  Soup half = sphere;
  half.triangles.clear();
  for (const Triangle& t : sphere.triangles)
    if (sphere.vertices[t[0]][2] + sphere.vertices[t[1]][2] + sphere.vertices[t[2]][2] > 0.0) half.triangles.push_back(t);
  return half;
}

// A sphere whose equator is a crease: its vertices doubled, the upper copy's normals tilted up,
// the lower copy's down (the loops then run along the crease for a while).
Soup creased_sphere() {
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
  return sphere;
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
          {"icosphere, computed normals", caster_of(icosphere({0, 0, 0}, 1.0, 1), {.use_file_normals = false})},
          {"sphere creased at its equator", caster_of(creased_sphere())}};
}

// A point light 1.5 to 5 radii from the origin, or a directional light, from `random`.
Light random_light(std::mt19937_64& random, bool directional) {
  std::normal_distribution<double> normal;
  Vec3 d = normalized(Vec3{normal(random), normal(random), normal(random)});
  if (directional) return Light{{d[0], d[1], d[2], 0.0}};
  const double r = std::uniform_real_distribution<double>(1.5, 5.0)(random);
  return Light{{r * d[0], r * d[1], r * d[2], 1.0}};
}

HomogeneousMesh captured(const SmoothSilhouetteVolume& volume) {
  HomogeneousMesh mesh;
  for (const VolumeTriangle& t : volume.read_triangles()) {
    const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), t.begin(), t.end());
    mesh.triangles.push_back({first, first + 1, first + 2});
  }
  return mesh;
}

SmoothCasterArrays arrays_of(const SmoothCaster& c, double epsilon, double cap_offset = 0.0) {
  SmoothCasterArrays a;
  append_smooth_caster(a, c, epsilon, cap_offset);
  return a;
}

// Whether two homogeneous points agree within `tolerance` (per coordinate, w exactly).
bool near(const Vec4f& a, const Vec4f& b, double tolerance) {
  if (a[3] != b[3]) return false;
  for (std::size_t k = 0; k < 3; ++k)
    if (std::abs(double(a[k]) - double(b[k])) > tolerance) return false;
  return true;
}

bool same_triangle(const VolumeTriangle& a, const VolumeTriangle& b, double tolerance) {
  for (std::size_t r = 0; r < 3; ++r)  // the same cyclic order, any first vertex
    if (near(a[0], b[r], tolerance) && near(a[1], b[(r + 1) % 3], tolerance) && near(a[2], b[(r + 2) % 3], tolerance))
      return true;
  return false;
}

// `triangles` less every pair of a triangle and its reverse (the same points, the other
// orientation): such a pair counts nothing anywhere. Where the light lies in a face's plane, the
// GPU's triangle that casts nothing extrudes a side that its own crease strip's side cancels,
// which the CPU's global cancellation never emits (gpu/shaders/smooth_silhouette_volume.comp.glsl).
std::vector<VolumeTriangle> without_cancelling_pairs(const std::vector<VolumeTriangle>& triangles, double tolerance) {
  std::vector<bool> gone(triangles.size(), false);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    if (gone[i]) continue;
    const VolumeTriangle reversed{triangles[i][0], triangles[i][2], triangles[i][1]};
    for (std::size_t j = i + 1; j < triangles.size(); ++j)
      if (!gone[j] && same_triangle(reversed, triangles[j], tolerance)) {
        gone[i] = gone[j] = true;
        break;
      }
  }
  std::vector<VolumeTriangle> kept;
  for (std::size_t i = 0; i < triangles.size(); ++i)
    if (!gone[i]) kept.push_back(triangles[i]);
  return kept;
}

// How many of `gpu`'s triangles have no partner among `cpu`'s (one to one, within tolerance);
// the triangles of either without area are left out (the CPU drops a triangle when two of its
// vertices are one point; the GPU when they round to one float); with `drop_cancelling_pairs`,
// so are pairs that cancel, from both.
std::size_t unmatched(std::vector<VolumeTriangle> gpu, const HomogeneousMesh& cpu_mesh, double tolerance,
                      bool drop_cancelling_pairs = false) {
  const auto has_area = [&](const VolumeTriangle& t) {
    return !(near(t[0], t[1], tolerance) || near(t[1], t[2], tolerance) || near(t[2], t[0], tolerance));
  };
  std::vector<VolumeTriangle> cpu;
  for (const auto& t : cpu_mesh.triangles) {
    const VolumeTriangle x{cpu_mesh.vertices[t[0]], cpu_mesh.vertices[t[1]], cpu_mesh.vertices[t[2]]};
    if (has_area(x)) cpu.push_back(x);
  }
  std::erase_if(gpu, [&](const VolumeTriangle& t) { return !has_area(t); });
  if (drop_cancelling_pairs) {
    gpu = without_cancelling_pairs(gpu, tolerance);
    cpu = without_cancelling_pairs(cpu, tolerance);
  }
  if (gpu.size() != cpu.size()) return std::max(gpu.size(), cpu.size());
  // A key that moves by at most 15 tolerances between matching triangles and seldom ties (the
  // casters' axis-aligned coordinates would make a plain x sum tie everywhere).
  const auto key = [](const VolumeTriangle& t) {
    double k = 0.0;
    for (const Vec4f& v : t) k += double(v[0]) + 1.7 * v[1] + 2.3 * v[2] + 0.3 * v[3];
    return k;
  };
  std::sort(cpu.begin(), cpu.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
  std::vector<bool> used(cpu.size(), false);
  std::size_t missing = 0;
  for (const VolumeTriangle& t : gpu) {
    const double k = key(t);
    auto it = std::lower_bound(cpu.begin(), cpu.end(), k - 15 * tolerance,
                               [&](const VolumeTriangle& x, double v) { return key(x) < v; });
    bool found = false;
    for (; it != cpu.end() && key(*it) <= k + 15 * tolerance; ++it) {
      const auto i = static_cast<std::size_t>(it - cpu.begin());
      if (!used[i] && same_triangle(t, *it, tolerance)) {
        used[i] = true;
        found = true;
        break;
      }
    }
    missing += !found;
  }
  return missing;
}

TEST_F(SmoothSilhouetteVolumeTest, EqualsTheCpuBuildUpToFloatRounding) {
  // The float build's points differ from the double one's by a few ulps of the caster's size;
  // far points (x - l) by a few ulps of the light's distance. 1e-4 is hundreds of ulps at the
  // scale 5 and far below any geometric feature of these casters.
  constexpr double kTolerance = 1e-4;
  const std::uint64_t seed = 20261203;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 random(seed);
  for (const NamedCaster& c : casters()) {
    const SmoothCasterBuffers buffers(arrays_of(c.caster, 0.01));
    const SmoothCasterBuffers offset_buffers(arrays_of(c.caster, 0.01, 0.01));
    SmoothSilhouetteVolume volume(buffers);
    SmoothSilhouetteVolume offset_volume(offset_buffers);
    for (int i = 0; i < 200; ++i) {
      const Light light = random_light(random, i % 2 == 1);
      const Light rounded{{double(float(light.position[0])), double(float(light.position[1])),
                           double(float(light.position[2])), light.position[3]}};
      // One light in five with the caps set behind the surface (the GL path's depth band).
      const double cap_offset = i % 5 == 0 ? 0.01 : 0.0;
      SmoothSilhouetteVolume& v = cap_offset > 0.0 ? offset_volume : volume;
      v.build(rounded);
      const std::vector<VolumeTriangle> gpu = v.read_triangles();
      const SmoothVolume cpu = smooth_shadow_volume(
          c.caster, rounded, {.method = SilhouetteMethod::smooth, .epsilon = 0.01, .cap_offset = cap_offset});
      EXPECT_EQ(unmatched(gpu, cpu.mesh, kTolerance), 0u)
          << c.name << ", light " << i << ": " << gpu.size() << " GPU triangles, " << cpu.mesh.triangles.size()
          << " CPU triangles";
      if (HasFailure()) return;
    }
  }
}

TEST_F(SmoothSilhouetteVolumeTest, ThousandRandomLightsPerCaster_CapturedVolumeIsClosed) {
  const std::uint64_t seed = 20261204;
  std::cout << "seed " << seed << "\n";
  std::mt19937_64 random(seed);
  for (const NamedCaster& c : casters()) {
    const SmoothCasterBuffers buffers(arrays_of(c.caster, 0.01));
    const SmoothCasterBuffers offset_buffers(arrays_of(c.caster, 0.003, 0.01));
    SmoothSilhouetteVolume volume(buffers);
    SmoothSilhouetteVolume offset_volume(offset_buffers);
    for (int i = 0; i < 1000; ++i) {
      const Light light = random_light(random, i % 2 == 1);
      const bool with_offset = i % 10 == 0;
      SmoothSilhouetteVolume& v = with_offset ? offset_volume : volume;
      v.build(light);
      ASSERT_LE(v.read_requested_vertices(), v.capacity_vertices());
      const VolumeClosure closure = certify_volume_closure(captured(v));
      EXPECT_TRUE(closure.certificate.closed)
          << c.name << ", light " << i << (with_offset ? " (cap offset 0.01, epsilon 0.003)" : "");
      if (HasFailure()) return;
    }
  }
}

// The hard cases of docs/definitions.md#hard-cases for a smooth caster: f = 0 exactly at whole
// rings of vertices (a torus lit along its axis: its equators' normals are horizontal; a sphere
// with its equator vertex (1, 0, 0) on the terminator), and a light in faces' planes, where whole
// triangles cast nothing (f = 0 at all three corners: a box lit from one of its corners, and
// along its faces by a directional light; a floor with the light in its plane). Closed, and the
// CPU's volume up to float rounding and pairs that cancel.
TEST_F(SmoothSilhouetteVolumeTest, LightThroughVerticesOrInFacePlanes_ClosedAndEqualToTheCpuBuild) {
  const SmoothCaster torus_caster = caster_of(torus({0, 0, 0}, 1.0, 0.4, 16, 8));
  const SmoothCaster sphere_caster = caster_of(uv_sphere({0, 0, 0}, 1.0, 12, 6));
  const SmoothCaster box_caster = caster_of(box({0.5, 1, -0.5}, {1.5, 2, 0.5}));
  const SmoothCaster floor_caster = caster_of(floor_quad(2.0));
  const std::vector<std::pair<const SmoothCaster*, Light>> cases{
      {&torus_caster, Light{{0.0, 1.0, 0.0, 0.0}}},   {&sphere_caster, Light{{1.0, 3.0, 0.5, 1.0}}},
      {&box_caster, Light{{0.5, 2.0, 0.5, 1.0}}},     {&box_caster, Light{{0.5, 1.0, 0.5, 1.0}}},
      {&box_caster, Light{{0.0, 0.0, 1.0, 0.0}}},     {&box_caster, Light{{1.0, 1.0, 0.0, 0.0}}},
      {&floor_caster, Light{{0.5, 0.0, 3.0, 1.0}}},   {&floor_caster, Light{{1.0, 0.0, 0.0, 0.0}}}};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [caster, light] = cases[i];
    const SmoothCasterBuffers buffers(arrays_of(*caster, 0.01));
    SmoothSilhouetteVolume volume(buffers);
    volume.build(light);
    EXPECT_TRUE(certify_volume_closure(captured(volume)).certificate.closed) << "case " << i;
    const SmoothVolume cpu = smooth_shadow_volume(*caster, light, {.method = SilhouetteMethod::smooth});
    EXPECT_EQ(unmatched(volume.read_triangles(), cpu.mesh, 1e-4, true), 0u) << "case " << i;
  }
}

TEST_F(SmoothSilhouetteVolumeTest, SmallFirstBuffer_GrowsToTheWholeVolume) {
  // A fine sphere with an epsilon below float rounding: every silhouette segment is halved to
  // the depth bound (256 pieces), far more than the first sizing holds, so build() must grow.
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 256, 128));
  const SmoothCasterBuffers buffers(arrays_of(c, 1e-12));
  SmoothSilhouetteVolume volume(buffers);
  const std::uint64_t first = volume.capacity_vertices();
  volume.build(Light{{0.3, 2.0, 0.2, 1.0}});
  EXPECT_LE(volume.read_requested_vertices(), volume.capacity_vertices());
  EXPECT_GT(volume.capacity_vertices(), first);
  EXPECT_TRUE(certify_volume_closure(captured(volume)).certificate.closed);
}




TEST_F(SmoothSilhouetteVolumeTest, BadArrays_ThrowNamingTheClass) {
  const SmoothCaster c = caster_of(uv_sphere({0, 0, 0}, 1.0, 8, 4));
  SmoothCasterArrays a = arrays_of(c, 0.01);
  a.triangles[0][1] = 100000;
  EXPECT_THROW(SmoothCasterBuffers{a}, std::invalid_argument);
  a = arrays_of(c, 0.01);
  a.epsilon[3] = 0.0f;
  EXPECT_THROW(SmoothCasterBuffers{a}, std::invalid_argument);
  a = arrays_of(c, 0.01);
  a.across.pop_back();
  EXPECT_THROW(SmoothCasterBuffers{a}, std::invalid_argument);
  EXPECT_THROW(append_smooth_caster(a, c, -1.0, 0.0), std::invalid_argument);
  const SmoothCasterBuffers buffers(arrays_of(c, 0.01));
  SmoothSilhouetteVolume volume(buffers);
  EXPECT_THROW(volume.build(Light{{0.0, 0.0, 0.0, 0.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert::gpu
