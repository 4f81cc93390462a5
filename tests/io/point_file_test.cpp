// io/point_file.h: certify's --points files, read from a file or from text, with every
// bad line an InputError naming the file and line.
#include "io/point_file.h"

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

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("shadowcert_point_file_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string parse_error(const std::string& text, const std::string& name) {
  try {
    (void)parse_point_file(text, name);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PointFile, CommentsBlankLinesTabsAndCrlf_PointsInOrder) {
  const std::vector<Vec3> points = parse_point_file("# sample points\n1 2 3\n\n  -4.5\t5e-3 6\r\n7 8 9", "p.txt");
  EXPECT_EQ(points, (std::vector<Vec3>{{1, 2, 3}, {-4.5, 5e-3, 6}, {7, 8, 9}}));
  EXPECT_TRUE(parse_point_file("", "empty.txt").empty());
}

TEST(PointFile, BadLines_NameFileAndLine) {
  struct Case {
    const char* text;
    const char* expected;  // a part of what()
  };
  const Case cases[] = {
      {"1 2\n", "p.txt:1: expected three coordinates"},
      {"# c\n1 x 3\n", "p.txt:2: not a number: 'x'"},
      {"1 2 3\n1 2 inf\n", "p.txt:2: coordinate is not finite"},
      {"1 2 3 4\n", "p.txt:1: more than three values on the line"},
      {"\n\n1e999 0 0\n", "p.txt:3: not a number: '1e999'"},
  };
  for (const Case& c : cases) {
    const std::string message = parse_error(c.text, "p.txt");
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.text << ": " << message;
  }
}

TEST(PointFile, File_SameAsItsText) {
  const std::string text = "0.1 0.2 0.3\n# c\n-1 -2 -3\n";
  const fs::path file = temp_dir() / "points.txt";
  std::ofstream(file) << text;
  EXPECT_EQ(read_point_file(file), parse_point_file(text, file.string()));
  EXPECT_THROW((void)read_point_file(temp_dir() / "missing.txt"), InputError);
  EXPECT_THROW((void)read_point_file(temp_dir()), InputError);
}

}  // namespace
}  // namespace shadowcert
