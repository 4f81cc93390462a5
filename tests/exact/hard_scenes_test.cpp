// The scenes of data/scenes/hard/ (docs/definitions.md#hard-cases), GL-free: every scene loads as `shadowcert
// render` loads it (scene/scene_file.h with exact/'s read_soup), is small, is listed in the
// folder's README.md, and really is the hard case it is named after, checked exactly where the
// case is about exactness (a light exactly in a plane, on an edge's line, at a vertex), and by
// counting where it is about combinatorics (256 triangles on one edge, repeated indices,
// duplicates, bow-ties). tests/gpu/hard_case_render_test.cpp renders them with every method.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/vector3.h"
#include "core/scene.h"
#include "exact/caster_diagnostics.h"
#include "exact/count_certificate.h"
#include "exact/degenerate_triangles.h"
#include "exact/edge_multiplicity.h"
#include "exact/light_orientation.h"
#include "io/soup_file.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/merged_soup.h"
#include "scene/scene_file.h"
#include "scene/welded_soup.h"

namespace {

using namespace shadowcert;

const std::filesystem::path kFolder = std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data/scenes/hard";

// Small enough for every GL test and for a diff over the whole folder: the cameras' images.
constexpr std::uint64_t kMaxImagePixels = 256 * 192;
// And the scenes' triangles (the 256-blade fan and the room around it are the largest).
constexpr std::size_t kMaxTriangles = 1000;

// Every scene this file checks; EverySceneIsCheckedAndListed compares it with the folder.
const std::set<std::string> kCheckedScenes{"bow_tie_vertices",
                                           "camera_inside_volume",
                                           "coplanar_overlaps",
                                           "directional_parallel_to_faces",
                                           "duplicate_triangles",
                                           "fan_256_one_edge",
                                           "integer_grid_soup",
                                           "light_at_vertex",
                                           "light_in_floor_plane",
                                           "light_inside_closed_caster",
                                           "light_on_edge_line",
                                           "light_one_ulp_off_floor_plane",
                                           "offset_1e6",
                                           "repeated_indices",
                                           "scale_1e-3",
                                           "scale_1e-6",
                                           "scale_1e2",
                                           "scale_1e3",
                                           "scale_1e6",
                                           "slivers_and_zero_area",
                                           "t_junctions_and_cracks"};

std::vector<std::string> scene_names() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kFolder))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Scene load(const std::string& name) {
  return load_scene(kFolder / (name + ".json"), [](const std::filesystem::path& file) { return read_soup(file); });
}

const Soup& mesh(const Scene& scene, const std::string& name) {
  for (const SceneMesh& m : scene.meshes)
    if (m.name == name) return m.soup;
  throw std::invalid_argument("no mesh named " + name);
}

Sign sign_of(const Soup& soup, const Triangle& t, const Light& light) {
  return light_orientation(soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]], light);
}

// Exactly collinear points: every axis-direction orientation of (a, b, c) is zero, i.e.
// (b - a) x (c - a) = 0 (docs/definitions.md#orientation's orient with a point at infinity).
bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  for (const Light& axis : {Light{{1.0, 0.0, 0.0, 0.0}}, Light{{0.0, 1.0, 0.0, 0.0}}, Light{{0.0, 0.0, 1.0, 0.0}}})
    if (light_orientation(a, b, c, axis) != Sign::zero) return false;
  return true;
}

Vec3 position(const Light& light) { return {light.position[0], light.position[1], light.position[2]}; }
// x rounded to float, through memory: GCC 12.2 at -O2 (its SLP vectorizer) drops the round
// trip (double)(float)x of two neighbouring coordinates built in one braced initializer
// (seen here and in tests/exact/closure_certificate_test.cpp; docs/certificates.md).
double float_value(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}
Vec3 to_float(const Vec3& x) { return {float_value(x[0]), float_value(x[1]), float_value(x[2])}; }
Light to_float(const Light& l) {
  return Light{{float_value(l.position[0]), float_value(l.position[1]), float_value(l.position[2]), l.position[3]}};
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// ---- the folder --------------------------------------------------------------------------------

TEST(HardScenes, EverySceneIsCheckedAndListed) {
  const std::vector<std::string> names = scene_names();
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), kCheckedScenes);
  const std::string readme = read_text(kFolder / "README.md");
  for (const std::string& name : names) EXPECT_NE(readme.find("`" + name + ".json`"), std::string::npos) << name;
}

