#pragma once
// The token reader of io/'s own line formats (point files, volume files): fields separated by
// spaces, tabs or a stray '\r' (a file written on Windows). Private to io/.
#include <algorithm>
#include <string_view>

namespace shadowcert::io_detail {

// The next token of `rest` and `rest` moved past it; empty at the end of the line.
[[nodiscard]] inline std::string_view next_token(std::string_view& rest) {
  const auto begin = rest.find_first_not_of(" \t\r");
  if (begin == std::string_view::npos) {
    rest = {};
    return {};
  }
  rest.remove_prefix(begin);
  const auto end = std::min(rest.find_first_of(" \t\r"), rest.size());
  const std::string_view token = rest.substr(0, end);
  rest.remove_prefix(end);
  return token;
}

}  // namespace shadowcert::io_detail
