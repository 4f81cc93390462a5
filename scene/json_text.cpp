#include "scene/json_text.h"

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "core/input_error.h"

namespace shadowcert {
namespace {

// nlohmann's what() reads "[json.exception.parse_error.101] parse error at line 3, column 4:
// syntax error ..."; its line is counted differently from ours (a newline inside a string is
// blamed on the next line), so keep only the description after the position.
std::string parse_error_detail(const std::string& what) {
  const std::size_t column = what.find("column ");
  if (column != std::string::npos) {
    const std::size_t colon = what.find(": ", column);
    if (colon != std::string::npos) return what.substr(colon + 2);
  }
  const std::size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

// Tracks where the parser is (a key path like "meshes[2].params") and the keys already seen
// in each open object, through nlohmann's parser callback events.
class DuplicateKeyChecker {
 public:
  explicit DuplicateKeyChecker(const std::string& file_name) : file_name_(file_name) {}

  bool on_event(nlohmann::json::parse_event_t event, const nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
        enter_element();
        frames_.push_back(Frame{false, 0, {}, {}});
        break;
      case Event::array_start:
        enter_element();
        frames_.push_back(Frame{true, 0, {}, {}});
        break;
      case Event::object_end:
      case Event::array_end:
        frames_.pop_back();
        break;
      case Event::key: {
        Frame& top = frames_.back();
        const auto& key = parsed.get_ref<const std::string&>();
        if (!top.keys.insert(key).second) {
          const std::string where = path();
          throw InputError(file_name_, "duplicate key '" + key + "' " + (where.empty() ? "at the top level" : "in " + where));
        }
        top.key = key;
        break;
      }
      case Event::value:
        enter_element();
        break;
    }
    return true;  // keep everything: this callback only checks
  }

 private:
  struct Frame {
    bool array;
    std::size_t elements;  // arrays: elements begun so far
    std::string key;       // objects: the key being read
    std::set<std::string> keys;
  };

  void enter_element() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().elements;
  }

  // The path of the innermost open container.
  std::string path() const {
    std::string out;
    for (std::size_t i = 0; i + 1 < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      if (f.array) {
        out.append("[").append(std::to_string(f.elements - 1)).append("]");
      } else {
        if (!out.empty()) out += ".";
        out += f.key;
      }
    }
    return out;
  }

  const std::string& file_name_;
  std::vector<Frame> frames_;
};

}  // namespace

TextPosition position_of_byte(std::string_view text, std::size_t byte) {
  std::size_t index = std::min(byte > 0 ? byte - 1 : 0, text.size());
  // At the end of input, blame the last non-blank character: the file's trailing newline
  // would otherwise point at an empty line after it.
  if (index >= text.size()) {
    const std::size_t last = text.find_last_not_of(" \t\r\n");
    index = last == std::string_view::npos ? 0 : last;
  }
  const std::string_view before = text.substr(0, index);
  const auto newlines = static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t last_newline = before.rfind('\n');
  const std::size_t column = last_newline == std::string_view::npos ? index + 1 : index - last_newline;
  return {newlines + 1, column};
}

nlohmann::json parse_json_text(std::string_view text, const std::string& file_name) {
  DuplicateKeyChecker checker(file_name);
  try {
    return nlohmann::json::parse(
        text.begin(), text.end(),
        [&checker](int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
          return checker.on_event(event, parsed);
        });
  } catch (const nlohmann::json::parse_error& e) {
    const TextPosition at = position_of_byte(text, e.byte);
    throw InputError(file_name, at.line,
                     "JSON syntax error at column " + std::to_string(at.column) + ": " + parse_error_detail(e.what()));
  } catch (const nlohmann::json::out_of_range& e) {
    // A literal such as 1e400: JSON has no infinity, so nlohmann refuses it (no position given).
    throw InputError(file_name, "JSON number out of range: " + parse_error_detail(e.what()));
  }
}

}  // namespace shadowcert