TEST(HardScenes, EverySceneLoadsSmallWithALightAndAShadowCaster) {
  for (const std::string& name : scene_names()) {
    SCOPED_TRACE(name);
    const Scene scene = load(name);
    ASSERT_FALSE(scene.lights.empty());
    EXPECT_LE(std::uint64_t{scene.camera.width} * scene.camera.height, kMaxImagePixels);
    const Soup soup = merged_soup(scene);
    EXPECT_LE(soup.triangles.size(), kMaxTriangles);
    // Every light has something to shadow: a triangle that casts exactly.
    for (const Light& light : scene.lights) {
      EXPECT_TRUE(std::any_of(soup.triangles.begin(), soup.triangles.end(),
                              [&](const Triangle& t) { return sign_of(soup, t, light) != Sign::zero; }));
    }
  }
}

// ---- one check per scene ------------------------------------------------------------------------

TEST(HardScenes, LightInFloorPlane_FloorCastsNothingExactly) {
  const Scene scene = load("light_in_floor_plane");
  const Soup& floor = mesh(scene, "floor");
  ASSERT_EQ(floor.triangles.size(), 2u);
  for (const Light& light : scene.lights)
    for (const Triangle& t : floor.triangles) EXPECT_EQ(sign_of(floor, t, light), Sign::zero);
  EXPECT_EQ(scene.lights.front().position[1], 0.0);  // the point light lies in y = 0 itself
  EXPECT_TRUE(scene.lights.back().directional());
}

TEST(HardScenes, LightOneUlpOffFloorPlane_ExactSeesTheUlpFloatDoesNot) {
  const Scene scene = load("light_one_ulp_off_floor_plane");
  const Soup& floor = mesh(scene, "floor");
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].position[1], std::nextafter(1.0, 2.0));
  EXPECT_EQ(scene.lights[1].position[1], std::nextafter(1.0, 0.0));
  for (const Vec3& v : floor.vertices) EXPECT_EQ(v[1], 1.0);
  for (const Triangle& t : floor.triangles) {
    const Sign above = sign_of(floor, t, scene.lights[0]), below = sign_of(floor, t, scene.lights[1]);
    EXPECT_NE(above, Sign::zero);
    EXPECT_EQ(below, -above);
    // Rounded to float (as every GPU method holds it), the light is in the plane.
    for (const Light& light : scene.lights) {
      EXPECT_EQ(light_orientation(to_float(floor.vertices[t[0]]), to_float(floor.vertices[t[1]]),
                                  to_float(floor.vertices[t[2]]), to_float(light)),
                Sign::zero);
    }
  }
}

TEST(HardScenes, LightOnEdgeLine_EachLightIsOnTheLineOfABoxEdgeBeyondIt) {
  const Scene scene = load("light_on_edge_line");
  const CanonicalSoup box = canonical_soup(mesh(scene, "box"));
  const EdgeTable table = build_edge_table(box.soup);
  for (const Light& light : scene.lights) {
    const Vec3 l = position(light);
    std::size_t on_line = 0;
    for (std::size_t e = 0; e < table.size(); ++e) {
      const Vec3 &a = box.soup.vertices[table.edges[e][0]], &b = box.soup.vertices[table.edges[e][1]];
      if (!collinear(a, b, l)) continue;
      ++on_line;
      // Beyond the edge, not on it: (l - a) . (l - b) > 0 (integers: exact in double).
      EXPECT_GT((l[0] - a[0]) * (l[0] - b[0]) + (l[1] - a[1]) * (l[1] - b[1]) + (l[2] - a[2]) * (l[2] - b[2]), 0.0);
      // The two faces on that edge hold the light in their plane: they cast nothing.
      for (std::uint32_t k = table.first_opposite[e]; k < table.first_opposite[e + 1]; ++k)
        EXPECT_EQ(sign_of(box.soup, box.soup.triangles[table.opposite_triangle[k]], light), Sign::zero);
    }
    EXPECT_EQ(on_line, 1u) << "light (" << l[0] << ", " << l[1] << ", " << l[2] << ")";
  }
}

