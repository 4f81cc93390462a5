#include "scene/json_field.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "core/input_error.h"

namespace shadowcert {

void JsonField::fail(const std::string& message) const {
  throw InputError(*file_, path_.empty() ? message : path_ + ": " + message);
}

void JsonField::fail_type(const char* expected) const {
  fail(std::string("expected ") + expected + ", got " + value_->type_name());
}

void JsonField::require_keys_within(std::initializer_list<std::string_view> allowed) const {
  if (!value_->is_object()) fail_type("an object");
  for (const auto& item : value_->items()) {
    const std::string& key = item.key();
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string message = "unknown key '" + key + "' " + (path_.empty() ? "at the top level" : "in " + path_);
    const std::string hint = closest_name(key, {allowed.begin(), allowed.end()});
    if (!hint.empty()) {
      message += " (did you mean '" + hint + "'?)";
    } else if (allowed.size() > 0) {
      message += " (allowed:";
      for (std::string_view a : allowed) message.append(" ").append(a);
      message += ")";
    } else {
      message += " (it takes no keys)";
    }
    throw InputError(*file_, message);
  }
}

std::optional<JsonField> JsonField::member(std::string_view key) const {
  if (!value_->is_object()) fail_type("an object");
  const auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return JsonField(*it, *file_, path_.empty() ? std::string(key) : path_ + "." + std::string(key));
}

std::size_t JsonField::array_size() const {
  if (!value_->is_array()) fail_type("an array");
  return value_->size();
}

JsonField JsonField::element(std::size_t index) const {
  return JsonField((*value_)[index], *file_, path_ + "[" + std::to_string(index) + "]");
}

double JsonField::number() const {
  if (!value_->is_number()) fail_type("a number");
  return value_->get<double>();
}

std::uint64_t JsonField::unsigned_integer(std::uint64_t max) const {
  const nlohmann::json& v = *value_;
  if (!v.is_number()) fail_type("an unsigned integer");
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u > max) fail("expected an unsigned integer <= " + std::to_string(max) + ", got " + std::to_string(u));
    return u;
  }
  if (v.is_number_integer()) fail("expected an unsigned integer, got " + v.dump());  // negative
  // A float literal is accepted when it is a whole number in range: "triangles": 1e6 reads well.
  const auto d = v.get<double>();
  if (!(d >= 0.0) || std::floor(d) != d) fail("expected an unsigned integer, got " + v.dump());
  if (d > static_cast<double>(max))
    fail("expected an unsigned integer <= " + std::to_string(max) + ", got " + v.dump());
  return static_cast<std::uint64_t>(d);
}

std::string JsonField::string() const {
  if (!value_->is_string()) fail_type("a string");
  return value_->get<std::string>();
}

bool JsonField::boolean() const {
  if (!value_->is_boolean()) fail_type("true or false");
  return value_->get<bool>();
}

Vec3 JsonField::vec3() const {
  if (!value_->is_array() || value_->size() != 3) {
    if (value_->is_array()) fail("expected an array of 3 numbers, got " + std::to_string(value_->size()) + " elements");
    fail_type("an array of 3 numbers");
  }
  return {element(0).number(), element(1).number(), element(2).number()};
}

double number_or(const JsonField& object, std::string_view key, double fallback) {
  const auto field = object.member(key);
  return field ? field->number() : fallback;
}

std::uint64_t unsigned_or(const JsonField& object, std::string_view key, std::uint64_t max, std::uint64_t fallback) {
  const auto field = object.member(key);
  return field ? field->unsigned_integer(max) : fallback;
}

Vec3 vec3_or(const JsonField& object, std::string_view key, const Vec3& fallback) {
  const auto field = object.member(key);
  return field ? field->vec3() : fallback;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitute});
    }
  }
  return row[b.size()];
}

std::string closest_name(std::string_view word, const std::vector<std::string_view>& candidates) {
  std::string best;
  std::size_t best_distance = std::min<std::size_t>(3, word.size());
  for (std::string_view c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(c);
    }
  }
  return best;
}

}  // namespace shadowcert
