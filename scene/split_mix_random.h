#pragma once
// SplitMix64 (Steele, Lea and Flood 2014, "Fast splittable pseudorandom number generators";
// the generator java.util.SplittableRandom uses): 64 bits of state, a Weyl sequence through a
// strong finaliser. The random-soup campaign seeds one per (seed, case, purpose) stream, millions of
// times: std::mt19937_64 costs a 312-word initialisation per stream, this one a few adds.
// Every draw below is fully specified (no std::*_distribution), so a case is the same with any
// standard library.
#include <cstdint>
#include <initializer_list>

namespace shadowcert {

// The finaliser alone: a bijective mix of 64 bits.
[[nodiscard]] constexpr std::uint64_t split_mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

class SplitMixRandom {
 public:
  // A stream keyed by several numbers (seed, index, purpose...): each is mixed in turn.
  constexpr SplitMixRandom(std::initializer_list<std::uint64_t> keys) {
    for (std::uint64_t k : keys) state_ = split_mix(state_ ^ k);
  }

  constexpr std::uint64_t operator()() {
    state_ += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  constexpr double unit() { return static_cast<double>((*this)() >> 11) * 0x1.0p-53; }  // [0, 1), exact
  constexpr double symmetric() { return 2.0 * unit() - 1.0; }                           // [-1, 1), exact
  // Below n (n >= 1); the modulo bias is below n / 2^64, nothing for the small n used here.
  constexpr std::uint64_t below(std::uint64_t n) { return (*this)() % n; }

 private:
  std::uint64_t state_ = 0;
};

}  // namespace shadowcert