TEST(HardScenes, LightAtVertex_ThePointLightIsAVertexOfTheRightBox) {
  const Scene scene = load("light_at_vertex");
  const Soup& box = mesh(scene, "right box");
  ASSERT_FALSE(scene.lights.front().directional());
  const Vec3 l = position(scene.lights.front());
  EXPECT_NE(std::find(box.vertices.begin(), box.vertices.end(), l), box.vertices.end());
  std::size_t zero = 0;
  for (const Triangle& t : box.triangles) zero += sign_of(box, t, scene.lights.front()) == Sign::zero;
  EXPECT_EQ(zero, 6u);  // the three faces through that corner, two triangles each
}

TEST(HardScenes, SliversAndZeroArea_CollinearSliverAndGrazingTriangles) {
  const Scene scene = load("slivers_and_zero_area");
  const Soup& soup = mesh(scene, "slivers.obj");
  const std::vector<TriangleShape> shapes = classify_triangle_shapes(weld_soup(soup).soup);
  EXPECT_EQ(std::count(shapes.begin(), shapes.end(), TriangleShape::Collinear), 1);
  // A sliver: proper, but its height over its longest edge is below 1e-9 (double is enough to
  // measure it; exact collinearity is what the classification above rules out).
  bool sliver = false;
  for (std::size_t i = 0; i < soup.triangles.size(); ++i) {
    if (shapes[i] != TriangleShape::Proper) continue;
    const Triangle& t = soup.triangles[i];
    const Vec3 &a = soup.vertices[t[0]], &b = soup.vertices[t[1]], &c = soup.vertices[t[2]];
    const Vec3 n = cross(difference(b, a), difference(c, a));
    const double area2 = std::sqrt(dot(n, n));
    double longest = 0.0;
    for (const auto& [p, q] : {std::pair{&a, &b}, std::pair{&b, &c}, std::pair{&c, &a}})
      longest = std::max(longest, std::hypot((*p)[0] - (*q)[0], (*p)[1] - (*q)[1], (*p)[2] - (*q)[2]));
    sliver = sliver || area2 / (longest * longest) < 1e-9;
  }
  EXPECT_TRUE(sliver);
  // The second light is 1e-9 off the plane z = 0 that holds most of the soup: edge-on, yet
  // exactly off the plane.
  const Light& grazing = scene.lights.at(1);
  EXPECT_EQ(grazing.position[2], 1e-9);
  EXPECT_EQ(light_orientation({-1, 1, 0}, {0, 1, 0}, {0, 2, 0}, grazing), Sign::positive);
}

TEST(HardScenes, RepeatedIndices_TrianglesRepeatAnIndexAndAVertexIsABitwiseCopy) {
  const Scene scene = load("repeated_indices");
  const Soup& soup = mesh(scene, "repeated_indices.obj");
  std::size_t repeated = 0;
  for (const Triangle& t : soup.triangles) repeated += !has_distinct_indices(t);
  EXPECT_EQ(repeated, 3u);
  std::set<Vec3> positions(soup.vertices.begin(), soup.vertices.end());
  EXPECT_EQ(positions.size() + 1, soup.vertices.size());  // one vertex is a copy, welded away
  // Welded, the triangle that names the copy and its original repeats an index too.
  EXPECT_EQ(diagnose_caster(soup).degenerate_triangles, 4u);
}

