#pragma once
// The result of every predicate: a sign. Callers switch on it and handle zero explicitly
// (docs/definitions.md#orientation: a zero is a degenerate configuration with its own meaning, never rounded away).
#include <cstdint>

namespace shadowcert {

enum class Sign : std::int8_t { negative = -1, zero = 0, positive = 1 };

[[nodiscard]] constexpr int to_int(Sign s) { return static_cast<int>(s); }
[[nodiscard]] constexpr Sign operator-(Sign s) { return static_cast<Sign>(-static_cast<int>(s)); }
[[nodiscard]] constexpr Sign operator*(Sign a, Sign b) {
  return static_cast<Sign>(static_cast<int>(a) * static_cast<int>(b));
}
template <typename T>
[[nodiscard]] constexpr Sign sign_of(T x) {
  return x > T(0) ? Sign::positive : (x < T(0) ? Sign::negative : Sign::zero);
}

}  // namespace shadowcert
