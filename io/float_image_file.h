#pragma once
// One-channel float images as PFM files (Portable Float Map, the "Pf" gray variant: a text
// header "Pf\n<width> <height>\n<scale>\n", then width x height 32-bit IEEE floats, rows from
// the BOTTOM up, little-endian when the scale is negative, big-endian when positive), read by
// ImageMagick, OpenCV, netpbm and Python's imageio. `render --light-image` and `shadowcert soft`
// write a light image this way, lossless, with -1 where no light is defined
// (cli/light_image_output.h; docs/smoothies.md).
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace shadowcert {

struct FloatImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> pixels;  // row-major, row 0 at the TOP (gpu/image.h's convention)
};

// Writes `pixels` (width x height, row 0 at the top) as a little-endian PFM, creating parent
// folders. Throws std::invalid_argument("write_pfm: ...") when pixels.size() != width * height
// or a side is 0, InputError naming the file when it cannot be written.
void write_pfm(const std::filesystem::path& file, std::uint32_t width, std::uint32_t height,
               std::span<const float> pixels);

// Reads a "Pf" PFM of either byte order: parse_pfm of the file's bytes. Throws InputError
// naming the file when it cannot be opened, and what parse_pfm throws.
[[nodiscard]] FloatImage read_pfm(const std::filesystem::path& file);

// The image in `bytes`, a whole PFM file. Throws InputError naming `file_name` when the header
// is not a gray PFM with sides in [1, 65536] and a finite nonzero scale, or the data is shorter
// or longer than width x height floats.
[[nodiscard]] FloatImage parse_pfm(std::string_view bytes, const std::string& file_name);

}  // namespace shadowcert
