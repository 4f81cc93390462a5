#include "io/detail/soup_file_text_check.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <span>

#include "io/detail/soup_file_lines.h"

namespace shadowcert::soup_file_detail {

std::size_t line_of(const std::vector<std::size_t>& lines, std::size_t k) {
  return k < lines.size() ? lines[k] : 0;
}

namespace {

std::string binary_byte_message(unsigned char byte) {
  std::array<char, 8> hex{};
  std::snprintf(hex.data(), hex.size(), "0x%02x", byte);
  return "byte " + std::string(hex.data()) + " is not text: binary data in a text format";
}

// The non-blank lines of a text, tokenized; '#' starts a comment where the format has them.
class Records {
 public:
  Records(std::string_view text, const std::string& file, bool hash_comments, std::size_t offset = 0,
          std::size_t first_line = 1)
      : lines_(text, offset, first_line), file_(file), hash_comments_(hash_comments) {}

  // Moves to the next line with a token; false at the end of the text.
  bool next() {
    while (lines_.next()) {
      std::string_view line = lines_.line();
      if (const auto byte = first_binary_byte(line)) fail_here(binary_byte_message(*byte));
      if (hash_comments_) line = line.substr(0, line.find('#'));
      split_tokens(line, tokens_);
      if (!tokens_.empty()) return true;
    }
    return false;
  }
  [[nodiscard]] const std::vector<std::string_view>& tokens() const { return tokens_; }
  // The current line as written, comment included.
  [[nodiscard]] std::string_view text() const { return lines_.line(); }
  // The current line; at the end of the text, the last line.
  [[nodiscard]] std::size_t line() const { return lines_.number(); }
  [[noreturn]] void fail_here(const std::string& message) const { fail(file_, lines_.number(), message); }

 private:
  LineReader lines_;
  const std::string& file_;
  bool hash_comments_;
  std::vector<std::string_view> tokens_;
};

void check_finite_numbers(const Records& records, std::size_t first, std::size_t last, const std::string& what) {
  for (std::size_t t = first; t < last; ++t)
    if (const auto error = finite_number_error(records.tokens()[t])) records.fail_here(what + *error);
}

std::string element_name(const std::string& kind, std::size_t k) { return kind + " " + std::to_string(k) + ": "; }

// ---------------------------------------------------------------------------------- OBJ

// Keywords CGAL's OBJ reader skips; any other keyword makes it reject the file.
bool is_skipped_obj_keyword(std::string_view keyword) {
  static constexpr std::string_view kSkipped[] = {
      "vt",     "vn",       "vp",       "bevel",  "lod",    "ctech",      "c_interp",  "usemap", "usemtl",
      "stech",  "d_interp", "mtllib",   "shadow_obj", "trace_obj", "o",   "g",         "s",      "p",
      "cstype", "deg",      "step",     "bmat",   "con",    "curv",       "curv2",     "surf",   "parm",
      "trim",   "hole",     "scrv",     "sp",     "end",    "surf_1",     "q0_1",      "q1_1",   "curv2d_1",
      "surf_2", "q0_2",     "q1_2",     "curv2d_2", "bsp",  "bzp",        "cdc",       "cdp",    "res"};
  for (const std::string_view skipped : kSkipped)
    if (skipped == keyword) return true;
  return false;
}

// First pass: positive indices may point forward, and CGAL checks them against the total.
std::size_t count_obj_vertices(std::string_view text) {
  std::size_t count = 0;
  LineReader lines(text);
  while (lines.next()) {
    const std::string_view line = lines.line();
    const std::size_t first = line.find_first_not_of(" \t\r\v\f");
    if (first != std::string_view::npos && line[first] == 'v' && first + 1 < line.size() &&
        std::string_view(" \t\r\v\f").find(line[first + 1]) != std::string_view::npos)
      ++count;
  }
  return count;
}

// The corners of an "f" line: its tokens up to a comment. CGAL ends the face at the first
// token that is not an integer, so a '#' token ends it as a comment does.
std::span<const std::string_view> obj_corners(const std::vector<std::string_view>& tokens) {
  const auto comment = std::find_if(tokens.begin() + 1, tokens.end(),
                                    [](std::string_view token) { return token.front() == '#'; });
  return {tokens.begin() + 1, comment};
}

// CGAL skips to the next space after each index, so a tab between corners hides a corner.
bool has_tab_between(std::span<const std::string_view> corners) {
  if (corners.size() < 2) return false;
  const char* begin = corners.front().data();
  const char* end = corners.back().data() + corners.back().size();
  return std::string_view(begin, static_cast<std::size_t>(end - begin)).find('\t') != std::string_view::npos;
}

class ObjChecker {
 public:
  ObjChecker(std::string_view text, const std::string& file)
      : records_(text, file, false), vertex_total_(count_obj_vertices(text)), file_(file) {}

