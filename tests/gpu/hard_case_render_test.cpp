// Every volume method against the exact `cpu` chain on the hard cases of docs/definitions.md#hard-cases,
// on llvmpipe or any EGL device, each drawn as `render --method` draws it
// (gpu/shadow_method_renderer.h, one light at a time):
//  1. every scene of data/scenes/hard/, every one of its lights (point and directional): each
//     method (cpu, cs, gs, ts, pertri) builds its volume without overflow and the volume it drew
//     is certified closed by exact/'s certify_volume_closure (docs/definitions.md#closure, on the float
//     triangles read back); each GPU method's z-fail stencil counts equal the reference's on
//     every pixel that is not a boundary pixel (defined at kBoundaryRadius), and the boundary
//     pixels where they differ are counted and bounded by kMaxBoundaryDifferenceFraction of the
//     image. The reference is cpu, the exact chain of the input rounded to float as the GPU
//     receives it (exact/cpu_volume.h): on light_one_ulp_off_floor_plane.json, where the lights
//     lie in the floor's plane once rounded, the floor casts nothing for cpu as for the others;
//  2. camera_inside_volume.json: z-fail equals cpu for every method; z-pass is off by exactly the
//     eye's own occluder count n(eye) >= 1 (exact) on every non-boundary pixel;
//  3. an edge with 100 opposite triangles, every apex on one side of the light: every method,
//     cpu included, draws |m| = 100 copies of that edge's side quad (counted in the triangles it
//     drew) and counts as cpu off boundaries, point and directional light.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "exact/volume_closure.h"
#include "core/homogeneous_mesh.h"
#include "core/scene.h"
#include "io/volume_file.h"
#include "exact/count_certificate.h"
#include "io/soup_file.h"
#include "support/gl_test_support.h"
#include "gpu/flat_soup_renderer.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_method_renderer.h"
#include "gpu/soup_mesh.h"
#include "gpu/stencil_shadow_renderer.h"
#include "scene/merged_soup.h"
#include "scene/scene_file.h"
#include "support/volume_test_support.h"

