#include "io/float_image_file.h"

#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "core/input_error.h"
#include "io/output_file.h"

namespace shadowcert {
namespace {

// The largest side read: the largest image anything writes (core/camera.h's kMaxImageSide is
// 16384); a header beyond it is malformed, not an allocation to attempt.
constexpr std::uint64_t kMaxPfmSide = 1u << 16;

std::uint32_t byte_swapped(std::uint32_t x) {
  return (x >> 24) | ((x >> 8) & 0xFF00u) | ((x << 8) & 0xFF0000u) | (x << 24);
}

}  // namespace

void write_pfm(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
               std::span<const float> pixels) {
  if (width == 0 || height == 0) throw std::invalid_argument("write_pfm: empty image");
  if (pixels.size() != std::size_t{width} * height)
    throw std::invalid_argument("write_pfm: " + std::to_string(pixels.size()) + " values for " + std::to_string(width) +
                                "x" + std::to_string(height));
  create_parent_directories(file);
  std::ofstream out(file, std::ios::binary);
  if (!out) throw InputError(file.string(), "cannot open for writing");
  out << "Pf\n" << width << ' ' << height << "\n-1.0\n";
  std::vector<std::uint32_t> row(width);
  for (std::uint32_t r = height; r-- > 0;) {  // bottom row first
    for (std::uint32_t i = 0; i < width; ++i) {
      std::uint32_t bits = std::bit_cast<std::uint32_t>(pixels[std::size_t{r} * width + i]);
      if constexpr (std::endian::native == std::endian::big) bits = byte_swapped(bits);
      row[i] = bits;
    }
    out.write(reinterpret_cast<const char*>(row.data()), static_cast<std::streamsize>(row.size() * 4));
  }
  if (!out) throw InputError(file.string(), "write failed");
}

FloatImage read_pfm(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "cannot open");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file.string(), "read failed");
  return parse_pfm(bytes, file.string());
}

FloatImage parse_pfm(std::string_view bytes, const std::string& file_name) {
  const auto bad = [&](const std::string& what) { return InputError(file_name, "not a gray PFM image: " + what); };
  // The header: three whitespace-separated tokens after the magic, then one whitespace byte.
  std::size_t at = 0;
  const auto token = [&]() {
    while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
    const std::size_t start = at;
    while (at < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
    return std::string(bytes.substr(start, at - start));
  };
  const auto side = [&](const std::string& text) -> std::uint64_t {
    if (text.empty() || text.size() > 6 || text.find_first_not_of("0123456789") != std::string::npos) return 0;
    const std::uint64_t value = std::stoull(text);
    return value <= kMaxPfmSide ? value : 0;
  };
  if (token() != "Pf") throw bad("it does not start with \"Pf\"");
  const std::uint64_t width = side(token()), height = side(token());
  if (width == 0 || height == 0) throw bad("no width and height in [1, " + std::to_string(kMaxPfmSide) + "]");
  const std::string scale_text = token();
  double scale = 0.0;
  const char* const scale_end = scale_text.data() + scale_text.size();
  if (const auto [end, error] = std::from_chars(scale_text.data(), scale_end, scale);
      scale_text.empty() || error != std::errc() || end != scale_end || !std::isfinite(scale) || scale == 0.0)
    throw bad("no finite nonzero scale");
  if (at >= bytes.size()) throw bad("no data");
  ++at;  // the one whitespace byte after the scale
  const bool little = scale < 0.0;
  const std::string_view data = bytes.substr(at);
  const std::size_t count = static_cast<std::size_t>(width * height);
  if (data.size() != 4 * count)
    throw bad(std::to_string(data.size()) + " bytes of data for " + std::to_string(width) + "x" +
              std::to_string(height) + " floats (" + std::to_string(4 * count) + ")");
  FloatImage image;
  image.width = static_cast<std::uint32_t>(width);
  image.height = static_cast<std::uint32_t>(height);
  image.pixels.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, data.data() + 4 * k, 4);
    if ((std::endian::native == std::endian::little) != little) bits = byte_swapped(bits);
    const std::size_t row = image.height - 1 - k / image.width;  // bottom row first in the file
    image.pixels[row * image.width + k % image.width] = std::bit_cast<float>(bits);
  }
  return image;
}

}  // namespace shadowcert
