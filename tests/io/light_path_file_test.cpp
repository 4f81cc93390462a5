// io/light_path_file.h: `shadowcert track --path` files, read from a file or from text, with
// every bad line an InputError naming the file and line.
#include "io/light_path_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/input_error.h"

namespace shadowcert {
namespace {

namespace fs = std::filesystem;

std::string parse_error(const std::string& text, const std::string& name) {
  try {
    (void)parse_light_path_file(text, name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(LightPathFile, CommentsBlankLinesTabsAndCrlf_LightsInOrder) {
  const std::vector<Light> lights = parse_light_path_file("# path\n1 2 3 1\n\n  -4.5\t5e-3 6 0\r\n", "l.txt");
  ASSERT_EQ(lights.size(), 2u);
  EXPECT_EQ(lights[0].position, (std::array<double, 4>{1, 2, 3, 1}));
  EXPECT_EQ(lights[1].position, (std::array<double, 4>{-4.5, 5e-3, 6, 0}));
}

TEST(LightPathFile, BadLines_NameFileAndLine) {
  struct Case {
    const char* text;
    const char* expected;  // a part of what()
  };
  const Case cases[] = {
      {"1 2 3\n", "l.txt:1: expected four values"},
      {"# c\n1 x 3 1\n", "l.txt:2: not a number: 'x'"},
      {"1 2 3 1\n1 2 inf 1\n", "l.txt:2: value is not finite"},
      {"1 2 3 1 5\n", "l.txt:1: more than four values"},
      {"1 2 3 0.5\n", "l.txt:1: w must be 1 (point light) or 0 (directional light)"},
      {"\n\n0 0 0 0\n", "l.txt:3: a directional light needs a nonzero direction"},
      {"# nothing\n\n", "l.txt: no light in the path"},
  };
  for (const Case& c : cases) EXPECT_NE(parse_error(c.text, "l.txt").find(c.expected), std::string::npos) << c.text;
}

TEST(LightPathFile, Files_ReadOrNamedInTheError) {
  const fs::path dir = fs::temp_directory_path() / ("shadowcert_light_path_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "path.txt";
  std::ofstream(file) << "0 5 0 1\n0 1 0 0\n";
  EXPECT_EQ(read_light_path_file(file).size(), 2u);
  try {
    (void)read_light_path_file(dir / "missing.txt");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir / "missing.txt").string());
  }
  EXPECT_THROW((void)read_light_path_file(dir), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shadowcert
