// Tests of io/soup_file.h: round trips, the same cube in every format, fan
// triangulation, the bad-file corpus (tests/data/bad/EXPECTED.tsv) and the real meshes.
#include "io/soup_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/input_error.h"
#include "support/mesh_data.h"

namespace shadowcert {
namespace {

namespace fs = std::filesystem;

const fs::path kTestData = SHADOWCERT_TEST_DATA;

// A directory of its own for each test, removed afterwards.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("shadowcert_soup_file_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(reinterpret_cast<std::uintptr_t>(this)));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  [[nodiscard]] fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

// Bitwise, so that -0.0 differs from 0.0 and a NaN would equal itself.
bool same_bits(const Vec3& a, const Vec3& b) {
  for (std::size_t i = 0; i < 3; ++i)
    if (std::bit_cast<std::uint64_t>(a[i]) != std::bit_cast<std::uint64_t>(b[i])) return false;
  return true;
}

void expect_bitwise_equal(const Soup& expected, const Soup& actual) {
  ASSERT_EQ(expected.vertices.size(), actual.vertices.size());
  for (std::size_t k = 0; k < expected.vertices.size(); ++k)
    EXPECT_TRUE(same_bits(expected.vertices[k], actual.vertices[k]))
        << "vertex " << k << ": " << expected.vertices[k][0] << " " << expected.vertices[k][1] << " "
        << expected.vertices[k][2] << " read back as " << actual.vertices[k][0] << " " << actual.vertices[k][1]
        << " " << actual.vertices[k][2];
  EXPECT_EQ(expected.triangles, actual.triangles);
}

// Doubles that a careless writer or reader loses: signed zero, digits beyond 15,
// extremes, subnormals.
Soup tricky_soup() {
  using L = std::numeric_limits<double>;
  Soup soup;
  soup.vertices = {
      {-0.0, 0.0, 0.1},
      {1e-300, 1e300, -1e300},
      {L::denorm_min(), -L::denorm_min(), 2.5e-310},
      {L::max(), L::lowest(), L::min()},
      {1.0 / 3.0, 2.0 / 3.0, -0.1},
      {123456789.123456789, 0.30000000000000004, 9007199254740993.0},
      {std::nextafter(1.0, 2.0), std::nextafter(1.0, 0.0), -4.9406564584124654e-324},
  };
  soup.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 0, 3}, {2, 2, 5}, {1, 0, 2}};
  return soup;
}

TEST(SoupFile, RoundTripEveryWritableFormat_BitwiseIdentical) {
  const ScratchDirectory scratch;
  const Soup soup = tricky_soup();
  for (const char* extension : {".off", ".obj", ".ply", ".OFF"}) {
    SCOPED_TRACE(extension);
    const fs::path file = scratch / (std::string("tricky") + extension);
    write_soup(file, soup);
    expect_bitwise_equal(soup, read_soup(file));
  }
}

TEST(SoupFile, PlyRoundTripWithNormals_NormalsBitwiseIdentical) {
  const ScratchDirectory scratch;
  Soup soup = tricky_soup();
  for (std::size_t k = 0; k < soup.vertices.size(); ++k)
    soup.normals.push_back({0.1f * static_cast<float>(k), -0.0f, std::numeric_limits<float>::denorm_min()});
  const fs::path file = scratch / "normals.ply";
  write_soup(file, soup);
  const Soup read = read_soup(file);
  expect_bitwise_equal(soup, read);
  ASSERT_EQ(read.normals.size(), soup.normals.size());
  for (std::size_t k = 0; k < soup.normals.size(); ++k)
    for (std::size_t i = 0; i < 3; ++i)
      EXPECT_EQ(std::bit_cast<std::uint32_t>(read.normals[k][i]), std::bit_cast<std::uint32_t>(soup.normals[k][i]));
}

TEST(WriteSoup, UnwritableExtension_ThrowsInvalidArgument) {
  const ScratchDirectory scratch;
  EXPECT_THROW(write_soup(scratch / "soup.stl", tricky_soup()), std::invalid_argument);
  EXPECT_THROW(write_soup(scratch / "soup", tricky_soup()), std::invalid_argument);
}