namespace shadowcert::gpu {
namespace {

using namespace test;

// ---- the comparison ------------------------------------------------------------------------

// A pixel is a BOUNDARY pixel when some pixel within kBoundaryRadius of it (Chebyshev distance:
// its 8 neighbours for radius 1; pixels outside the image do not count), the pixel itself
// included, differs from it in
//   - the reference's stencil count (modulo 256): a face of the reference volume passes
//     between the two pixel centres;
//   - coverage (a receiver drawn or not): a silhouette of the scene; or
//   - the receiver triangle visible at the pixel centre: docs/definitions.md#pixel-protocol calls a pixel whose
//     footprint sees different triangles ambiguous. Along a triangle's edge the volume faces
//     that start on that edge (every edge's quads for pertri, whose interior pairs must cancel;
//     the silhouette's quads for all) have the visible surface's own depth, and which of them
//     pass the depth test is decided by rounding.
// Everywhere else the count is constant over the pixel's neighbourhood, on one triangle, so a
// method whose faces differ from the reference's by roundings (far vertices x_f - l_f in float
// against x - l in double, pertri's other quad diagonal, a float sign against the exact one
// for a triangle (almost) edge-on to the light, whose V(t) is thinner than a pixel) cannot
// change it. An open or wrongly oriented volume, a missing record or a wrong multiplicity
// changes whole regions, whose inner pixels are not boundary pixels: the test fails there.
constexpr int kBoundaryRadius = 1;
// The boundary pixels where a method may differ from the reference, as a fraction of the
// image's pixels: differences lie along level lines of the count and triangle edges of the
// visible surface, at most a few image widths long in these scenes. Measured on llvmpipe
// (256 x 192 = 49152 pixels, printed per scene, light and method): cs, gs and ts 0 everywhere;
// pertri at most 35 (directional_parallel_to_faces.json, where its quads' other diagonal
// moves pixels next to side planes) and 1 in scale_1e2.json (110 while its interior pairs did
// not always cancel, below); the bound is 491.
constexpr double kMaxBoundaryDifferenceFraction = 0.01;
// pertri's interior pairs: each triangle on an interior edge emits that edge's side quad, the
// two in one vertex order, one of them drawn with the facings' stencil operations swapped
// (gpu/shaders/per_triangle_volume.comp.glsl), so they cancel at every pixel and pertri, like
// cs, gs and ts, equals the reference off boundaries. When the two were written as reversed
// triangles, llvmpipe rounded their depths apart where they met the visible surface and they
// did not cancel on dotted lines along those edges: up to 2 pixels per frame at unit scale and
// 88 in scale_1e2.json here (the count off by one, by two where two pairs met), a tolerance
// this test had for pertri alone; now 0 everywhere.
// Shadowed receiver pixels (reference count != 0) the FIRST light of every hard scene must
// show, so that each scene's comparison is about a visible shadow.
constexpr std::size_t kMinShadowedPixels = 60;

using TriangleIds = std::vector<std::int64_t>;  // per pixel, row 0 at the top; -1: no receiver

// The receiver triangle (index in `soup`) seen at each pixel centre: each triangle drawn alone
// in a flat colour that encodes its index, depth-tested, into `target` (which is cleared).
TriangleIds visible_triangles(const Soup& soup, const Camera& camera, const OffscreenTarget& target) {
  if (soup.triangles.size() >= (1u << 24) - 1) throw std::invalid_argument("visible_triangles: too many triangles");
  const FlatSoupRenderer flat;
  target.bind();
  target.clear({0.0f, 0.0f, 0.0f, 0.0f});
  for (std::size_t i = 0; i < soup.triangles.size(); ++i) {
    const Triangle& t = soup.triangles[i];
    Soup one;
    one.vertices = {soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]};
    one.triangles = {{0, 1, 2}};
    const SoupMesh mesh(one);
    const std::size_t code = i + 1;  // 0 is the background
    flat.draw(mesh, camera,
              {.colour = {static_cast<float>(code & 0xFF) / 255.0f, static_cast<float>((code >> 8) & 0xFF) / 255.0f,
                          static_cast<float>((code >> 16) & 0xFF) / 255.0f, 1.0f}});
  }
  const RgbaImage colour = target.read_colour();
  TriangleIds ids(colour.pixels.size() / 4);
  for (std::size_t p = 0; p < ids.size(); ++p) {
    const std::int64_t code = colour.pixels[4 * p] | (colour.pixels[4 * p + 1] << 8) | (colour.pixels[4 * p + 2] << 16);
    ids[p] = code - 1;
  }
  return ids;
}

struct CountComparison {
  std::size_t pixels = 0;
  std::size_t shadowed = 0;            // covered by a receiver, reference count != 0
  std::size_t boundary = 0;            // boundary pixels (see kBoundaryRadius)
  std::size_t differing_boundary = 0;  // boundary pixels where the counts differ
  std::size_t differing_inside = 0;    // other pixels where the counts differ: must be 0
  int largest_inside_step = 0;         // of those, the largest |method - expected| (mod 256, signed)
  std::string first_inside;            // "x,row: reference a, method b; " for the first few
};

// Compares `method`'s first-light counts, plus `offset` (mod 256), with `reference`'s.
CountComparison compare_counts(const StencilShadowFrame& reference, const StencilShadowFrame& method,
                               const TriangleIds& ids, int offset = 0) {
  const GrayImage& a = reference.first_stencil;
  const GrayImage& b = method.first_stencil;
  if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size() ||
      reference.colour.pixels.size() != 4 * a.pixels.size() || ids.size() != a.pixels.size())
    throw std::invalid_argument("compare_counts: images of different sizes");
  const auto covered = [&](std::size_t i) { return reference.colour.pixels[4 * i + 3] != 0; };
  const auto w = static_cast<int>(a.width), h = static_cast<int>(a.height);
  CountComparison c;
  c.pixels = a.pixels.size();
  for (int row = 0; row < h; ++row) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(row) * a.width + static_cast<std::size_t>(x);
      bool boundary = false;
      for (int dr = -kBoundaryRadius; dr <= kBoundaryRadius; ++dr) {
        for (int dx = -kBoundaryRadius; dx <= kBoundaryRadius; ++dx) {
          const int r2 = row + dr, x2 = x + dx;
          if (r2 < 0 || r2 >= h || x2 < 0 || x2 >= w) continue;
          const std::size_t j = static_cast<std::size_t>(r2) * a.width + static_cast<std::size_t>(x2);
          boundary = boundary || a.pixels[j] != a.pixels[i] || covered(j) != covered(i) || ids[j] != ids[i];
        }
      }
      c.boundary += boundary;
      c.shadowed += covered(i) && a.pixels[i] != 0;
      const auto expected = static_cast<std::uint8_t>(a.pixels[i] - offset);  // modulo 256
      if (b.pixels[i] == expected) continue;
      if (boundary) {
        ++c.differing_boundary;
        continue;
      }
      c.largest_inside_step =
          std::max(c.largest_inside_step, std::abs(static_cast<int>(static_cast<std::int8_t>(b.pixels[i] - expected))));
      if (c.differing_inside++ < 4) {
        c.first_inside += std::to_string(x) + "," + std::to_string(row) + (covered(i) ? "" : " (no receiver)") +
                          ": expected " + std::to_string(expected) + ", method " + std::to_string(b.pixels[i]) + "; ";
      }
    }
  }
  return c;
}

