#pragma once
// Strict JSON text parsing for scene files: syntax errors become InputErrors with the 1-based
// line (nlohmann reports a byte offset), and a key repeated in one object is an error naming
// its key path, since nlohmann would silently keep the last value.
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace shadowcert {

// Throws InputError(file_name, line, ...) on a syntax error, InputError(file_name, ...) on a
// duplicate key or a number beyond the range of a double.
[[nodiscard]] nlohmann::json parse_json_text(std::string_view text, const std::string& file_name);

// The 1-based line and column of the byte that nlohmann's parse_error::byte designates
// (1-based, the last byte read; may be one past the end at end of input).
struct TextPosition {
  std::size_t line;
  std::size_t column;
};
[[nodiscard]] TextPosition position_of_byte(std::string_view text, std::size_t byte);

}  // namespace shadowcert