TEST(WriteSoup, InvalidSoup_ThrowsInvalidArgument) {
  const ScratchDirectory scratch;
  Soup nan_vertex = tricky_soup();
  nan_vertex.vertices[1][2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_soup(scratch / "a.off", nan_vertex), std::invalid_argument);
  Soup bad_index = tricky_soup();
  bad_index.triangles.push_back({0, 1, 7});
  EXPECT_THROW(write_soup(scratch / "b.obj", bad_index), std::invalid_argument);
  Soup bad_normals = tricky_soup();
  bad_normals.normals.resize(2);
  EXPECT_THROW(write_soup(scratch / "c.ply", bad_normals), std::invalid_argument);
}

// ------------------------------------------------------------- one cube, every format

using Corner = std::array<double, 3>;
using GeometricTriangle = std::array<Corner, 3>;

// The triangles as coordinates, each rotated (orientation kept) to start at its smallest
// corner, then sorted: equal for two soups that weld to the same geometry, whatever their
// vertex numbering (STL readers weld and renumber).
std::vector<GeometricTriangle> welded_geometry(const Soup& soup) {
  std::vector<GeometricTriangle> triangles;
  for (const Triangle& t : soup.triangles) {
    GeometricTriangle g{soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]};
    std::rotate(g.begin(), std::min_element(g.begin(), g.end()), g.end());
    triangles.push_back(g);
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

// The fan triangulation of the six quads of tests/data/good/cube_quads.obj.
const std::vector<Triangle> kCubeTriangles = {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                              {2, 3, 7}, {2, 7, 6}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};

TEST(ReadSoup, CubeInEveryFormat_SameTrianglesAndGeometry) {
  const Soup reference = read_soup(kTestData / "good" / "cube_quads.obj");
  ASSERT_EQ(reference.vertices.size(), 8U);
  EXPECT_EQ(reference.triangles, kCubeTriangles);
  const auto geometry = welded_geometry(reference);
  for (const char* name : {"cube_quads_slashes.obj", "cube_quads.off", "cube_quads_ascii.ply",
                           "cube_quads_binary_le.ply", "cube_quads_binary_be.ply", "cube_ascii.stl",
                           "cube_binary.stl", "cube_binary_solid_header.stl"}) {
    SCOPED_TRACE(name);
    const Soup soup = read_soup(kTestData / "good" / name);
    EXPECT_EQ(soup.triangles.size(), 12U);
    EXPECT_EQ(soup.vertices.size(), 8U);  // STL readers weld the 36 corners back to 8
    EXPECT_EQ(welded_geometry(soup), geometry);
    // Formats with an index list keep the file's numbering, so the triangles are the same.
    if (!std::string(name).ends_with(".stl")) {
      EXPECT_EQ(soup.triangles, kCubeTriangles);
    }
  }
}

TEST(ReadSoup, BinaryPlyWithNormals_OneNormalPerVertex) {
  const Soup soup = read_soup(kTestData / "good" / "cube_quads_binary_le.ply");
  ASSERT_EQ(soup.normals.size(), soup.vertices.size());
  for (std::size_t k = 0; k < soup.vertices.size(); ++k)
    for (std::size_t i = 0; i < 3; ++i)  // outward at every corner of the cube
      EXPECT_EQ(soup.normals[k][i] > 0, soup.vertices[k][i] > 0) << "vertex " << k;
  EXPECT_TRUE(read_soup(kTestData / "good" / "cube_quads_ascii.ply").normals.empty());
}

TEST(ReadSoup, UppercaseExtension_ReadLikeLowercase) {
  const ScratchDirectory scratch;
  fs::copy_file(kTestData / "good" / "cube_quads.obj", scratch / "CUBE.OBJ");
  EXPECT_EQ(read_soup(scratch / "CUBE.OBJ").triangles, kCubeTriangles);
}

// OFF's optional per-vertex values (N normals, C colors of 1, 3 or 4 values, ST texture
// coordinates after the color) and C face colors are read over; the points stay the file's.
TEST(ReadSoup, OffVariantsWithColorsNormalsTextures_SamePointsAndTriangle) {
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::map<std::string, std::string> files = {
      {"plain", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"indexed colors", "COFF\n3 1 0\n0 0 0 0\n1 0 0 148\n0 1 0 7\n3 0 1 2 5\n"},
      {"integer and float colors", "COFF\n3 1 0\n0 0 0 255 0 0\n1 0 0 0.5 1 0\n0 1 0 0 0 255 128\n"
                                   "3 0 1 2 0 0.25 1 1\n"},
      {"late colors", "COFF\n3 1 0\n0 0 0\n1 0 0 1 2 3\n0 1 0 4 5 6\n3 0 1 2\n"},
      {"normals and colors", "CNOFF\n3 1 0\n0 0 0 0 0 1 9 9 9\n1 0 0 0 0 1 9 9 9\n0 1 0 0 0 1 9 9 9\n3 0 1 2\n"},
      {"textures and colors", "STCOFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 2 1 0\n0 1 0 3 0 1\n3 0 1 2\n"},
      {"homogeneous", "4OFF\n3 1 0\n0 0 0 1\n2 0 0 2\n0 1 0 1\n3 0 1 2\n"},
      {"comment after the keyword", "OFF # written by hand\n3 1 0 # counts\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      // The largest edge count CGAL can double as an int; one more is in the bad corpus.
      {"largest edge count", "OFF\n3 1 1073741823\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
  };
  for (const auto& [what, text] : files) {
    SCOPED_TRACE(what);
    const Soup soup = parse_soup(text, what + ".off");
    EXPECT_EQ(soup.vertices, points);
    EXPECT_EQ(soup.triangles, (std::vector<Triangle>{{0, 1, 2}}));
  }
}

std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

TEST(ParseSoup, EveryGoodFile_SameSoupAsReadSoup) {
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(kTestData / "good")) {
    SCOPED_TRACE(entry.path().filename().string());
    const Soup from_file = read_soup(entry.path());
    const Soup from_bytes = parse_soup(file_bytes(entry.path()), entry.path().filename().string());
    expect_bitwise_equal(from_file, from_bytes);
    EXPECT_EQ(from_file.normals, from_bytes.normals);
    ++files;
  }
  EXPECT_GE(files, 9U);
}

TEST(ParseSoup, Bytes_FormatFromTheNameAndMessagesNameIt) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_EQ(parse_soup(obj, "dir/MESH.OBJ").triangles.size(), 1U);
  try {
    (void)parse_soup(obj, "mesh.off");  // OBJ bytes under an OFF name are read as OFF
    FAIL() << "not rejected";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "mesh.off");
    EXPECT_EQ(error.line(), 1U);
  }
  EXPECT_THROW((void)parse_soup(obj, "mesh.xyz"), InputError);
  EXPECT_THROW((void)parse_soup("", "mesh.obj"), InputError);
}