std::size_t max_boundary_differences(const CountComparison& c) {
  return static_cast<std::size_t>(kMaxBoundaryDifferenceFraction * static_cast<double>(c.pixels));
}

// The counts equal the reference's on every non-boundary pixel, and differ on few boundary
// pixels.
void expect_equal_off_boundaries(ShadowMethod method, const CountComparison& c) {
  EXPECT_EQ(c.differing_inside, 0u) << shadow_method_name(method) << ", first: " << c.first_inside;
  EXPECT_LE(c.differing_boundary, max_boundary_differences(c));
}

// ---- the hard scenes -------------------------------------------------------------------------

std::filesystem::path hard_scene_folder() { return std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data/scenes/hard"; }

std::vector<std::string> hard_scene_names() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(hard_scene_folder()))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Scene load_hard_scene(const std::string& name) {
  return load_scene(hard_scene_folder() / (name + ".json"),
                    [](const std::filesystem::path& file) { return read_soup(file); });
}

std::string light_label(std::size_t index, const Light& light) {
  return "light " + std::to_string(index) + (light.directional() ? " (directional)" : " (point)");
}

// One frame of a method and the volume it drew (cpu: the exact chain as uploaded; GPU-built
// methods: the triangles read back after the frame, unwelded).
struct MethodFrame {
  ShadowMethod method;
  StencilShadowFrame frame;
  HomogeneousMesh volume;
};

// One soup and camera, prepared once: the target every method draws into, and the visible
// triangle at each pixel.
struct Rig {
  Rig(const Soup& scene_soup, const Camera& scene_camera)
      : soup(scene_soup),
        camera(scene_camera),
        prepared(prepare(soup)),
        target(camera.width, camera.height),
        ids(visible_triangles(soup, camera, target)) {}

  // A frame of `method` lit by `light` alone, as `render --method` draws it (one_light_renderer;
  // cpu draws cpu_volume(prepared, light)); the volume must not have overflowed its buffers.
  [[nodiscard]] MethodFrame draw(ShadowMethod method, const Light& light,
                                 StencilMethod stencil = StencilMethod::zfail) const {
    const HomogeneousMesh cpu = method == ShadowMethod::cpu ? cpu_volume(prepared, light) : HomogeneousMesh{};
    ShadowMethodRenderer renderer = one_light_renderer(method, soup, prepared, light, &cpu, stencil);
    StencilShadowFrame frame = renderer.render(target, camera);
    EXPECT_NO_THROW(renderer.check_capacity()) << shadow_method_name(method) << ": the drawn volume is truncated";
    return {method, std::move(frame), renderer.first_volume()};
  }

