// exact/captured_volume.h: the .vol file round-trips floats bit for bit, rejects bad files
// naming file:line, and its closure certificate sees a missing face.
#include "exact/captured_volume.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/input_error.h"

namespace shadowcert {
namespace {

namespace fs = std::filesystem;

fs::path temp_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("shadowcert_captured_volume_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path file = temp_file(name);
  std::ofstream(file) << text;
  return file;
}

// A tetrahedron with outward faces: the smallest closed volume; vertex 3 is at infinity so
// w = 0 vertices take part like any other.
CapturedVolume tetrahedron() {
  CapturedVolume v;
  v.vertices = {{0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {0.25f, 0.25f, 1, 0}};
  v.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  return v;
}

std::string read_error(const fs::path& file) {
  try {
    (void)read_captured_volume(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(CapturedVolume, RoundTrip_IsBitwiseIncludingNegativeZeroAndInfinity) {
  CapturedVolume v;
  const float tiny = std::numeric_limits<float>::denorm_min();
  v.vertices = {{0.1f, -0.0f, 1e-30f, 1.0f},
                {3.4028235e38f, tiny, -7.123456789f, 0.0f},
                {1.0f / 3.0f, -2.0f / 3.0f, 12345.678f, 1.0f}};
  v.triangles = {{0, 1, 2}};
  const fs::path file = temp_file("round_trip.vol");
  write_captured_volume(file, v, "two\nlines");
  const CapturedVolume back = read_captured_volume(file);
  ASSERT_EQ(back.vertices.size(), 3u);
  ASSERT_EQ(back.triangles, v.triangles);
  for (std::size_t i = 0; i < 3; ++i)
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(std::bit_cast<std::uint32_t>(back.vertices[i][k]), std::bit_cast<std::uint32_t>(v.vertices[i][k]))
          << i << "," << k;
}

TEST(CapturedVolume, Write_WeldsBitwiseEqualVerticesAndSignedZeros) {
  CapturedVolume v;
  v.vertices = {{0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {-0.0f, 0, -0.0f, 1}, {1, 0, 0, 0}};
  v.triangles = {{0, 1, 2}, {3, 2, 4}};
  const fs::path file = temp_file("weld.vol");
  write_captured_volume(file, v);
  const CapturedVolume back = read_captured_volume(file);
  EXPECT_EQ(back.vertices.size(), 4u);  // (-0, 0, -0, 1) is (0, 0, 0, 1); (1, 0, 0, 0) stays apart (w)
  ASSERT_EQ(back.triangles.size(), 2u);
  EXPECT_EQ(back.triangles[1][0], 0u);
}

TEST(CapturedVolume, PolygonFace_IsReadAsAFan) {
  const fs::path file = write_text("quad.vol", "# a quad\nv 0 0 0 1\nv 1 0 0 1\nv 1 1 0 1\nv 0 1 0 0\nf 1 2 3 4\n");
  const CapturedVolume v = read_captured_volume(file);
  ASSERT_EQ(v.triangles.size(), 2u);
  EXPECT_EQ(v.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

TEST(CapturedVolume, BadFiles_NameFileAndLine) {
  struct Case {
    const char* name;
    const char* text;
    const char* expected;  // a part of what()
  };
  const Case cases[] = {
      {"w.vol", "v 0 0 0 1\nv 1 2 3 0.5\n", "w.vol:2: w must be"},
      {"nan.vol", "# c\nv nan 0 0 1\n", "nan.vol:2: coordinates must be finite"},
      {"inf.vol", "v 1e39 0 0 1\n", "inf.vol:1: "},
      {"word.vol", "v 1 x 0 1\n", "word.vol:1: 'x' is not a float"},
      {"short.vol", "\nv 1 0 1\n", "short.vol:2: a vertex needs four numbers"},
      {"long.vol", "v 1 0 1 1 1\n", "long.vol:1: a vertex has exactly four"},
      {"range.vol", "v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 4\n", "range.vol:4: vertex index 4"},
      {"zero.vol", "v 0 0 0 1\nf 0 1 1\n", "zero.vol:2: '0' is not a 1-based"},
      {"two.vol", "v 0 0 0 1\nv 1 0 0 1\nf 1 2\n", "two.vol:3: a face needs at least 3"},
      {"tag.vol", "v 0 0 0 1\nvn 0 0 1\n", "tag.vol:2: unknown record 'vn'"},
  };
  for (const Case& c : cases) {
    const std::string message = read_error(write_text(c.name, c.text));
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
  }
  EXPECT_NE(read_error(temp_file("missing.vol")).find("missing.vol: cannot open"), std::string::npos);
}

TEST(CapturedVolume, ParseText_SameAsReadingTheFile) {
  const std::string text = "# c\nv 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nv 0.25 0.25 1 0\nf 1 3 2\nf 1 2 4 3\n";
  const fs::path file = write_text("parse.vol", text);
  const CapturedVolume from_file = read_captured_volume(file);
  const CapturedVolume from_text = parse_captured_volume(text, file.string());
  EXPECT_EQ(from_text.vertices, from_file.vertices);
  EXPECT_EQ(from_text.triangles, from_file.triangles);
  EXPECT_EQ(from_text.triangles.size(), 3u);
  const std::string bad = "v 0 0 0 1\nf 1 1 2\n";
  const fs::path bad_file = write_text("parse_bad.vol", bad);
  try {
    (void)parse_captured_volume(bad, bad_file.string());
    FAIL() << "not rejected";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), read_error(bad_file));
    EXPECT_EQ(e.line(), 2u);
  }
}

TEST(CapturedVolume, ClosedTetrahedron_IsClosed) {
  const CapturedClosure result = certify_captured_closure(tetrahedron());
  EXPECT_TRUE(result.certificate.closed);
  EXPECT_TRUE(result.certificate.unbalanced.empty());
}

TEST(CapturedVolume, TetrahedronMissingAFace_HasThreeUnbalancedEdges) {
  CapturedVolume v = tetrahedron();
  v.triangles.pop_back();
  const CapturedClosure result = certify_captured_closure(v);
  EXPECT_FALSE(result.certificate.closed);
  EXPECT_EQ(result.certificate.unbalanced.size(), 3u);
}

TEST(CapturedVolume, TriangleSoupOfAClosedVolume_IsClosedAfterWelding) {
  // As the GPU reads back: three fresh vertices per triangle, some zeros negative.
  CapturedVolume soup;
  const CapturedVolume tet = tetrahedron();
  for (const auto& t : tet.triangles) {
    const auto first = static_cast<std::uint32_t>(soup.vertices.size());
    for (std::uint32_t id : t) {
      auto p = tet.vertices[id];
      if (first % 2 == 1)
        for (float& x : p)
          if (x == 0.0f) x = -0.0f;
      soup.vertices.push_back(p);
    }
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  const CapturedClosure result = certify_captured_closure(soup);
  EXPECT_TRUE(result.certificate.closed);
  EXPECT_EQ(result.welded.vertices.size(), 4u);
}

}  // namespace
}  // namespace shadowcert
