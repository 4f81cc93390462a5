#include "core/vector3.h"
#include "scene/scene_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/input_error.h"
#include "core/near_plane.h"

using shadowcert::InputError;
using shadowcert::Scene;
using shadowcert::Soup;
using shadowcert::cross;
using shadowcert::difference;
using shadowcert::dot;
using shadowcert::Vec3;

namespace {

const std::filesystem::path kTestScenes = std::filesystem::path(SHADOWCERT_TEST_DATA) / "scenes";
const std::filesystem::path kBundledScenes = std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "scenes";

// Scenes built from generators only must never ask for a file.
Soup no_mesh_files(const std::filesystem::path& p) {
  throw std::logic_error("this scene should not read mesh files, asked for " + p.string());
}

Scene parse(const std::string& json) { return shadowcert::parse_scene(json, "inline.json", "/scenes", no_mesh_files); }

Vec3 sub(const Vec3& a, const Vec3& b) { return difference(a, b); }
Vec3 unit(const Vec3& v) {
  const double l = std::sqrt(dot(v, v));
  return {v[0] / l, v[1] / l, v[2] / l};
}

double signed_volume(const Soup& s) {
  double six_v = 0.0;
  for (const auto& t : s.triangles)
    six_v += dot(s.vertices[t[0]], cross(s.vertices[t[1]], s.vertices[t[2]]));
  return six_v / 6.0;
}

// Whether a world point projects inside the camera's image (pinhole, docs/definitions.md#pixel-protocol).
bool in_view(const shadowcert::Camera& c, const Vec3& q) {
  const Vec3 f = unit(sub(c.target, c.eye));
  const Vec3 r = unit(cross(f, c.up));
  const Vec3 u = cross(r, f);
  const Vec3 d = sub(q, c.eye);
  const double z = dot(d, f);
  if (!(z > 0.0)) return false;
  const double half_h = std::tan(c.fov_y_degrees * 3.141592653589793 / 360.0);
  const double half_w = half_h * c.width / c.height;
  return std::abs(dot(d, u) / z) < half_h && std::abs(dot(d, r) / z) < half_w;
}

}  // namespace

TEST(ParseScene, EmptyObject_AllDefaults) {
  const Scene s = parse("{}");
  EXPECT_TRUE(s.meshes.empty());
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].position, (shadowcert::Light{}.position));
  const shadowcert::Camera d;
  EXPECT_EQ(s.camera.eye, d.eye);
  EXPECT_EQ(s.camera.target, d.target);
  EXPECT_EQ(s.camera.up, d.up);
  EXPECT_EQ(s.camera.fov_y_degrees, d.fov_y_degrees);
  EXPECT_EQ(s.camera.width, d.width);
  EXPECT_EQ(s.camera.height, d.height);
}

TEST(ParseScene, NoLights_OnePointLightAboveTheScene) {
  const Scene s = parse(R"({"meshes": [{"generator": "floor", "params": {"half_size": 10}}]})");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].position, (std::array<double, 4>{0.0, std::hypot(20.0, 0.0, 20.0), 0.0, 1.0}));
}

TEST(ParseScene, AllGenerators_DefaultParams) {
  const std::map<std::string, std::size_t> triangles = {
      {"floor", 2},           {"box", 12},          {"uv_sphere", 2 * 32 * 15},    {"icosphere", 20 * 64},
      {"torus", 2 * 48 * 24}, {"sphere_grid", 1'000'000}, {"random_soup", 100}, {"nonmanifold_fan", 8},
      {"open_box_with_fins", 14}, {"torus_knot", 2 * 128 * 12}};
  for (const auto& [name, count] : triangles) {
    const Scene s = parse(R"({"meshes": [{"generator": ")" + name + R"("}]})");
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].name, name);
    EXPECT_EQ(s.meshes[0].soup.triangles.size(), count) << name;
  }
}