  Soup soup;
  Camera camera;
  Prepared prepared;
  OffscreenTarget target;
  TriangleIds ids;
};

// The volume `drawn` drew is closed: exact/'s certificate (docs/definitions.md#closure) on its float
// triangles as drawn.
void expect_closed(const MethodFrame& drawn) {
  const VolumeClosure closure = certify_volume_closure(drawn.volume);
  EXPECT_TRUE(closure.certificate.closed)
      << shadow_method_name(drawn.method) << ": " << closure.certificate.unbalanced.size() << " unbalanced edges of "
      << drawn.volume.triangles.size() << " triangles";
}

class HardCaseRenderTest : public GlTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(HardCaseRenderTest, EveryMethodIsClosedAndCountsAsCpuOffBoundaries) {
  const Scene scene = load_hard_scene(GetParam());
  ASSERT_FALSE(scene.lights.empty());
  const Rig rig(merged_soup(scene), scene.camera);
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    const Light& light = scene.lights[l];
    const std::string label = GetParam() + ", " + light_label(l, light);
    SCOPED_TRACE(label);
    const MethodFrame cpu = rig.draw(ShadowMethod::cpu, light);
    expect_closed(cpu);
    const StencilShadowFrame& reference = cpu.frame;
    for (ShadowMethod method : kGpuBuiltMethods) {
      SCOPED_TRACE(shadow_method_name(method));
      const MethodFrame drawn = rig.draw(method, light);
      expect_closed(drawn);
      const CountComparison c = compare_counts(reference, drawn.frame, rig.ids);
      std::cout << label << ", " << shadow_method_name(method) << " against cpu: " << c.shadowed
                << " shadowed, " << c.boundary << " boundary pixels, " << c.differing_boundary << " of them differ; "
                << c.differing_inside << " others differ (largest step " << c.largest_inside_step << ")\n";
      expect_equal_off_boundaries(method, c);
      if (l == 0) { EXPECT_GE(c.shadowed, kMinShadowedPixels) << "the camera should see the first light's shadow"; }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(HardScenes, HardCaseRenderTest, ::testing::ValuesIn(hard_scene_names()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

// ---- the camera inside a shadow volume -------------------------------------------------------

// Covered non-boundary pixels where z-pass must be off by n(eye): most of the image (the eye
// looks at floor and wall in and out of the slab's shadow).
constexpr std::size_t kMinZPassOffPixels = 20000;
// The GL context fixture (support/gl_test_support.h) under this unit's name, for
// --gtest_filter=HardCaseSceneTest.*
class HardCaseSceneTest : public GlTest {};

TEST_F(HardCaseSceneTest, CameraInsideAVolume_ZFailEqualsCpuZPassIsOffByTheEyesCount) {
  const Scene scene = load_hard_scene("camera_inside_volume");
  const Rig rig(merged_soup(scene), scene.camera);
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    const Light& light = scene.lights[l];
    SCOPED_TRACE(light_label(l, light));
    const std::optional<std::uint32_t> eye_count =
        OccluderCounter(rig.prepared.canonical.soup, light).count(scene.camera.eye);
    ASSERT_TRUE(eye_count.has_value()) << "the eye must not lie on a volume boundary";
    ASSERT_GE(*eye_count, 1u) << "the eye must be inside a shadow volume";
    const StencilShadowFrame reference = rig.draw(ShadowMethod::cpu, light).frame;
    for (ShadowMethod method : kVolumeMethods) {
      SCOPED_TRACE(std::string(shadow_method_name(method)));
      const CountComparison zfail =
          compare_counts(reference, rig.draw(method, light, StencilMethod::zfail).frame, rig.ids);
      expect_equal_off_boundaries(method, zfail);
      // z-pass counts the faces between the eye and P: n(P) - n(eye).
      const StencilShadowFrame zpass_frame = rig.draw(method, light, StencilMethod::zpass).frame;
      const CountComparison zpass = compare_counts(reference, zpass_frame, rig.ids, static_cast<int>(*eye_count));
      expect_equal_off_boundaries(method, zpass);
      const CountComparison zpass_as_zfail = compare_counts(reference, zpass_frame, rig.ids);
      std::cout << "camera inside, " << light_label(l, light) << ", n(eye) = " << *eye_count << ", "
                << shadow_method_name(method) << ": z-fail differs on " << zfail.differing_inside << " + "
                << zfail.differing_boundary << " boundary pixels, z-pass on " << zpass_as_zfail.differing_inside
                << " + " << zpass_as_zfail.differing_boundary << "\n";
      EXPECT_GE(zpass_as_zfail.differing_inside, kMinZPassOffPixels) << "z-pass should miss the eye's own count";
    }
  }
}

// ---- an edge with 100 opposite triangles ------------------------------------------------------

// volume_test_support.h's half fan of 100 blades before its wall: with the light in the plane
// x = 0, |m| = 100, beyond gs's 4 and ts's 16 opposites per record and cs's single edge
// invocation.
constexpr std::uint32_t kBlades = 100;

// The side quads drawn on the edge a-b: +1 per triangle that holds the directed edge a -> b and
// a far vertex (w = 0), -1 per one with b -> a (vertices compared by value: GPU-built volumes
// are read back unwelded). Every method splits a side quad so that exactly one of its
// triangles holds the finite edge, and caps hold no far vertex with it, so this is the edge's
// multiplicity as drawn.
std::int64_t drawn_side_multiplicity(const HomogeneousMesh& volume, const Vec4f& a, const Vec4f& b) {
  std::int64_t m = 0;
  for (const auto& triangle : volume.triangles) {
    const std::array<Vec4f, 3> t{volume.vertices.at(triangle[0]), volume.vertices.at(triangle[1]),
                                 volume.vertices.at(triangle[2])};
    if (std::none_of(t.begin(), t.end(), [](const Vec4f& x) { return x[3] == 0.0f; })) continue;
    for (int k = 0; k < 3; ++k) {
      if (t[k] == a && t[(k + 1) % 3] == b) ++m;
      if (t[k] == b && t[(k + 1) % 3] == a) --m;
    }
  }
  return m;
}

TEST_F(HardCaseSceneTest, EdgeWithHundredOppositeTriangles_EveryMethodReachesMultiplicity100AndCountsAsCpu) {
  Camera camera;
  camera.eye = {4.0, 3.0, -6.0};  // on the light's side, looking at the fan and the wall
  camera.target = {0.0, 0.5, kHalfFanWallZ};
  camera.width = 256;
  camera.height = 192;
  const Rig rig(half_fan_and_wall(kBlades), camera);
  const Vec4f edge_start{0.0f, 0.0f, 0.0f, 1.0f}, edge_end{0.0f, 1.0f, 0.0f, 1.0f};
  for (const Light& light : {kHalfFanLight, Light{{0.0, 0.2, -1.0, 0.0}}}) {
    SCOPED_TRACE(light.directional() ? "directional" : "point");
    const StencilShadowFrame reference = rig.draw(ShadowMethod::cpu, light).frame;
    for (ShadowMethod method : kVolumeMethods) {
      SCOPED_TRACE(std::string(shadow_method_name(method)));
      const MethodFrame drawn = rig.draw(method, light);
      expect_closed(drawn);
      const CountComparison c = compare_counts(reference, drawn.frame, rig.ids);
      const std::int64_t m = drawn_side_multiplicity(drawn.volume, edge_start, edge_end);
      EXPECT_EQ(std::abs(m), static_cast<std::int64_t>(kBlades));
      std::cout << "half fan of " << kBlades << ", " << (light.directional() ? "directional" : "point") << ", "
                << shadow_method_name(method) << ": drawn m = " << m << ", " << c.shadowed << " shadowed, "
                << c.differing_boundary << " boundary pixels differ, " << c.differing_inside << " others\n";
      EXPECT_GE(c.shadowed, kMinShadowedPixels);
      expect_equal_off_boundaries(method, c);
    }
  }
}

}  // namespace
}  // namespace shadowcert::gpu
