#pragma once
// Lines, tokens and numbers of text mesh files, for the checks that run before CGAL reads
// (private to io/soup_file.cpp). Nothing here builds a mesh: it only says where and
// why a line does not fit its format.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace shadowcert::soup_file_detail {

// Walks the '\n'-separated lines of a text, numbering them from 1 like an editor does.
class LineReader {
 public:
  // Starts at byte `offset`, which begins line `first_number`.
  explicit LineReader(std::string_view text, std::size_t offset = 0, std::size_t first_number = 1);

  // Moves to the next line; false at the end of the text.
  bool next();
  [[nodiscard]] std::string_view line() const { return line_; }
  // Number of the current line; before the first next(), the number of the line before.
  [[nodiscard]] std::size_t number() const { return number_; }
  // Offset of the byte after the current line's '\n' (the text's size if it has none).
  [[nodiscard]] std::size_t end_offset() const { return offset_; }

 private:
  std::string_view text_;
  std::string_view line_;
  std::size_t offset_;
  std::size_t number_;
};

// Splits at the whitespace that C++ streams skip (space, \t, \r, \v, \f); reuses `tokens`.
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens);

// The first byte that no text file contains (a control character other than whitespace),
// which is how a binary file given a text extension shows itself.
[[nodiscard]] std::optional<unsigned char> first_binary_byte(std::string_view text);

// Why `token` is not a finite double as the streams CGAL reads with accept it (optional
// '+', decimal or exponent form, underflow to zero allowed), or nothing if it is one.
[[nodiscard]] std::optional<std::string> finite_number_error(std::string_view token);
// The same, also giving the value when there is no error.
[[nodiscard]] std::optional<std::string> finite_number_error(std::string_view token, double& value);

// Whether `token` is a number at all, NaN and infinity included.
[[nodiscard]] bool is_number(std::string_view token);

// A decimal integer with an optional sign, the whole token; nothing otherwise.
[[nodiscard]] std::optional<long long> parse_integer(std::string_view token);

// "'token'" quoted for a message, shortened when a line of junk would swamp it.
[[nodiscard]] std::string quoted(std::string_view token);

// Throws InputError(file, line, message); line 0 means the file as a whole.
[[noreturn]] void fail(const std::string& file, std::size_t line, const std::string& message);

}  // namespace shadowcert::soup_file_detail