TEST(HardScenes, DuplicateTriangles_EveryFaceTwiceAndSomeFlipped) {
  const Scene scene = load("duplicate_triangles");
  const Soup& soup = mesh(scene, "duplicate_triangles.obj");
  std::map<std::array<std::uint32_t, 3>, int> same, flipped;  // by sorted vertex set
  std::size_t flips = 0;
  for (const Triangle& t : soup.triangles) {
    std::array<std::uint32_t, 3> key{t[0], t[1], t[2]};
    // Rotate the smallest index first: equal rotations are the same oriented triangle.
    std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
    ++same[key];
  }
  for (const auto& [key, n] : same) {
    const bool reversed = same.count({key[0], key[2], key[1]}) != 0;
    flips += reversed;
    EXPECT_TRUE(n >= 2 || reversed) << "a face neither duplicated nor flipped";
  }
  EXPECT_EQ(flips, 8u);  // 4 faces appear reversed; each pair is seen from both sides
  EXPECT_GT(diagnose_caster(soup).duplicate_triangles, 0u);
}

TEST(HardScenes, CoplanarOverlaps_OverlappingSquaresShareTwoPlanes) {
  const Scene scene = load("coplanar_overlaps");
  const Soup& soup = mesh(scene, "coplanar_overlaps.obj");
  std::map<double, std::size_t> per_plane;  // triangles per plane y = c, checked exactly below
  for (const Triangle& t : soup.triangles) {
    const Vec3 &a = soup.vertices[t[0]], &b = soup.vertices[t[1]], &c = soup.vertices[t[2]];
    ASSERT_TRUE(a[1] == b[1] && b[1] == c[1]);
    ++per_plane[a[1]];
  }
  EXPECT_EQ(per_plane, (std::map<double, std::size_t>{{1.5, 6}, {2.5, 4}}));
  // The squares of a plane overlap: their x-z boxes share an open region, pairwise.
  for (std::size_t s = 0; s + 1 < soup.triangles.size() / 2; ++s) {
    const Vec3 &lo1 = soup.vertices[4 * s], &hi1 = soup.vertices[4 * s + 2];
    const Vec3 &lo2 = soup.vertices[4 * s + 4], &hi2 = soup.vertices[4 * s + 6];
    if (lo1[1] != lo2[1]) continue;
    EXPECT_LT(std::max(lo1[0], lo2[0]), std::min(hi1[0], hi2[0])) << "square " << s;
    EXPECT_LT(std::max(lo1[2], lo2[2]), std::min(hi1[2], hi2[2])) << "square " << s;
  }
}

TEST(HardScenes, Fan256_OneEdgeCarries256TrianglesAndMultiplicity256) {
  const Scene scene = load("fan_256_one_edge");
  const CanonicalSoup fan = canonical_soup(mesh(scene, "half_fan_256.obj"));
  const EdgeTable table = build_edge_table(fan.soup);
  std::uint32_t most = 0;
  for (std::size_t e = 0; e < table.size(); ++e)
    most = std::max(most, table.first_opposite[e + 1] - table.first_opposite[e]);
  EXPECT_EQ(most, 256u);
  for (const Light& light : scene.lights) {
    const EdgeMultiplicities m = exact_multiplicities(fan.soup, table, light);
    std::int32_t largest = 0;
    for (std::int32_t x : m.multiplicity) largest = std::max(largest, std::abs(x));
    EXPECT_EQ(largest, 256) << (light.directional() ? "directional" : "point");
  }
}

