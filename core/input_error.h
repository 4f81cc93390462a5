#pragma once
// The one exception type for bad input (a malformed file, a wrong scene key, NaN...).
// It names the file and, where the format has lines, the 1-based line, so that
// what() reads "FILE:LINE: message" (or "FILE: message" without a line).
// Misuse of an API throws std::invalid_argument naming the function instead.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace shadowcert {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::size_t line, const std::string& message)
      : std::runtime_error(compose(file, line, message)),
        file_(std::move(file)),
        line_(line),
        message_(message) {}
  InputError(std::string file, const std::string& message) : InputError(std::move(file), 0, message) {}

  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] std::size_t line() const { return line_; }  // 0 when the format has no lines
  [[nodiscard]] const std::string& message() const { return message_; }

 private:
  static std::string compose(const std::string& file, std::size_t line, const std::string& message) {
    std::string s = file;
    if (line > 0) s.append(":").append(std::to_string(line));
    return s.append(": ").append(message);
  }
  std::string file_;
  std::size_t line_;
  std::string message_;
};

}  // namespace shadowcert
