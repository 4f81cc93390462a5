#include "io/detail/soup_file_lines.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <system_error>

// GCC 12 reports -Wrestrict inside the std::string concatenations of InputError::compose
// once fail() inlines it: a known false positive (GCC bug 105329). The pragma must precede
// the header, where the warning is located.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif
#include "core/input_error.h"

namespace shadowcert::soup_file_detail {

LineReader::LineReader(std::string_view text, std::size_t offset, std::size_t first_number)
    : text_(text), offset_(offset), number_(first_number - 1) {}

bool LineReader::next() {
  if (offset_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', offset_);
  if (end == std::string_view::npos) end = text_.size();
  line_ = text_.substr(offset_, end - offset_);
  offset_ = end < text_.size() ? end + 1 : end;  // a last line without '\n' ends the text
  ++number_;
  return true;
}

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Streams accept a leading '+', std::from_chars does not: drop it (but not a second sign).
std::string_view without_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
  return token;
}

}  // namespace

void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

std::optional<unsigned char> first_binary_byte(std::string_view text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && !is_space(c) && c != '\n') || byte == 0x7f) return byte;
  }
  return std::nullopt;
}

std::optional<std::string> finite_number_error(std::string_view token) {
  double value = 0;
  return finite_number_error(token, value);
}

std::optional<std::string> finite_number_error(std::string_view token, double& value) {
  const std::string_view digits = without_plus(token);
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value,
                                            std::chars_format::general);
  if (end != digits.data() + digits.size() || error == std::errc::invalid_argument)
    return quoted(token) + " is not a number";
  // from_chars calls both overflow and underflow out of range; the streams CGAL reads with
  // turn underflow into 0 and reject only overflow, so tell them apart with strtod.
  if (error == std::errc::result_out_of_range) value = std::strtod(std::string(digits).c_str(), nullptr);
  if (!std::isfinite(value)) return quoted(token) + " is not a finite number";
  return std::nullopt;
}

bool is_number(std::string_view token) {
  const std::string_view digits = without_plus(token);
  double value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value,
                                            std::chars_format::general);
  return end == digits.data() + digits.size() && error != std::errc::invalid_argument;
}

std::optional<long long> parse_integer(std::string_view token) {
  const std::string_view digits = without_plus(token);
  long long value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  return value;
}

std::string quoted(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string text(1, '\'');
  text += token.substr(0, kMaxShown);
  text += token.size() <= kMaxShown ? "'" : "...'";
  return text;
}

void fail(const std::string& file, std::size_t line, const std::string& message) {
  throw InputError(file, line, message);
}

}  // namespace shadowcert::soup_file_detail
