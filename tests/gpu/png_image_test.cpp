// Needs no GL context: lives here because png_image is part of shadowcert_gpu.
#include "gpu/png_image.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace shadowcert::gpu {
namespace {

// Reads with libpng itself (not gpu/) into the given 8-bit format.
std::vector<std::uint8_t> read_png(const std::string& path, png_uint_32 format, png_uint_32& width,
                                   png_uint_32& height) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) throw std::runtime_error(image.message);
  image.format = format;
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) throw std::runtime_error(image.message);
  width = image.width;
  height = image.height;
  return pixels;
}

std::string temp_path(const char* name) {
  return (std::filesystem::temp_directory_path() / (std::string("shadowcert_") + name)).string();
}

TEST(PngImage, RgbaRoundTripsBitwise) {
  RgbaImage image(7, 5);  // odd width: rows are not 4-byte aligned
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<std::uint8_t>(i * 37 + 11);
  const std::string path = temp_path("rgba.png");
  write_png(path, image);
  png_uint_32 w = 0, h = 0;
  EXPECT_EQ(read_png(path, PNG_FORMAT_RGBA, w, h), image.pixels);
  EXPECT_EQ(w, 7u);
  EXPECT_EQ(h, 5u);
  std::filesystem::remove(path);
}

TEST(PngImage, GrayStencilCountsRoundTripBitwise) {
  GrayImage counts(256, 3);  // every byte value 0..255 appears: counts are stored losslessly
  for (std::uint32_t row = 0; row < 3; ++row)
    for (std::uint32_t x = 0; x < 256; ++x) *counts.at(x, row) = static_cast<std::uint8_t>(x + row);
  const std::string path = temp_path("gray.png");
  write_png(path, counts);
  png_uint_32 w = 0, h = 0;
  EXPECT_EQ(read_png(path, PNG_FORMAT_GRAY, w, h), counts.pixels);
  EXPECT_EQ(w, 256u);
  EXPECT_EQ(h, 3u);
  std::filesystem::remove(path);
}

// encode_png gives the bytes write_png writes: same file, read back bitwise.
TEST(PngImage, EncodedInMemory_IsTheFilesBytes) {
  RgbaImage image(5, 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<std::uint8_t>(i * 13 + 1);
  const std::string path = temp_path("encoded.png");
  write_png(path, image);
  const std::uintmax_t size = std::filesystem::file_size(path);
  std::vector<std::uint8_t> file(size);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(std::fread(file.data(), 1, file.size(), f), file.size());
  std::fclose(f);
  EXPECT_EQ(encode_png(image), file);
  GrayImage gray(4, 4);
  gray.pixels[5] = 200;
  EXPECT_GT(encode_png(gray).size(), 8u);
  EXPECT_THROW((void)encode_png(RgbaImage()), std::runtime_error);
  std::filesystem::remove(path);
}

TEST(PngImage, ErrorsNameTheFile) {
  const std::string path = "/nonexistent-dir/shadowcert/out.png";
  try {
    write_png(path, GrayImage(2, 2));
    FAIL() << "expected an error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace shadowcert::gpu
