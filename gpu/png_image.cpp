#include "gpu/png_image.h"

#include <png.h>

#include <cstring>
#include <stdexcept>

namespace shadowcert::gpu {
namespace {

// libpng's simplified API: it owns the setjmp error handling, so no longjmp crosses C++
// frames, and it reports failures as text in png_image::message.
void write(const std::string& path, std::uint32_t width, std::uint32_t height, png_uint_32 format, int channels,
           const std::uint8_t* pixels) {
  if (width == 0 || height == 0) throw std::runtime_error(path + ": cannot write an empty image");
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = format;
  const auto row_stride = static_cast<png_int_32>(width) * channels;
  if (!png_image_write_to_file(&image, path.c_str(), 0, pixels, row_stride, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw std::runtime_error(path + ": " + message);
  }
}

std::vector<std::uint8_t> encode(std::uint32_t width, std::uint32_t height, png_uint_32 format, int channels,
                                 const std::uint8_t* pixels) {
  if (width == 0 || height == 0) throw std::runtime_error("encode_png: cannot encode an empty image");
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = format;
  const auto row_stride = static_cast<png_int_32>(width) * channels;
  // First the size (memory == nullptr), then the bytes: libpng's documented two-call protocol.
  png_alloc_size_t bytes = 0;
  if (!png_image_write_to_memory(&image, nullptr, &bytes, 0, pixels, row_stride, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw std::runtime_error("encode_png: " + message);
  }
  std::vector<std::uint8_t> memory(bytes);
  if (!png_image_write_to_memory(&image, memory.data(), &bytes, 0, pixels, row_stride, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw std::runtime_error("encode_png: " + message);
  }
  memory.resize(bytes);
  return memory;
}

void check_size(const std::string& path, std::size_t have, std::size_t want) {
  if (have != want) throw std::invalid_argument(path + ": write_png: pixel buffer does not match width x height");
}

}  // namespace

void write_png(const std::string& path, const RgbaImage& image) {
  check_size(path, image.pixels.size(), std::size_t{image.width} * image.height * 4);
  write(path, image.width, image.height, PNG_FORMAT_RGBA, 4, image.pixels.data());
}

void write_png(const std::string& path, const GrayImage& image) {
  check_size(path, image.pixels.size(), std::size_t{image.width} * image.height);
  write(path, image.width, image.height, PNG_FORMAT_GRAY, 1, image.pixels.data());
}

std::vector<std::uint8_t> encode_png(const RgbaImage& image) {
  if (image.pixels.size() != std::size_t{image.width} * image.height * 4)
    throw std::invalid_argument("encode_png: pixel buffer does not match width x height");
  return encode(image.width, image.height, PNG_FORMAT_RGBA, 4, image.pixels.data());
}

std::vector<std::uint8_t> encode_png(const GrayImage& image) {
  if (image.pixels.size() != std::size_t{image.width} * image.height)
    throw std::invalid_argument("encode_png: pixel buffer does not match width x height");
  return encode(image.width, image.height, PNG_FORMAT_GRAY, 1, image.pixels.data());
}

}  // namespace shadowcert::gpu