  // '#' starts a comment only as the first character of a line's first token (CGAL takes
  // "f#" for an unknown keyword); later on a line, see obj_corners.
  RecordLines run() {
    while (records_.next()) {
      const std::string_view keyword = records_.tokens()[0];
      if (keyword.front() == '#') continue;
      if (keyword == "v") check_vertex();
      else if (keyword == "f") check_face();
      else if (!is_skipped_obj_keyword(keyword))
        records_.fail_here("unknown OBJ keyword " + quoted(keyword) + " (CGAL's OBJ reader rejects it)");
    }
    if (result_.vertex.empty()) fail(file_, 0, "no vertex ('v' line) in the file");
    if (result_.face.empty()) fail(file_, 0, "no face ('f' line) in the file");
    return std::move(result_);
  }

 private:
  void check_vertex() {
    const std::size_t found = records_.tokens().size() - 1;
    if (found < 3) records_.fail_here("'v' needs 3 coordinates, found " + std::to_string(found));
    check_finite_numbers(records_, 1, 4, "");
    result_.vertex.push_back(records_.line());
  }

  void check_face() {
    const std::span<const std::string_view> corners = obj_corners(records_.tokens());
    if (has_tab_between(corners))
      records_.fail_here("tab between face corners (CGAL's OBJ reader separates corners by spaces only)");
    for (const std::string_view corner : corners)
      if (const auto error = corner_error(corner)) records_.fail_here(*error);
    result_.face.push_back(records_.line());
  }

  // Why a corner ("v", "v/vt", "v//vn" or "v/vt/vn") names no vertex, or nothing.
  std::optional<std::string> corner_error(std::string_view corner) const {
    const std::size_t slash = corner.find('/');
    const auto index = parse_integer(corner.substr(0, slash));
    if (!index || (slash != std::string_view::npos &&
                   corner.find_first_not_of("0123456789-/", slash) != std::string_view::npos))
      return "face corner " + quoted(corner) + " is not a vertex reference";
    const auto so_far = static_cast<long long>(result_.vertex.size());
    if (*index == 0) return std::string("vertex index 0 is invalid (OBJ indices start at 1)");
    if (*index < -so_far)
      return "relative vertex index " + std::to_string(*index) + " reaches before the first vertex (" +
             std::to_string(so_far) + " vertices so far)";
    if (*index > static_cast<long long>(vertex_total_))
      return "vertex index " + std::to_string(*index) + " is out of range (the file has " +
             std::to_string(vertex_total_) + " vertices)";
    return std::nullopt;
  }

