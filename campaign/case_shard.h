#pragma once
// One shard of a campaign (docs/batch-runs.md): the cases i of 0 .. cases-1 with
// i % count == index. Case i is a function of (seed, i) alone (campaign/random_soup.h), so the
// shards of a campaign certify between them exactly the cases of the whole run, each once,
// whatever machine runs each; their tallies add up to the whole run's. The command line's
// `--shard K/N` is {K - 1, N}: the same split as `bench --shard` (index % N == K - 1).
#include <cstdint>

namespace shadowcert {

struct CaseShard {
  std::uint64_t index = 0;  // 0-based, < count
  std::uint64_t count = 1;  // >= 1; {0, 1} is the whole campaign
};

// Whether the shard is one: count >= 1 and index < count.
[[nodiscard]] constexpr bool valid_case_shard(CaseShard shard) { return shard.count >= 1 && shard.index < shard.count; }

// How many of the cases 0 .. cases-1 the shard holds (0 when cases <= index).
[[nodiscard]] constexpr std::uint64_t shard_case_count(std::uint64_t cases, CaseShard shard) {
  return cases > shard.index ? (cases - shard.index - 1) / shard.count + 1 : 0;
}

// The campaign's index of the shard's j-th case (j < shard_case_count).
[[nodiscard]] constexpr std::uint64_t shard_case_index(CaseShard shard, std::uint64_t j) {
  return shard.index + j * shard.count;
}

}  // namespace shadowcert
