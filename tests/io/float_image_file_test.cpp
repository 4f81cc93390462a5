// PFM light images (io/float_image_file.h): a round trip keeps every float bit for bit with
// row 0 at the top, a big-endian file reads the same, and malformed files are InputErrors
// naming the file.
#include "io/float_image_file.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#include "core/input_error.h"

namespace {

using namespace shadowcert;
namespace fs = std::filesystem;

fs::path temp_file(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("shadowcert_pfm_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary);
  out << bytes;
}

TEST(FloatImageFile, RoundTrip_KeepsEveryValueAndTheRowOrder) {
  const std::vector<float> pixels{-1.0f, 0.0f, 0.25f, 1.0f, 1.0f / 3.0f, -0.0f};  // 3 x 2, row 0 first
  const fs::path file = temp_file("round_trip.pfm");
  write_pfm(file, 3, 2, pixels);
  const FloatImage image = read_pfm(file);
  EXPECT_EQ(image.width, 3u);
  EXPECT_EQ(image.height, 2u);
  ASSERT_EQ(image.pixels.size(), pixels.size());
  for (std::size_t p = 0; p < pixels.size(); ++p)
    EXPECT_EQ(std::bit_cast<std::uint32_t>(image.pixels[p]), std::bit_cast<std::uint32_t>(pixels[p])) << p;
  // The file holds the bottom row first, little-endian.
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string header = "Pf\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 24);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  float first = 0.0f;
  std::memcpy(&first, bytes.data() + header.size(), 4);
  EXPECT_EQ(first, 1.0f);  // pixel (0, 1)
}

TEST(FloatImageFile, BigEndianFile_ReadsTheSame) {
  std::string bytes = "Pf\n2 1\n1.0\n";
  for (float v : {0.5f, -1.0f}) {
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
    for (int shift : {24, 16, 8, 0}) bytes.push_back(static_cast<char>((bits >> shift) & 0xFF));
  }
  const fs::path file = temp_file("big_endian.pfm");
  write_bytes(file, bytes);
  const FloatImage image = read_pfm(file);
  EXPECT_EQ(image.pixels, (std::vector<float>{0.5f, -1.0f}));
}

TEST(FloatImageFile, MalformedFiles_ThrowInputErrorNamingTheFile) {
  const auto expect_input_error = [](const std::string& name, const std::string& bytes) {
    const fs::path file = temp_file(name);
    write_bytes(file, bytes);
    try {
      (void)read_pfm(file);
      ADD_FAILURE() << "no error for " << name;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file.string());
    }
  };
  expect_input_error("colour.pfm", "PF\n1 1\n-1.0\n" + std::string(12, '\0'));
  expect_input_error("no_size.pfm", "Pf\nx 1\n-1.0\n");
  expect_input_error("zero_scale.pfm", "Pf\n1 1\n0\n" + std::string(4, '\0'));
  expect_input_error("short.pfm", "Pf\n2 2\n-1.0\n" + std::string(12, '\0'));
  expect_input_error("long.pfm", "Pf\n1 1\n-1.0\n" + std::string(8, '\0'));
  EXPECT_THROW((void)read_pfm(temp_file("missing.pfm")), InputError);
  EXPECT_THROW(write_pfm(temp_file("bad.pfm"), 2, 2, std::vector<float>(3)), std::invalid_argument);
}

}  // namespace