  Records records_;
  std::size_t vertex_total_;
  const std::string& file_;
  RecordLines result_;
};

// ---------------------------------------------------------------------------------- OFF

// CGAL's keywords for polygon OFF files: [ST][C][N][4]OFF (nOFF, SKEL and BINARY are not
// polygon soups in text). Each letter adds values to a vertex line, in this order:
// x y z [w], then [N] nx ny nz [nw], then [C] a color of 1, 3 or 4 values, then
// [ST] s t [w]; [C] also lets a face line end with a color.
struct OffKeyword {
  bool textures = false;     // ST
  bool colors = false;       // C
  bool normals = false;      // N
  bool homogeneous = false;  // 4: every point (and normal, texture point) has a w
};

std::optional<OffKeyword> read_off_keyword(std::string_view keyword) {
  const auto take = [&keyword](std::string_view prefix) {
    const bool found = keyword.starts_with(prefix);
    if (found) keyword.remove_prefix(prefix.size());
    return found;
  };
  OffKeyword result;
  result.textures = take("ST");
  result.colors = take("C");
  result.normals = take("N");
  result.homogeneous = take("4");
  if (keyword != "OFF") return std::nullopt;
  return result;
}

// CGAL's OFF scanner casts each value of a 3- or 4-value color to unsigned char, as an integer
// when all three are integral and times 255 otherwise (undefined behaviour outside the range),
// and looks a 1-value color up in its 149-entry color map (read out of bounds past it).
std::optional<std::string> off_color_error(std::span<const std::string_view> values) {
  constexpr double kLastColorIndex = 148;
  if (values.size() != 1 && values.size() != 3 && values.size() != 4)
    return "a color has 1, 3 or 4 values, found " + std::to_string(values.size());
  std::array<double, 3> v{};
  for (std::size_t i = 0; i < std::min<std::size_t>(values.size(), 3); ++i) (void)finite_number_error(values[i], v[i]);
  const auto integral = [](double x) { return std::floor(x) == x; };
  if (values.size() == 1) {
    if (!integral(v[0]) || v[0] < 0 || v[0] > kLastColorIndex)
      return "color index " + quoted(values[0]) + " is not an integer in [0, 148] (CGAL's color map)";
    return std::nullopt;
  }
  const double top = integral(v[0]) && integral(v[1]) && integral(v[2]) ? 255 : 1;
  for (const double x : v)
    if (x < 0 || x > top)
      return "color " + quoted(values[0]) + " " + quoted(values[1]) + " " + quoted(values[2]) +
             " is neither three integers in [0, 255] nor three numbers in [0, 1]";
  return std::nullopt;
}

class OffChecker {
 public:
  OffChecker(std::string_view text, const std::string& file) : records_(text, file, true), file_(file) {}

  RecordLines run() {
    read_header();
    for (std::size_t k = 0; k < vertex_count_; ++k) check_vertex(k);
    for (std::size_t j = 0; j < face_count_; ++j) check_face(j);
    if (records_.next())
      records_.fail_here("more records than the header's counts (vertices " + std::to_string(vertex_count_) +
                         ", faces " + std::to_string(face_count_) + ")");
    return std::move(result_);
  }

 private:
  void read_header() {
    if (!records_.next()) fail(file_, records_.line(), "no OFF header (only blank lines and comments)");
    const auto keyword = read_off_keyword(records_.tokens()[0]);
    if (!keyword)
      records_.fail_here("expected the OFF header keyword (OFF, COFF, NOFF, STCOFF, 4OFF...), found " +
                         quoted(records_.tokens()[0]));
    // CGAL finds texture coordinates after the color, whose offset only a C sets.
    if (keyword->textures && !keyword->colors)
      records_.fail_here("texture coordinates without colors (" + std::string(records_.tokens()[0]) +
                         "): CGAL's OFF reader reads them from an uninitialised offset (write STCOFF)");
    // CGAL's header scanner takes the character that ends the keyword as its delimiter, so a
    // '#' right after it does not start a comment there: "4OFF#BINARY" is binary OFF to CGAL
    // (found by the OFF fuzzer: CGAL then read text as big-endian counts).
    const std::string_view keyword_token = records_.tokens()[0];
    const auto after_keyword = static_cast<std::size_t>(keyword_token.data() - records_.text().data()) + keyword_token.size();
    if (after_keyword < records_.text().size() && records_.text()[after_keyword] == '#')
      records_.fail_here("a comment right after the keyword " + quoted(keyword_token) +
                         " (CGAL reads it as part of the header): put a space before the '#'");
    keyword_ = *keyword;
    std::size_t first_count = 1;
    if (records_.tokens().size() == 1) {
      if (!records_.next()) fail(file_, records_.line(), "unexpected end of file: no vertex and face counts");
      first_count = 0;
    } else if (records_.tokens()[1] == "BINARY") {
      records_.fail_here("binary OFF is not supported (write the file as text OFF)");
    }
    read_counts(first_count);
  }