TEST(HardScenes, Offset1e6_MillionOffsetsAndMillimetreFeaturesThatCollapseInFloat) {
  const Scene scene = load("offset_1e6");
  for (const SceneMesh& m : scene.meshes)
    for (const Vec3& v : m.soup.vertices)
      for (double x : v) EXPECT_GE(std::abs(x), 999990.0) << m.name;
  for (const std::string name : {"small sphere", "small cube"}) {
    const Soup& small = mesh(scene, name);
    std::set<Vec3> exact(small.vertices.begin(), small.vertices.end()), rounded;
    for (const Vec3& v : small.vertices) rounded.insert(to_float(v));
    for (int axis = 0; axis < 3; ++axis) {
      const auto [lo, hi] = std::minmax_element(small.vertices.begin(), small.vertices.end(),
                                                [axis](const Vec3& a, const Vec3& b) { return a[axis] < b[axis]; });
      EXPECT_LE((*hi)[axis] - (*lo)[axis], 2.1e-3) << name;  // a feature of 1e-3
    }
    // Float's ulp at 1e6 is 0.0625: the feature's distinct vertices fall on one float point.
    EXPECT_GT(exact.size(), 1u) << name;
    EXPECT_EQ(rounded.size(), 1u) << name;
    // Exactly, it still casts.
    EXPECT_NE(sign_of(small, small.triangles.front(), scene.lights.front()), Sign::zero) << name;
  }
}

// The scale in the name, and the geometry within a factor 100 of it (the room is 8 units wide).
void expect_scaled(const std::string& name, double scale) {
  SCOPED_TRACE(name);
  const Soup soup = merged_soup(load(name));
  double extent = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    const auto [lo, hi] = std::minmax_element(soup.vertices.begin(), soup.vertices.end(),
                                              [axis](const Vec3& a, const Vec3& b) { return a[axis] < b[axis]; });
    extent = std::max(extent, (*hi)[axis] - (*lo)[axis]);
  }
  EXPECT_GE(extent, scale);
  EXPECT_LE(extent, 100 * scale);
}

TEST(HardScenes, Scales_GeometryAt1eMinus6_1eMinus3_1e2_1e3_1e6) {
  expect_scaled("scale_1e-6", 1e-6);
  expect_scaled("scale_1e-3", 1e-3);
  expect_scaled("scale_1e2", 1e2);
  expect_scaled("scale_1e3", 1e3);
  expect_scaled("scale_1e6", 1e6);
}

TEST(HardScenes, TJunctionsAndCracks_AVertexInsideAnEdgeAndAGapOf1eMinus3) {
  const Scene scene = load("t_junctions_and_cracks");
  const CanonicalSoup strip = canonical_soup(mesh(scene, "t_junctions_and_cracks.obj"));
  const EdgeTable table = build_edge_table(strip.soup);
  std::size_t t_junctions = 0;
  for (std::size_t e = 0; e < table.size(); ++e) {
    const Vec3 &a = strip.soup.vertices[table.edges[e][0]], &b = strip.soup.vertices[table.edges[e][1]];
    for (std::size_t i = 0; i < strip.soup.vertices.size(); ++i) {
      const Vec3& x = strip.soup.vertices[i];
      if (i == table.edges[e][0] || i == table.edges[e][1] || !collinear(a, b, x)) continue;
      // Strictly between a and b (the strip lies in y = 1.5: compare x and z).
      t_junctions += (x[0] - a[0]) * (x[0] - b[0]) + (x[2] - a[2]) * (x[2] - b[2]) < 0.0;
    }
  }
  EXPECT_EQ(t_junctions, 1u);
  // The crack: border edges x = 0.5 and x = 0.501 (z from 0 to 1), no triangle between them.
  const auto border_at = [&](double x) {
    for (std::size_t e = 0; e < table.size(); ++e) {
      const Vec3 &a = strip.soup.vertices[table.edges[e][0]], &b = strip.soup.vertices[table.edges[e][1]];
      if (a[0] == x && b[0] == x && table.first_opposite[e + 1] - table.first_opposite[e] == 1) return true;
    }
    return false;
  };
  EXPECT_TRUE(border_at(0.5));
  EXPECT_TRUE(border_at(0.501));
}