// z of (b - a) x (c - a): positive iff the triangle turns counter-clockwise seen from +z.
double normal_z(const Soup& soup, const Triangle& t) {
  const Vec3& a = soup.vertices[t[0]];
  const Vec3& b = soup.vertices[t[1]];
  const Vec3& c = soup.vertices[t[2]];
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

TEST(ReadSoup, PolygonsFanFromFirstVertex_OrientationKept) {
  const ScratchDirectory scratch;
  // A counter-clockwise quad and pentagon, and the quad again clockwise.
  write_text(scratch / "fans.obj",
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 3 1 0\nv 2.5 2 0\nv 1.5 2 0\nv 1.5 1 0\n"
             "f 1 2 3 4\nf 5 6 7 8 9\nf 4 3 2 1\n");
  const Soup soup = read_soup(scratch / "fans.obj");
  const std::vector<Triangle> expected = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}, {4, 7, 8}, {3, 2, 1}, {3, 1, 0}};
  EXPECT_EQ(soup.triangles, expected);
  for (std::size_t j = 0; j < 5; ++j) EXPECT_GT(normal_z(soup, soup.triangles[j]), 0) << "triangle " << j;
  for (std::size_t j = 5; j < 7; ++j) EXPECT_LT(normal_z(soup, soup.triangles[j]), 0) << "triangle " << j;
}

// ---------------------------------------------------------------------- the bad corpus

const fs::path kBad = kTestData / "bad";

// Files in tests/data/bad that are not test inputs.
const std::set<std::string> kNotInputs = {"EXPECTED.tsv", "make_binary_files.py"};