TEST(ParseScene, GeneratorParams_Passed) {
  const Scene s = parse(R"({"meshes": [
    {"generator": "uv_sphere", "params": {"center": [1, 2, 3], "radius": 2, "slices": 5, "stacks": 4}},
    {"generator": "sphere_grid", "params": {"triangles": 32000}},
    {"generator": "random_soup", "params": {"seed": 18446744073709551615, "triangles": 3, "extent": 0.5}},
    {"generator": "nonmanifold_fan", "params": {"k": 256}, "name": "big fan"}]})");
  ASSERT_EQ(s.meshes.size(), 4u);
  EXPECT_EQ(s.meshes[0].soup.triangles.size(), 2u * 5 * 3);
  EXPECT_EQ(s.meshes[0].soup.vertices.front(), (Vec3{1, 4, 3}));  // north pole
  EXPECT_EQ(s.meshes[1].soup.triangles.size(), 32000u);
  EXPECT_EQ(s.meshes[2].soup.triangles.size(), 3u);
  EXPECT_EQ(s.meshes[3].soup.triangles.size(), 256u);
  EXPECT_EQ(s.meshes[3].name, "big fan");
}

TEST(ParseScene, WholeFloat_AcceptedAsUnsigned) {
  const Scene s = parse(R"({"meshes": [{"generator": "sphere_grid", "params": {"triangles": 3.2e4}}],
                            "camera": {"size": [640.0, 480]}})");
  EXPECT_EQ(s.meshes[0].soup.triangles.size(), 32000u);
  EXPECT_EQ(s.camera.width, 640u);
}

TEST(ParseScene, Trs_ScaleThenRotateThenTranslate) {
  // Fan vertex 2 is (1, 0.5, 0): scale 2 -> (2, 1, 0); 90 deg about y -> (0, 1, -2); +t.
  const Scene s = parse(R"({"meshes": [{"generator": "nonmanifold_fan", "params": {"k": 1},
      "transform": {"translate": [1, 2, 3], "scale": 2, "rotate_deg": [0, 90, 0]}}]})");
  const auto& v = s.meshes[0].soup.vertices;
  EXPECT_EQ(v[0], (Vec3{1, 2, 3}));
  EXPECT_EQ(v[1], (Vec3{1, 4, 3}));
  EXPECT_EQ(v[2], (Vec3{1, 3, 1}));  // exact: multiples of 90 degrees use exact sines
}

TEST(ParseScene, Rotation_XThenYThenZ) {
  // (0, 1, 0) -> about x by 90 -> (0, 0, 1) -> about y by 90 -> (1, 0, 0). The other order
  // would give (0, 0, 1).
  const Scene s = parse(R"({"meshes": [{"generator": "nonmanifold_fan", "params": {"k": 1},
      "transform": {"rotate_deg": [90, 90, 0]}}]})");
  EXPECT_EQ(s.meshes[0].soup.vertices[1], (Vec3{1, 0, 0}));
  const Scene z = parse(R"({"meshes": [{"generator": "nonmanifold_fan", "params": {"k": 1},
      "transform": {"rotate_deg": [0, 0, 90], "scale": [1, 1, 1]}}]})");
  EXPECT_EQ(z.meshes[0].soup.vertices[2], (Vec3{-0.5, 1, 0}));  // counter-clockwise about +z
}

TEST(ParseScene, GeneralAngle_MatchesRotationMatrix) {
  const Scene s = parse(R"({"meshes": [{"generator": "nonmanifold_fan", "params": {"k": 1},
      "transform": {"rotate_deg": [0, 30, 0]}}]})");
  const Vec3 p = s.meshes[0].soup.vertices[2];  // (1, 0.5, 0) rotated about y
  EXPECT_NEAR(p[0], std::sqrt(3.0) / 2, 1e-15);
  EXPECT_EQ(p[1], 0.5);
  EXPECT_NEAR(p[2], -0.5, 1e-15);
}

TEST(ParseScene, Matrix_RowMajorOnColumnVectors) {
  const Scene s = parse(R"({"meshes": [{"generator": "nonmanifold_fan", "params": {"k": 1},
      "transform": {"matrix": [0, -1, 0, 5,  1, 0, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1]}}]})");
  EXPECT_EQ(s.meshes[0].soup.vertices[2], (Vec3{4.5, 1, 0}));
}

