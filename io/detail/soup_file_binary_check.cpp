#include "io/detail/soup_file_binary_check.h"

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "io/detail/soup_file_lines.h"

namespace shadowcert::soup_file_detail {

namespace {

constexpr std::size_t kStlHeaderBytes = 84;  // 80 bytes of header, then the uint32 count
constexpr std::size_t kStlTriangleBytes = 50;  // normal, 3 vertices (12 floats), 2 attribute bytes

// Bytes `offset`..`offset + size` as an unsigned integer of the given byte order.
std::uint64_t read_unsigned(std::string_view data, std::size_t offset, std::size_t size, bool little_endian) {
  std::uint64_t value = 0;
  for (std::size_t b = 0; b < size; ++b) {
    const std::size_t byte = little_endian ? size - 1 - b : b;
    value = (value << 8) | static_cast<unsigned char>(data[offset + byte]);
  }
  return value;
}

std::uint64_t stl_triangle_count(std::string_view data) { return read_unsigned(data, 80, 4, true); }

// Why a file that is not ASCII is no binary STL either.
std::string stl_size_problem(std::string_view data) {
  if (data.size() < kStlHeaderBytes)
    return "too short: " + std::to_string(data.size()) + " bytes, but its header alone has 84";
  const std::uint64_t triangles = stl_triangle_count(data);
  return "size mismatch: the header declares " + std::to_string(triangles) + " triangles, which take 84 + 50 * " +
         std::to_string(triangles) + " = " + std::to_string(kStlHeaderBytes + kStlTriangleBytes * triangles) +
         " bytes, but the file has " + std::to_string(data.size());
}

bool starts_with_solid(std::string_view data) {
  const std::size_t first = data.find_first_not_of(" \t\r\n\v\f");
  if (first == std::string_view::npos || !data.substr(first).starts_with("solid")) return false;
  const std::size_t after = first + 5;
  return after == data.size() || std::string_view(" \t\r\n\v\f").find(data[after]) != std::string_view::npos;
}

bool is_signed(PlyType type) {
  return type == PlyType::int8 || type == PlyType::int16 || type == PlyType::int32;
}

// Reads a list length of an integer PLY type, sign included.
long long read_ply_integer(std::string_view data, std::size_t offset, PlyType type, bool little_endian) {
  const std::size_t size = ply_type_size(type);
  const std::uint64_t raw = read_unsigned(data, offset, size, little_endian);
  const std::uint64_t sign_bit = std::uint64_t{1} << (8 * size - 1);
  // Two's complement: with the top bit set, the value is raw - 2^bits (counts have at most 32).
  if (is_signed(type) && (raw & sign_bit) != 0)
    return static_cast<long long>(raw) - static_cast<long long>(2 * sign_bit);
  return static_cast<long long>(raw);
}

class PlyLayoutWalker {
 public:
  PlyLayoutWalker(std::string_view data, const PlyHeader& header, const std::string& file)
      : data_(data),
        header_(header),
        file_(file),
        little_endian_(header.format == PlyFormat::binary_little_endian),
        offset_(header.body_offset) {}

  void run() {
    for (const PlyElement& element : header_.elements) walk(element);
    if (offset_ != data_.size())
      fail(file_, 0,
           std::to_string(data_.size() - offset_) +
               " bytes after the last element (an element count in the header is too small?)");
  }

 private:
  void walk(const PlyElement& element) {
    if (has_list(element)) {
      for (std::size_t i = 0; i < element.count; ++i) walk_item(element, i);
      return;
    }
    // Fixed-size items: one bound check for the whole element.
    const std::size_t item_bytes = fixed_item_bytes(element);
    if (item_bytes == 0) return;  // the header allows no property only with count 0
    const std::size_t left = data_.size() - offset_;
    if (element.count > left / item_bytes) truncated(element, left / item_bytes);
    offset_ += element.count * item_bytes;
  }

  void walk_item(const PlyElement& element, std::size_t i) {
    for (const PlyProperty& property : element.properties) {
      if (!property.is_list) {
        skip(ply_type_size(property.type), element, i);
        continue;
      }
      const std::size_t count_bytes = ply_type_size(property.count_type);
      skip(count_bytes, element, i);
      const long long length = read_ply_integer(data_, offset_ - count_bytes, property.count_type, little_endian_);
      if (length < 0)
        fail(file_, 0, element.name + " " + std::to_string(i) + ": negative list length " + std::to_string(length));
      const std::size_t item_bytes = ply_type_size(property.type);
      if (static_cast<std::uint64_t>(length) > (data_.size() - offset_) / item_bytes) truncated(element, i);
      offset_ += static_cast<std::size_t>(length) * item_bytes;
    }
  }

  void skip(std::size_t bytes, const PlyElement& element, std::size_t i) {
    if (data_.size() - offset_ < bytes) truncated(element, i);
    offset_ += bytes;
  }

  [[noreturn]] void truncated(const PlyElement& element, std::size_t i) const {
    fail(file_, 0,
         "truncated binary PLY: the file ends inside " + element.name + " " + std::to_string(i) + " (of " +
             std::to_string(element.count) + ")");
  }

  static bool has_list(const PlyElement& element) {
    for (const PlyProperty& property : element.properties)
      if (property.is_list) return true;
    return false;
  }

  static std::size_t fixed_item_bytes(const PlyElement& element) {
    std::size_t bytes = 0;
    for (const PlyProperty& property : element.properties) bytes += ply_type_size(property.type);
    return bytes;
  }

  std::string_view data_;
  const PlyHeader& header_;
  const std::string& file_;
  bool little_endian_;
  std::size_t offset_;
};

}  // namespace

StlEncoding classify_stl(std::string_view data, const std::string& file) {
  if (data.size() >= kStlHeaderBytes &&
      kStlHeaderBytes + kStlTriangleBytes * stl_triangle_count(data) == data.size())
    return StlEncoding::binary;
  if (!starts_with_solid(data)) fail(file, 0, "binary STL " + stl_size_problem(data));
  if (first_binary_byte(data))
    fail(file, 0,
         "starts with 'solid' like an ASCII STL but holds binary bytes, and is no binary STL either: " +
             stl_size_problem(data));
  return StlEncoding::ascii;
}

void check_binary_stl_coordinates(std::string_view data, const std::string& file) {
  const std::uint64_t triangles = stl_triangle_count(data);
  for (std::uint64_t t = 0; t < triangles; ++t) {
    const std::size_t vertices = kStlHeaderBytes + kStlTriangleBytes * t + 12;  // after the normal
    for (std::size_t c = 0; c < 9; ++c) {
      const auto bits = static_cast<std::uint32_t>(read_unsigned(data, vertices + 4 * c, 4, true));
      const float value = std::bit_cast<float>(bits);
      if (!std::isfinite(value))
        fail(file, 0,
             "triangle " + std::to_string(t) + ": vertex " + std::to_string(c / 3) + " has a non-finite coordinate (" +
                 std::to_string(value) + ")");
    }
  }
}

void check_binary_ply_layout(std::string_view data, const PlyHeader& header, const std::string& file) {
  PlyLayoutWalker(data, header, file).run();
}

}  // namespace shadowcert::soup_file_detail