// EXPECTED.tsv: "file<TAB>substring of what()" per line; '#' lines are comments.
std::vector<std::pair<std::string, std::string>> read_manifest() {
  std::ifstream in(kBad / "EXPECTED.tsv");
  std::vector<std::pair<std::string, std::string>> entries;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t tab = line.find('\t');
    if (tab == std::string::npos) throw std::runtime_error("EXPECTED.tsv: no tab in: " + line);
    entries.emplace_back(line.substr(0, tab), line.substr(tab + 1));
  }
  return entries;
}

TEST(ReadSoup, BadCorpus_EveryFileThrowsItsExpectedMessage) {
  const auto manifest = read_manifest();
  EXPECT_GE(manifest.size(), 25U);
  for (const auto& [name, expected] : manifest) {
    SCOPED_TRACE(name);
    try {
      const Soup soup = read_soup(kBad / name);
      ADD_FAILURE() << name << " was read (" << soup.triangles.size() << " triangles) instead of rejected";
    } catch (const InputError& error) {
      const std::string what = error.what();
      EXPECT_NE(what.find(name), std::string::npos) << what;
      EXPECT_NE(what.find(expected), std::string::npos) << "expected '" << expected << "' in: " << what;
    }
  }
}

// The bytes of every bad file, given under its path, fail with read_soup's message.
TEST(ParseSoup, BadCorpus_SameMessageAsReadSoup) {
  for (const auto& [name, expected] : read_manifest()) {
    SCOPED_TRACE(name);
    std::string from_file;
    try {
      (void)read_soup(kBad / name);
    } catch (const InputError& error) {
      from_file = error.what();
    }
    try {
      (void)parse_soup(file_bytes(kBad / name), (kBad / name).string());
      ADD_FAILURE() << "parse_soup accepted it";
    } catch (const InputError& error) {
      EXPECT_EQ(error.what(), from_file);
    }
  }
}

TEST(ReadSoup, BadCorpus_EveryFileIsInTheManifest) {
  std::set<std::string> listed;
  for (const auto& entry : read_manifest()) EXPECT_TRUE(listed.insert(entry.first).second) << entry.first;
  std::set<std::string> present;
  for (const auto& entry : fs::directory_iterator(kBad))
    if (!kNotInputs.contains(entry.path().filename().string())) present.insert(entry.path().filename().string());
  EXPECT_EQ(present, listed);
}

TEST(ReadSoup, BadCorpus_CgalPrintsNothing) {
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  for (const auto& entry : read_manifest()) EXPECT_THROW((void)read_soup(kBad / entry.first), InputError);
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
}

TEST(ReadSoup, TextError_NamesFileAndLine) {
  try {
    (void)read_soup(kBad / "obj_nan_vertex.obj");
    FAIL() << "not rejected";
  } catch (const InputError& error) {
    EXPECT_EQ(fs::path(error.file()).filename(), "obj_nan_vertex.obj");
    EXPECT_EQ(error.line(), 3U);
    EXPECT_EQ(error.message(), "'nan' is not a finite number");
  }
}

TEST(ReadSoup, MissingFile_ThrowsInputError) {
  const ScratchDirectory scratch;
  EXPECT_THROW((void)read_soup(scratch / "missing.obj"), InputError);
  try {
    (void)read_soup(scratch / "missing.obj");
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("missing.obj: no such file"), std::string::npos) << error.what();
  }
}

TEST(ReadSoup, Directory_ThrowsInputError) {
  const ScratchDirectory scratch;
  fs::create_directory(scratch / "meshes.obj");
  try {
    (void)read_soup(scratch / "meshes.obj");
    FAIL() << "not rejected";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("meshes.obj: is a directory"), std::string::npos) << error.what();
  }
}

TEST(ReadSoup, EmptyPath_ThrowsInvalidArgument) { EXPECT_THROW((void)read_soup(""), std::invalid_argument); }

// ------------------------------------------------------------------------ real meshes

// Each real mesh's triangle count (fan-triangulated polygons) and, where its source states it,
// its vertex count (STL: after exact welding of bitwise-equal points). The bundled meshes
// (data/meshes/) must be there; the shared ones skip when absent unless
// SHADOWCERT_REQUIRE_SHARED_DATA=1 (support/mesh_data.h).
struct RealMeshCounts {
  const char* file;
  std::size_t triangles;
  std::size_t vertices;  // 0: not stated
};