TEST(ParseScene, Mirror_KeepsOutwardOrientationAndNormals) {
  const Scene s = parse(R"({"meshes": [{"generator": "uv_sphere",
      "transform": {"scale": [-1, 1, 1]}}]})");
  const Soup& soup = s.meshes[0].soup;
  EXPECT_GT(signed_volume(soup), 0.0);
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
    const Vec3 n{soup.normals[i][0], soup.normals[i][1], soup.normals[i][2]};
    EXPECT_GT(dot(n, soup.vertices[i]), 0.0);
  }
}

TEST(ParseScene, NonUniformScale_NormalsByInverseTranspose) {
  // The sphere scaled by 3 along y is the ellipsoid x^2 + (y/3)^2 + z^2 = 1 whose normal at p
  // is along (x, y/9, z).
  const Scene s = parse(R"({"meshes": [{"generator": "uv_sphere", "transform": {"scale": [1, 3, 1]}}]})");
  const Soup& soup = s.meshes[0].soup;
  ASSERT_EQ(soup.normals.size(), soup.vertices.size());
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
    const Vec3& p = soup.vertices[i];
    const Vec3 expected = unit({p[0], p[1] / 9, p[2]});
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(soup.normals[i][a], expected[a], 1e-6);
  }
}

TEST(ParseScene, MeshKeys_CastsSilhouetteAndEpsilonRead) {
  const Scene s = parse(R"({"meshes": [
    {"generator": "floor", "casts": false},
    {"generator": "uv_sphere", "silhouette": "smooth", "epsilon": 0.02},
    {"generator": "box", "silhouette": "chain", "casts": true},
    {"generator": "icosphere", "epsilon": 1e-3},
    {"generator": "torus"}]})");
  ASSERT_EQ(s.meshes.size(), 5u);
  EXPECT_FALSE(s.meshes[0].casts);
  EXPECT_EQ(s.meshes[1].silhouette, shadowcert::MeshSilhouette::smooth);
  EXPECT_EQ(s.meshes[1].epsilon, 0.02);
  EXPECT_TRUE(s.meshes[2].casts);
  EXPECT_EQ(s.meshes[2].silhouette, shadowcert::MeshSilhouette::chain);
  // An epsilon without "silhouette" is kept: it applies whenever the command casts the mesh smooth.
  EXPECT_FALSE(s.meshes[3].silhouette.has_value());
  EXPECT_EQ(s.meshes[3].epsilon, 1e-3);
  // Absent keys: the mesh casts, and the command decides.
  EXPECT_TRUE(s.meshes[4].casts);
  EXPECT_FALSE(s.meshes[4].silhouette.has_value());
  EXPECT_FALSE(s.meshes[4].epsilon.has_value());
  for (const char* name : {"discrete", "accurate"})
    EXPECT_TRUE(parse(std::string(R"({"meshes": [{"generator": "box", "silhouette": ")") + name + R"("}]})")
                    .meshes[0]
                    .silhouette.has_value())
        << name;
}

// |A^-1 (x - c)| for the ellipsoid x = c + A u: 1 on its surface.
double ellipsoid_radius(const shadowcert::Ellipsoid& e, const Vec3& x) {
  const Vec3& a = e.axes[0];
  const Vec3& b = e.axes[1];
  const Vec3& c = e.axes[2];
  // A^-1 = (rows b x c, c x a, a x b) / det A, by Cramer's rule.
  const double det = dot(a, cross(b, c));
  const Vec3 d = sub(x, e.centre);
  const Vec3 u{dot(cross(b, c), d) / det, dot(cross(c, a), d) / det, dot(cross(a, b), d) / det};
  return std::sqrt(dot(u, u));
}

