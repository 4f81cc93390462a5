#pragma once
// Typed reading of a parsed JSON value that knows its key path ("meshes[1].params.slices") and
// file, so that every wrong type, range or unknown key becomes an InputError naming both.
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/soup.h"

namespace shadowcert {

class JsonField {
 public:
  // The root of a document; `file_name` must outlive every field derived from it.
  JsonField(const nlohmann::json& value, const std::string& file_name) : value_(&value), file_(&file_name) {}

  [[nodiscard]] const nlohmann::json& json() const { return *value_; }
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const std::string& file_name() const { return *file_; }

  // Throws InputError(file, "<path>: <message>") (or "<message>" alone at the root).
  [[noreturn]] void fail(const std::string& message) const;

  // Objects. require_keys_within fails unless this is an object whose keys are all in `allowed`.
  void require_keys_within(std::initializer_list<std::string_view> allowed) const;
  [[nodiscard]] std::optional<JsonField> member(std::string_view key) const;  // object required

  // Arrays.
  [[nodiscard]] std::size_t array_size() const;  // array required
  [[nodiscard]] JsonField element(std::size_t index) const;

  // Scalars and small vectors.
  [[nodiscard]] double number() const;  // any JSON number (always finite)
  [[nodiscard]] std::uint64_t unsigned_integer(std::uint64_t max) const;  // integral, in [0, max]
  [[nodiscard]] std::string string() const;
  [[nodiscard]] bool boolean() const;  // true or false, never a number or a string
  [[nodiscard]] Vec3 vec3() const;  // exactly three numbers

 private:
  JsonField(const nlohmann::json& value, const std::string& file_name, std::string path)
      : value_(&value), file_(&file_name), path_(std::move(path)) {}
  [[noreturn]] void fail_type(const char* expected) const;

  const nlohmann::json* value_;
  const std::string* file_;
  std::string path_;
};

// Optional members with a default, the common case of the scene format.
[[nodiscard]] double number_or(const JsonField& object, std::string_view key, double fallback);
[[nodiscard]] std::uint64_t unsigned_or(const JsonField& object, std::string_view key, std::uint64_t max,
                                        std::uint64_t fallback);
[[nodiscard]] Vec3 vec3_or(const JsonField& object, std::string_view key, const Vec3& fallback);

// Levenshtein distance, for "did you mean" hints on unknown keys and names.
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);
// The closest candidate within distance 2 (and less than the word's length), else empty.
[[nodiscard]] std::string closest_name(std::string_view word, const std::vector<std::string_view>& candidates);

}  // namespace shadowcert