void PrintTo(const RealMeshCounts& m, std::ostream* os) { *os << m.file; }

class RealMesh : public ::testing::TestWithParam<RealMeshCounts> {};

TEST_P(RealMesh, Read_TriangleAndVertexCountsOfItsSource) {
  const RealMeshCounts& m = GetParam();
  SHADOWCERT_REQUIRE_MESH(m.file);
  const Soup soup = read_soup(test::mesh_file(m.file));
  EXPECT_EQ(soup.triangles.size(), m.triangles);
  if (m.vertices != 0) {
    EXPECT_EQ(soup.vertices.size(), m.vertices);
  }
  if (std::string_view(m.file) == "closed_defective/horse.ply") {
    EXPECT_EQ(soup.normals.size(), soup.vertices.size());
  }
}

INSTANTIATE_TEST_SUITE_P(
    Meshes, RealMesh,
    ::testing::Values(RealMeshCounts{"closed_manifold/thingi10k_65004.stl", 1466, 731},
                      RealMeshCounts{"closed_manifold/spot.obj", 5856, 2930},
                      RealMeshCounts{"closed_manifold/thingi10k_908460.stl", 36074, 18035},
                      RealMeshCounts{"closed_manifold/nefertiti.obj", 99938, 49971},
                      RealMeshCounts{"closed_defective/horse.ply", 96966, 0},
                      RealMeshCounts{"closed_defective/beast.obj", 64618, 0},
                      RealMeshCounts{"closed_defective/manifold_self_intersectA.obj", 17160, 0},
                      RealMeshCounts{"soups/trimesh_bunny.ply", 16301, 0},
                      RealMeshCounts{"soups/trimesh_cycloidal.ply", 43368, 0},
                      RealMeshCounts{"soups/trimesh_chair_model.obj", 12756, 0},
                      RealMeshCounts{"soups/beetle.obj", 2053, 0},
                      RealMeshCounts{"soups/stanford-bunny.obj", 69451, 0},
                      RealMeshCounts{"soups/ogre.obj", 124008, 0},  // the largest: gtest's time is its read time
                      RealMeshCounts{"edge_cases/trimesh_multibody.stl", 32, 0},
                      RealMeshCounts{"edge_cases/manifold_openscad-nonmanifold-crash.obj", 1442, 0},
                      RealMeshCounts{"edge_cases/trimesh_featuretype.STL", 3476, 0},
                      RealMeshCounts{"edge_cases/trimesh_shared.STL", 24, 0},
                      RealMeshCounts{"edge_cases/teapot.obj", 6320, 0}),
    [](const ::testing::TestParamInfo<RealMeshCounts>& mesh) { return test::mesh_test_name(mesh.param.file); });

// The bundled meshes are byte-identical to their sources: the sizes data/meshes/README.md's
// checksums were taken of (a cheap guard against an editor's or git's line-ending rewrite).
TEST(BundledMeshes, EveryFile_PresentWithItsSourceSize) {
  const std::map<std::string, std::uintmax_t> sizes = {
      {"closed_manifold/thingi10k_65004.stl", 73384},
      {"closed_manifold/spot.obj", 330624},
      {"closed_defective/manifold_self_intersectA.obj", 873958},
      {"soups/trimesh_bunny.ply", 658744},
      {"soups/trimesh_chair_model.obj", 639979},
      {"soups/trimesh_cycloidal.ply", 1079764},
      {"edge_cases/trimesh_multibody.stl", 8216},
      {"edge_cases/manifold_openscad-nonmanifold-crash.obj", 72429},
      {"edge_cases/trimesh_featuretype.STL", 173884},
      {"edge_cases/trimesh_shared.STL", 1284},
  };
  ASSERT_EQ(sizes.size(), test::kBundledMeshes.size());
  for (const std::string_view mesh : test::kBundledMeshes) {
    SCOPED_TRACE(mesh);
    const fs::path file = test::bundled_mesh_dir() / std::string(mesh);
    ASSERT_TRUE(fs::is_regular_file(file));
    EXPECT_EQ(fs::file_size(file), sizes.at(std::string(mesh)));
  }
}

}  // namespace
}  // namespace shadowcert