TEST(ParseScene, SphereGenerators_RecordTheirEllipsoidUnderAnyTransform) {
  const Scene s = parse(R"({"meshes": [
    {"generator": "uv_sphere", "params": {"center": [1, 0, 0], "radius": 2}},
    {"generator": "uv_sphere", "params": {"center": [1, 0, 0], "radius": 2},
     "transform": {"translate": [1, 2, 3], "scale": [2, 3, 4]}},
    {"generator": "icosphere", "params": {"center": [0.5, -1, 2], "radius": 0.75, "subdivisions": 2},
     "transform": {"translate": [-3, 1, 0.25], "scale": [1, 0.5, 2], "rotate_deg": [20, -35, 110]}},
    {"generator": "uv_sphere", "params": {"radius": 1.5, "slices": 9, "stacks": 7},
     "transform": {"matrix": [1, 0.5, 0, 2,  0, -1, 0.25, 0,  0.3, 0, 2, -1,  0, 0, 0, 1]}},
    {"generator": "icosphere", "transform": {"rotate_deg": [0, 0, 45], "scale": -2}}]})");
  ASSERT_EQ(s.meshes.size(), 5u);
  // Untransformed: the params' sphere. Scaled and moved: centre M c, axes A r e_i.
  ASSERT_TRUE(s.meshes[0].ellipsoid.has_value());
  EXPECT_EQ(s.meshes[0].ellipsoid->centre, (Vec3{1, 0, 0}));
  EXPECT_EQ(s.meshes[0].ellipsoid->axes, (std::array<Vec3, 3>{{{2, 0, 0}, {0, 2, 0}, {0, 0, 2}}}));
  ASSERT_TRUE(s.meshes[1].ellipsoid.has_value());
  EXPECT_EQ(s.meshes[1].ellipsoid->centre, (Vec3{3, 2, 3}));
  EXPECT_EQ(s.meshes[1].ellipsoid->axes, (std::array<Vec3, 3>{{{4, 0, 0}, {0, 6, 0}, {0, 0, 8}}}));
  // Whatever the transform (rotation, shear, mirror), every vertex lies on the recorded surface.
  for (const shadowcert::SceneMesh& mesh : s.meshes) {
    ASSERT_TRUE(mesh.ellipsoid.has_value()) << mesh.name;
    double worst = 0.0;
    for (const Vec3& v : mesh.soup.vertices) worst = std::max(worst, std::abs(ellipsoid_radius(*mesh.ellipsoid, v) - 1.0));
    EXPECT_LT(worst, 1e-14) << mesh.name;
  }
}

TEST(ParseScene, OtherMeshes_HaveNoEllipsoid) {
  const Scene s = parse(R"({"meshes": [{"generator": "floor"}, {"generator": "box"}, {"generator": "torus"},
    {"generator": "nonmanifold_fan"}, {"generator": "open_box_with_fins"}, {"generator": "random_soup"}]})");
  for (const shadowcert::SceneMesh& mesh : s.meshes) EXPECT_FALSE(mesh.ellipsoid.has_value()) << mesh.name;
}

TEST(ParseScene, Lights_PointAndDirectional) {
  const Scene s = parse(R"({"lights": [[0, 10, 0, 1], [1, 1, 1, 0], [1e300, -2, 3, 1]]})");
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_FALSE(s.lights[0].directional());
  EXPECT_TRUE(s.lights[1].directional());
  EXPECT_EQ(s.lights[1].position, (std::array<double, 4>{1, 1, 1, 0}));
  EXPECT_EQ(s.lights[2].position[0], 1e300);  // huge but finite numbers are fine
}

TEST(ParseScene, Camera_AllFields) {
  const Scene s =
      parse(R"({"camera": {"eye": [1, 2, 3], "target": [0, 1, 0], "up": [0, 0, 1], "fov_y_deg": 60, "size": [640, 480]}})");
  EXPECT_EQ(s.camera.eye, (Vec3{1, 2, 3}));
  EXPECT_EQ(s.camera.target, (Vec3{0, 1, 0}));
  EXPECT_EQ(s.camera.up, (Vec3{0, 0, 1}));
  EXPECT_EQ(s.camera.fov_y_degrees, 60.0);
  EXPECT_EQ(s.camera.width, 640u);
  EXPECT_EQ(s.camera.height, 480u);
}

TEST(ParseScene, CameraNear_GivenIsKept) {
  const Scene s = parse(R"({"camera": {"eye": [0, 0, 9], "near": 0.25}})");
  EXPECT_EQ(s.camera.near_plane, 0.25);
}

