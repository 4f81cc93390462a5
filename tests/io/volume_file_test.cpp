// io/volume_file.h: the .vol file round-trips floats bit for bit, welds what it writes, and
// rejects bad files naming file:line.
#include "io/volume_file.h"

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
  const fs::path dir = fs::temp_directory_path() / ("shadowcert_volume_file_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path file = temp_file(name);
  std::ofstream(file) << text;
  return file;
}

std::string read_error(const fs::path& file) {
  try {
    (void)read_volume_file(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(VolumeFile, RoundTrip_IsBitwiseIncludingNegativeZeroAndInfinity) {
  HomogeneousMesh v;
  const float tiny = std::numeric_limits<float>::denorm_min();
  v.vertices = {{0.1f, -0.0f, 1e-30f, 1.0f},
                {3.4028235e38f, tiny, -7.123456789f, 0.0f},
                {1.0f / 3.0f, -2.0f / 3.0f, 12345.678f, 1.0f}};
  v.triangles = {{0, 1, 2}};
  const fs::path file = temp_file("round_trip.vol");
  write_volume_file(file, v, "two\nlines");
  const HomogeneousMesh back = read_volume_file(file);
  ASSERT_EQ(back.vertices.size(), 3u);
  ASSERT_EQ(back.triangles, v.triangles);
  for (std::size_t i = 0; i < 3; ++i)
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(std::bit_cast<std::uint32_t>(back.vertices[i][k]), std::bit_cast<std::uint32_t>(v.vertices[i][k]))
          << i << "," << k;
}

TEST(VolumeFile, Write_WeldsBitwiseEqualVerticesAndSignedZeros) {
  HomogeneousMesh v;
  v.vertices = {{0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {-0.0f, 0, -0.0f, 1}, {1, 0, 0, 0}};
  v.triangles = {{0, 1, 2}, {3, 2, 4}};
  const fs::path file = temp_file("weld.vol");
  write_volume_file(file, v);
  const HomogeneousMesh back = read_volume_file(file);
  EXPECT_EQ(back.vertices.size(), 4u);  // (-0, 0, -0, 1) is (0, 0, 0, 1); (1, 0, 0, 0) stays apart (w)
  ASSERT_EQ(back.triangles.size(), 2u);
  EXPECT_EQ(back.triangles[1][0], 0u);
}

TEST(VolumeFile, PolygonFace_IsReadAsAFan) {
  const fs::path file = write_text("quad.vol", "# a quad\nv 0 0 0 1\nv 1 0 0 1\nv 1 1 0 1\nv 0 1 0 0\nf 1 2 3 4\n");
  const HomogeneousMesh v = read_volume_file(file);
  ASSERT_EQ(v.triangles.size(), 2u);
  EXPECT_EQ(v.triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

TEST(VolumeFile, BadFiles_NameFileAndLine) {
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

TEST(VolumeFile, ParseText_SameAsReadingTheFile) {
  const std::string text = "# c\nv 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nv 0.25 0.25 1 0\nf 1 3 2\nf 1 2 4 3\n";
  const fs::path file = write_text("parse.vol", text);
  const HomogeneousMesh from_file = read_volume_file(file);
  const HomogeneousMesh from_text = parse_volume_file(text, file.string());
  EXPECT_EQ(from_text.vertices, from_file.vertices);
  EXPECT_EQ(from_text.triangles, from_file.triangles);
  EXPECT_EQ(from_text.triangles.size(), 3u);
  const std::string bad = "v 0 0 0 1\nf 1 1 2\n";
  const fs::path bad_file = write_text("parse_bad.vol", bad);
  try {
    (void)parse_volume_file(bad, bad_file.string());
    FAIL() << "not rejected";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), read_error(bad_file));
    EXPECT_EQ(e.line(), 2u);
  }
}

}  // namespace
}  // namespace shadowcert