  // CGAL reads the counts as int, and sizes its arrays by them before reading a record.
  void read_counts(std::size_t first) {
    const auto& tokens = records_.tokens();
    std::array<long long, 3> counts{};
    for (std::size_t c = 0; c < 3; ++c) {
      const auto value = first + c < tokens.size() ? parse_integer(tokens[first + c]) : std::nullopt;
      if (!value || *value < 0 || *value > std::numeric_limits<int>::max() || tokens.size() != first + 3)
        records_.fail_here("expected the counts 'vertices faces edges' (three non-negative integers)");
      counts[c] = *value;
    }
    // CGAL doubles the edge count in int arithmetic (its halfedge estimate), which overflows
    // above INT_MAX / 2; the count is otherwise unused, so 0 is what most files write.
    constexpr long long kLargestEdgeCount = std::numeric_limits<int>::max() / 2;
    if (counts[2] > kLargestEdgeCount)
      records_.fail_here("edge count " + std::to_string(counts[2]) + " is over " +
                         std::to_string(kLargestEdgeCount) + " (CGAL doubles it as an int; write 0)");
    vertex_count_ = static_cast<std::size_t>(counts[0]);
    face_count_ = static_cast<std::size_t>(counts[1]);
    // With no usable edge count CGAL estimates halfedges as int((V + F + 10) * 2.1), a
    // float-to-int overflow past this many elements; no file that large reads anyway.
    constexpr auto kLargestElementCount = static_cast<std::size_t>(std::numeric_limits<int>::max() / 2.1) - 10;
    if (vertex_count_ + face_count_ > kLargestElementCount)
      records_.fail_here("vertices + faces = " + std::to_string(vertex_count_ + face_count_) +
                         " is more than CGAL's OFF reader can count (at most " +
                         std::to_string(kLargestElementCount) + ")");
    // Also what CGAL needs: it fails on a last vertex line without '\n' when no face follows.
    if (face_count_ == 0) records_.fail_here("the header declares no face");
  }

  void next_record(const std::string& kind, std::size_t k, std::size_t count) {
    if (!records_.next())
      records_.fail_here("unexpected end of file: " + kind + " " + std::to_string(k) + " of " +
                         std::to_string(count) + " is missing");
  }

  void check_vertex(std::size_t k) {
    next_record("vertex", k, vertex_count_);
    const std::size_t point = keyword_.homogeneous ? 4 : 3;
    const std::size_t found = records_.tokens().size();
    if (found < point)
      records_.fail_here(element_name("vertex", k) + "expected " + std::to_string(point) +
                         " coordinates, found " + std::to_string(found));
    // Beyond the coordinates come colors, normals or texture coordinates: numbers too.
    check_finite_numbers(records_, 0, found, element_name("vertex", k));
    const std::size_t normal = keyword_.normals ? point : 0;
    const std::size_t texture = keyword_.textures ? point - 1 : 0;
    if (found < point + normal + texture)
      records_.fail_here(element_name("vertex", k) + "expected " + std::to_string(point + normal + texture) +
                         " numbers (the point" + (normal > 0 ? ", its normal" : "") +
                         (texture > 0 ? ", its texture coordinates" : "") + "), found " + std::to_string(found));
    if (keyword_.colors)
      check_color("vertex", k, point + normal, found - point - normal - texture, vertex_colored_);
    result_.vertex.push_back(records_.line());
  }

  // The color of record k of a C file (`kind`: vertex or face): `count` values from token
  // `first`. CGAL reads a color on every record after the first one that has one (`colored`).
  void check_color(const std::string& kind, std::size_t k, std::size_t first, std::size_t count, bool& colored) {
    if (count == 0) {
      if (colored)
        records_.fail_here(element_name(kind, k) + "no color, but an earlier " + kind +
                           " has one (CGAL would read one anyway)");
      return;
    }
    colored = true;
    if (const auto error = off_color_error(std::span(records_.tokens()).subspan(first, count)))
      records_.fail_here(element_name(kind, k) + *error);
  }

  void check_face(std::size_t j) {
    next_record("face", j, face_count_);
    const auto& tokens = records_.tokens();
    const std::string name = element_name("face", j);
    const auto corners = parse_integer(tokens[0]);
    if (!corners || *corners < 0)
      records_.fail_here(name + "vertex count " + quoted(tokens[0]) + " is not a non-negative integer");
    const auto corner_count = static_cast<std::size_t>(*corners);
    if (tokens.size() - 1 < corner_count)
      records_.fail_here(name + "declares " + std::to_string(corner_count) + " vertices but lists " +
                         std::to_string(tokens.size() - 1));
    for (std::size_t t = 1; t <= corner_count; ++t) check_index(name, tokens[t]);
    check_finite_numbers(records_, corner_count + 1, tokens.size(), name);  // a face color
    // CGAL reads a face's color only in a C file.
    if (keyword_.colors) check_color("face", j, corner_count + 1, tokens.size() - 1 - corner_count, face_colored_);
    result_.face.push_back(records_.line());
  }