// Without "near" the camera's near plane is fitted to the meshes (core/near_plane.h): a scene
// 1e6 away gets a near plane that keeps it off the cleared depth.
TEST(ParseScene, CameraWithoutNear_IsFittedToTheMeshes) {
  const Scene unit = parse(R"({"meshes": [{"generator": "uv_sphere"}]})");
  EXPECT_EQ(unit.camera.near_plane, shadowcert::kDefaultNearPlane);
  const Scene far = parse(R"({"meshes": [{"generator": "uv_sphere"}], "camera": {"eye": [0, 0, 1e6]}})");
  EXPECT_GE(far.camera.near_plane, 1e6 / shadowcert::kFarOverNear);
  EXPECT_LE(far.camera.near_plane, 0.5 * 1e6);
}

TEST(ParseScene, SyntaxError_ReportsLineOfTheError) {
  try {
    (void)parse("{\n\n  \"meshes\": [,]\n}\n");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "inline.json");
    EXPECT_EQ(e.line(), 3u);
    EXPECT_NE(std::string(e.what()).find("inline.json:3: JSON syntax error"), std::string::npos) << e.what();
  }
}

TEST(LoadScene, MeshFiles_ResolvedAgainstSceneFolderAndPlaced) {
  std::vector<std::filesystem::path> asked;
  const auto reader = [&asked](const std::filesystem::path& p) {
    asked.push_back(p);
    Soup s;
    s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    s.triangles = {{0, 1, 2}};
    return s;
  };
  const Scene s = shadowcert::load_scene(kTestScenes / "with_mesh_file.json", reader);
  ASSERT_EQ(asked.size(), 2u);
  EXPECT_EQ(asked[0], kTestScenes / "meshes/tri.obj");
  EXPECT_EQ(asked[1], std::filesystem::path("/absolute/tri.obj"));
  EXPECT_EQ(s.meshes[0].name, "meshes/tri.obj");
  EXPECT_EQ(s.meshes[1].name, "absolute");
  EXPECT_EQ(s.meshes[0].soup.vertices[1], (Vec3{1, 0, 5}));
  EXPECT_FALSE(s.meshes[0].ellipsoid.has_value());  // a file says nothing of the surface it samples
}

TEST(LoadScene, MissingMeshFile_ErrorKeepsReaderMessage) {
  const auto reader = [](const std::filesystem::path& p) -> Soup { throw InputError(p.string(), "cannot open the file"); };
  const auto scene_file = kTestScenes / "with_mesh_file.json";
  try {
    (void)shadowcert::load_scene(scene_file, reader);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), scene_file.string());
    EXPECT_NE(what.find("meshes[0].file: "), std::string::npos) << what;
    EXPECT_NE(what.find((kTestScenes / "meshes/tri.obj").string() + ": cannot open the file"), std::string::npos)
        << what;
  }
}

TEST(LoadScene, ReaderRuntimeError_WrappedWithPath) {
  const auto reader = [](const std::filesystem::path&) -> Soup { throw std::runtime_error("disk on fire"); };
  try {
    (void)shadowcert::load_scene(kTestScenes / "with_mesh_file.json", reader);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("meshes[0].file: cannot read '"), std::string::npos) << what;
    EXPECT_NE(what.find("tri.obj': disk on fire"), std::string::npos) << what;
  }
}

TEST(LoadScene, MissingSceneFile_InputErrorNamingIt) {
  const auto missing = kTestScenes / "no_such_scene.json";
  try {
    (void)shadowcert::load_scene(missing, no_mesh_files);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), missing.string());
  }
}