TEST(HardScenes, BowTieVertices_TwoVerticesJoinPartsThatShareNoEdge) {
  const Scene scene = load("bow_tie_vertices");
  const CasterDiagnostics d = diagnose_caster(mesh(scene, "bow_ties.obj"));
  EXPECT_EQ(d.nonmanifold_vertices, 2u);
  EXPECT_EQ(d.nonmanifold_edges, 0u);
  // The second light lies on the z axis line through the tetrahedra's shared vertex.
  const Light& axis = scene.lights.at(1);
  EXPECT_EQ(axis.position[0], -1.0);
  EXPECT_EQ(axis.position[1], 2.0);
}

TEST(HardScenes, DirectionalParallelToFaces_SomeFacesExactlyParallelToEachLight) {
  const Scene scene = load("directional_parallel_to_faces");
  const Soup& cube = mesh(scene, "cube");
  const Soup& floor = mesh(scene, "floor");
  const std::array<std::size_t, 2> expected_parallel{4, 8};  // (1, 1, 0): 2 z faces; (0, 0, 1): 4 faces
  ASSERT_EQ(scene.lights.size(), 2u);
  for (std::size_t l = 0; l < 2; ++l) {
    const Light& light = scene.lights[l];
    EXPECT_TRUE(light.directional());
    std::size_t parallel = 0;
    for (const Triangle& t : cube.triangles) parallel += sign_of(cube, t, light) == Sign::zero;
    EXPECT_EQ(parallel, expected_parallel[l]) << "light " << l;
  }
  for (const Triangle& t : floor.triangles) EXPECT_EQ(sign_of(floor, t, scene.lights[1]), Sign::zero);
}

TEST(HardScenes, CameraInsideVolume_TheEyeIsShadowedByEveryLight) {
  const Scene scene = load("camera_inside_volume");
  const CanonicalSoup soup = canonical_soup(merged_soup(scene));
  for (const Light& light : scene.lights) {
    const std::optional<std::uint32_t> n = OccluderCounter(soup.soup, light).count(scene.camera.eye);
    ASSERT_TRUE(n.has_value());
    EXPECT_GE(*n, 1u);
  }
}

TEST(HardScenes, LightInsideClosedCaster_TheIcosphereIsClosedAndHoldsThePointLight) {
  const Scene scene = load("light_inside_closed_caster");
  const Soup& sphere = mesh(scene, "icosphere");
  const CasterDiagnostics d = diagnose_caster(sphere);
  EXPECT_TRUE(d.closed);
  EXPECT_TRUE(d.manifold);
  // The segment from the (outside) eye to the light crosses the closed sphere once.
  const std::optional<std::uint32_t> n = OccluderCounter(sphere, scene.lights.front()).count(scene.camera.eye);
  EXPECT_EQ(n, std::optional<std::uint32_t>(1));
}

TEST(HardScenes, IntegerGridSoup_IntegerCoordinatesAndLightsInTrianglePlanes) {
  const Scene scene = load("integer_grid_soup");
  const Soup& soup = mesh(scene, "integer_grid_soup.obj");
  for (const Vec3& v : soup.vertices)
    for (double x : v) EXPECT_EQ(x, std::round(x));
  for (const Light& light : scene.lights)
    for (double x : light.position) EXPECT_EQ(x, std::round(x));
  // Exact coplanarities: proper triangles with a light exactly in their plane.
  const std::vector<TriangleShape> shapes = classify_triangle_shapes(weld_soup(soup).soup);
  std::size_t in_plane = 0;
  for (std::size_t i = 0; i < soup.triangles.size(); ++i)
    in_plane +=
        shapes[i] == TriangleShape::Proper && sign_of(soup, soup.triangles[i], scene.lights.front()) == Sign::zero;
  EXPECT_GE(in_plane, 1u);
  EXPECT_GE(std::count(shapes.begin(), shapes.end(), TriangleShape::RepeatedIndex) +
                std::count(shapes.begin(), shapes.end(), TriangleShape::Collinear),
            1);
}

}  // namespace