  // CGAL reads an index as a double and casts it: 2.5 would be 2 and -1 undefined.
  void check_index(const std::string& name, std::string_view token) const {
    const auto index = parse_integer(token);
    if (!index) records_.fail_here(name + "vertex index " + quoted(token) + " is not an integer");
    if (*index < 0 || static_cast<unsigned long long>(*index) >= vertex_count_)
      records_.fail_here(name + "vertex index " + std::to_string(*index) + " is out of range (the file has " +
                         std::to_string(vertex_count_) + " vertices)");
  }

  Records records_;
  const std::string& file_;
  OffKeyword keyword_;
  bool vertex_colored_ = false;
  bool face_colored_ = false;
  std::size_t vertex_count_ = 0;
  std::size_t face_count_ = 0;
  RecordLines result_;
};

// ---------------------------------------------------------------------------- ASCII PLY

// The range of an integer PLY type, as [min, max].
std::array<long long, 2> ply_integer_range(PlyType type) {
  switch (type) {
    case PlyType::int8: return {INT8_MIN, INT8_MAX};
    case PlyType::uint8: return {0, UINT8_MAX};
    case PlyType::int16: return {INT16_MIN, INT16_MAX};
    case PlyType::uint16: return {0, UINT16_MAX};
    case PlyType::int32: return {INT32_MIN, INT32_MAX};
    default: return {0, UINT32_MAX};
  }
}

class PlyAsciiChecker {
 public:
  PlyAsciiChecker(std::string_view text, const PlyHeader& header, const std::string& file)
      : records_(text, file, false, header.body_offset, header.line_count + 1), header_(header) {}

  RecordLines run() {
    for (const PlyElement& element : header_.elements)
      for (std::size_t i = 0; i < element.count; ++i) check_item(element, i);
    if (records_.next())
      records_.fail_here("data after the last element (an element count in the header is too small?)");
    return std::move(result_);
  }

 private:
  void check_item(const PlyElement& element, std::size_t i) {
    if (!records_.next())
      records_.fail_here("unexpected end of file: " + element.name + " " + std::to_string(i) + " of " +
                         std::to_string(element.count) + " is missing");
    name_ = element_name(element.name, i);
    token_ = 0;
    for (const PlyProperty& property : element.properties) take_property(property);
    if (token_ < records_.tokens().size())
      records_.fail_here(name_ + "more values than the header declares");
    if (is_ply_vertex_element(element)) result_.vertex.push_back(records_.line());
    if (is_ply_face_element(element)) result_.face.push_back(records_.line());
  }

  void take_property(const PlyProperty& property) {
    if (!property.is_list) {
      take_value(property.type);
      return;
    }
    const long long length = take_value(property.count_type);
    if (length < 0) records_.fail_here(name_ + "negative list length " + std::to_string(length));
    for (long long k = 0; k < length; ++k) take_value(property.type);
  }

  // Checks the next value against its type; returns it when it is an integer.
  long long take_value(PlyType type) {
    if (token_ >= records_.tokens().size()) records_.fail_here(name_ + "fewer values than the header declares");
    const std::string_view token = records_.tokens()[token_++];
    if (is_ply_integer(type)) return take_integer(type, token);
    double value = 0;
    if (const auto error = finite_number_error(token, value)) records_.fail_here(name_ + *error);
    if (type == PlyType::float32 && std::fabs(value) > FLT_MAX)
      records_.fail_here(name_ + quoted(token) + " is out of the float range");
    return 0;
  }

  long long take_integer(PlyType type, std::string_view token) const {
    const auto value = parse_integer(token);
    const auto [min, max] = ply_integer_range(type);
    if (!value) records_.fail_here(name_ + quoted(token) + " is not an integer");
    if (*value < min || *value > max)
      records_.fail_here(name_ + quoted(token) + " is out of the range of its type [" + std::to_string(min) +
                         ", " + std::to_string(max) + "]");
    return *value;
  }

  Records records_;
  const PlyHeader& header_;
  std::string name_;
  std::size_t token_ = 0;
  RecordLines result_;
};

// ---------------------------------------------------------------------------- ASCII STL

class StlAsciiChecker {
 public:
  StlAsciiChecker(std::string_view text, const std::string& file) : records_(text, file, false) {}