TEST(LoadScene, BadScenes_ErrorNamesFileKeyAndProblem) {
  struct Case {
    const char* file;
    const char* message;
    std::size_t line;  // 0: the error has no line
  };
  const std::vector<Case> cases = {
      {"unknown_key.json", "unknown key 'colour' in meshes[0]", 0},
      {"wrong_type_slices.json", "meshes[1].params.slices: expected an unsigned integer, got string", 0},
      {"syntax_error.json", "JSON syntax error at column 5", 4},
      {"unterminated.json", "JSON syntax error", 5},
      {"light_w.json", "lights[0][3]: w must be 0 (directional) or 1 (point), got 0.5", 0},
      {"directional_zero.json", "lights[1]: a directional light (w = 0) needs a non-zero direction", 0},
      {"file_and_generator.json", "meshes[0]: give either 'file' or 'generator', not both", 0},
      {"neither_file_nor_generator.json", "meshes[0]: needs a 'file' or a 'generator'", 0},
      {"camera_size_zero.json", "camera.size[1]: the image size must be at least 1 pixel", 0},
      {"camera_fov.json", "camera.fov_y_deg: must be in (0, 180) degrees, got 180", 0},
      {"camera_near.json", "camera.near: must be a finite distance > 0, got -0.5", 0},
      {"eye_equals_target.json", "camera: eye and target must be different points", 0},
      {"unknown_generator.json", "meshes[0].generator: unknown generator 'sphere'", 0},
      {"negative_integer.json", "meshes[0].params.stacks: expected an unsigned integer, got -3", 0},
      {"matrix_size.json", "meshes[0].transform.matrix: expected 16 numbers (a row-major 4x4 matrix), got 15", 0},
      {"matrix_and_translate.json", "meshes[0].transform: 'matrix' cannot be combined", 0},
      {"projective_matrix.json", "meshes[0].transform.matrix: the last row must be [0, 0, 0, 1]", 0},
      {"zero_scale.json", "meshes[0].transform: singular transform", 0},
      {"scale_string.json", "meshes[0].transform.scale: expected a number or an array of 3 numbers, got string", 0},
      {"duplicate_key.json", "duplicate key 'radius' in meshes[0].params", 0},
      {"params_with_file.json", "meshes[0].params: only generators take params", 0},
      {"generator_range.json", "meshes[0].params: uv_sphere: slices must be >= 3, got 2", 0},
      {"unknown_param.json", "unknown key 'minor_radus' in meshes[0].params (did you mean 'minor_radius'?)", 0},
      {"empty_lights.json", "lights: needs at least one light", 0},
      {"top_level_array.json", "a scene is a JSON object {...}, got array", 0},
      {"number_overflow.json", "JSON number out of range", 0},
      {"up_parallel.json", "camera: up must not be parallel to the viewing direction", 0},
      {"top_level_typo.json", "unknown key 'light' at the top level (did you mean 'lights'?)", 0},
      {"vec3_length.json", "camera.eye: expected an array of 3 numbers, got 2 elements", 0},
      {"fractional_integer.json", "meshes[0].params.subdivisions: expected an unsigned integer, got 2.5", 0},
      {"meshes_not_array.json", "meshes: expected an array, got object", 0},
      {"image_too_large.json", "camera.size[0]: expected an unsigned integer <= 16384, got 100000", 0},
      {"open_box_params.json", "unknown key 'size' in meshes[0].params (it takes no keys)", 0},
      {"overflowing_transform.json", "meshes[0].transform: maps a vertex to a non-finite coordinate", 0},
      {"description_type.json", "description: expected a string, got number", 0},
      // Found by fuzz/scene_file_fuzzer (docs/fuzzing-parsers.md): a box scaled by 1e308.
      {"default_light_overflow.json", "the default light (above the meshes, as high as they are across) overflows", 0},
      {"casts_not_boolean.json", "meshes[0].casts: expected true or false, got number", 0},
      {"silhouette_unknown.json",
       "meshes[1].silhouette: expected \"chain\", \"discrete\", \"accurate\" or \"smooth\", got \"smoth\"", 0},
      {"epsilon_not_positive.json", "meshes[0].epsilon: must be a distance > 0 (world units), got 0", 0},
  };
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kTestScenes / "bad")) files += entry.is_regular_file();
  EXPECT_EQ(files, cases.size()) << "every bad scene file has a case here";

  for (const Case& c : cases) {
    const auto file = kTestScenes / "bad" / c.file;
    try {
      (void)shadowcert::load_scene(file, no_mesh_files);
      ADD_FAILURE() << c.file << " loaded without error";
    } catch (const InputError& e) {
      const std::string prefix = file.string() + (c.line ? ":" + std::to_string(c.line) : std::string()) + ": ";
      EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
      EXPECT_NE(e.message().find(c.message), std::string::npos) << c.file << ": " << e.what();
      EXPECT_EQ(e.line(), c.line) << c.file;
    }
  }
}

TEST(BundledScenes, AllLoad_FromGeneratorsOnly) {
  std::size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kBundledScenes)) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    const Scene s = shadowcert::load_scene(entry.path(), no_mesh_files);
    EXPECT_FALSE(s.meshes.empty()) << entry.path();
    EXPECT_FALSE(s.lights.empty()) << entry.path();
  }
  EXPECT_GE(count, 3u);
}

TEST(BundledScenes, SphereGrid1m_HasAMillionTrianglesAndNoFloor) {
  const Scene s = shadowcert::load_scene(kBundledScenes / "sphere_grid_1m.json", no_mesh_files);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].soup.triangles.size(), 1'000'000u);
}

TEST(BundledScenes, CastersAndTheirShadows_InViewOnTheFloor) {
  for (const char* name : {"default.json", "sphere_over_floor.json", "fan_256_over_floor.json", "closed_casters.json",
                           "sphere_grid_1m.json"}) {
    const Scene s = shadowcert::load_scene(kBundledScenes / name, no_mesh_files);
    ASSERT_EQ(s.lights.size(), 1u);
    const auto& l = s.lights[0].position;
    ASSERT_EQ(l[3], 1.0) << name;
    const auto floor =
        std::find_if(s.meshes.begin(), s.meshes.end(), [](const shadowcert::SceneMesh& m) { return m.name == "floor"; });
    double half = 0.0;
    if (floor != s.meshes.end())
      for (const Vec3& p : floor->soup.vertices) {
        EXPECT_EQ(p[1], 0.0);
        half = std::max(half, std::abs(p[0]));
      }
    for (const auto& mesh : s.meshes) {
      if (mesh.name == "floor") continue;
      std::size_t out_of_view = 0, off_floor = 0, shadow_out_of_view = 0;
      for (const Vec3& v : mesh.soup.vertices) {
        out_of_view += !in_view(s.camera, v);
        if (floor == s.meshes.end()) continue;
        // Casters hover above the floor, below the light; their shadow lands on the floor.
        ASSERT_GT(v[1], 0.0) << name << " " << mesh.name;
        ASSERT_LT(v[1], l[1]) << name;
        const double t = l[1] / (l[1] - v[1]);
        const Vec3 shadow{l[0] + t * (v[0] - l[0]), 0.0, l[2] + t * (v[2] - l[2])};
        off_floor += std::max(std::abs(shadow[0]), std::abs(shadow[2])) >= half;
        shadow_out_of_view += !in_view(s.camera, shadow);
      }
      EXPECT_EQ(out_of_view, 0u) << name << " " << mesh.name;
      EXPECT_EQ(off_floor, 0u) << name << " " << mesh.name;
      EXPECT_EQ(shadow_out_of_view, 0u) << name << " " << mesh.name;
    }
  }
}

TEST(BundledScenes, Default_CastersAreNonManifoldSoups) {
  const Scene s = shadowcert::load_scene(kBundledScenes / "default.json", no_mesh_files);
  std::vector<std::string> names;
  for (const auto& m : s.meshes) names.push_back(m.name);
  EXPECT_EQ(names, (std::vector<std::string>{"floor", "fan", "open box", "random soup"}));
  EXPECT_EQ(s.camera.width, 1024u);
  EXPECT_EQ(s.camera.height, 768u);
  // The fan's shared edge carries all 16 blades.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_count;
  for (const auto& t : s.meshes[1].soup.triangles)
    for (int i = 0; i < 3; ++i) ++edge_count[std::minmax(t[i], t[(i + 1) % 3])];
  int widest = 0;
  for (const auto& [edge, n] : edge_count) widest = std::max(widest, n);
  EXPECT_EQ(widest, 16);
}