  RecordLines run() {
    while (records_.next()) step(records_.tokens()[0]);
    if (state_ == State::facet_or_endsolid) records_.fail_here("unexpected end of file: missing 'endsolid'");
    if (state_ != State::solid) records_.fail_here("unexpected end of file inside a facet");
    return std::move(result_);
  }

 private:
  enum class State { solid, facet_or_endsolid, outer_loop, vertex, endloop, endfacet };

  void step(std::string_view keyword) {
    switch (state_) {
      case State::solid: return named_line(keyword == "solid", "'solid'", State::facet_or_endsolid);
      case State::facet_or_endsolid: return facet_or_endsolid(keyword);
      case State::outer_loop:
        return fixed_line(keyword == "outer" && token(1) == "loop", "'outer loop'", 2, State::vertex);
      case State::vertex: return vertex(keyword);
      case State::endloop: return endloop(keyword);
      case State::endfacet: return fixed_line(keyword == "endfacet", "'endfacet'", 1, State::facet_or_endsolid);
    }
  }

  std::string_view token(std::size_t t) const {
    return t < records_.tokens().size() ? records_.tokens()[t] : std::string_view();
  }

  void expect(bool found, const char* what, State next) {
    if (!found) records_.fail_here(std::string("expected ") + what + ", found " + quoted(token(0)));
    state_ = next;
  }

  // CGAL reads words, not lines, and acts on a keyword wherever it is: an extra word
  // ("endloop vertex") could start a vertex or end a facet. So each line has its exact shape.
  void fixed_line(bool found, const char* what, std::size_t words, State next) {
    expect(found, what, next);
    if (records_.tokens().size() != words)
      records_.fail_here(std::string("expected exactly ") + what + " on this line");
  }

  // "solid" and "endsolid" take a name, which must not hold a word CGAL acts on there.
  void named_line(bool found, const char* what, State next) {
    expect(found, what, next);
    for (std::size_t t = 1; t < records_.tokens().size(); ++t)
      if (token(t) == "solid" || token(t) == "endsolid" || token(t) == "facet")
        records_.fail_here("the name after " + quoted(token(0)) + " holds the keyword " + quoted(token(t)) +
                           ", which CGAL's STL reader would act on");
  }

  void facet_or_endsolid(std::string_view keyword) {
    if (keyword == "endsolid") return named_line(true, "'endsolid'", State::solid);
    fixed_line(keyword == "facet" && token(1) == "normal", "'facet normal nx ny nz' or 'endsolid'", 5,
               State::outer_loop);
    // CGAL skips the normal, so any number will do, even NaN.
    for (std::size_t t = 2; t < 5; ++t)
      if (!is_number(token(t))) records_.fail_here("facet normal: " + quoted(token(t)) + " is not a number");
    result_.face.push_back(records_.line());
    corners_ = 0;
  }

  void vertex(std::string_view keyword) {
    if (keyword == "endloop")
      records_.fail_here("a facet with " + std::to_string(corners_) + " vertices: STL facets are triangles");
    expect(keyword == "vertex", "'vertex x y z'", State::vertex);
    const std::size_t found = records_.tokens().size() - 1;
    if (found != 3) records_.fail_here("'vertex' needs 3 coordinates, found " + std::to_string(found));
    check_finite_numbers(records_, 1, 4, "");
    if (++corners_ == 3) state_ = State::endloop;
  }

  void endloop(std::string_view keyword) {
    if (keyword == "vertex") records_.fail_here("a fourth vertex: STL facets are triangles");
    fixed_line(keyword == "endloop", "'endloop'", 1, State::endfacet);
  }

  Records records_;
  State state_ = State::solid;
  int corners_ = 0;
  RecordLines result_;
};

}  // namespace

RecordLines check_obj_text(std::string_view text, const std::string& file) { return ObjChecker(text, file).run(); }

RecordLines check_off_text(std::string_view text, const std::string& file) { return OffChecker(text, file).run(); }

RecordLines check_ply_ascii_body(std::string_view text, const PlyHeader& header, const std::string& file) {
  return PlyAsciiChecker(text, header, file).run();
}

RecordLines check_stl_ascii_text(std::string_view text, const std::string& file) {
  return StlAsciiChecker(text, file).run();
}

}  // namespace shadowcert::soup_file_detail
