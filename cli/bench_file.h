#pragma once
// bench.json as an input (docs/bench.md#benchjson). `bench --from` and `merge` read files that
// may come from another machine, an older shadowcert, an interrupted run or a hand edit, so
// check_bench_file checks the whole document before anything reads it: every key that the
// outputs (cli/bench_outputs.h), the plots (tools/bench_plots.py) and the merge read, with its
// type, and that the file agrees with itself (the scenes are the shard's, in index order; the
// totals are the scenes' sums; every run id is one of "methods"). A file that fails is an
// InputError naming the file and the key path (cli/json_field.h): exit 2. After it the readers
// may index the document freely.
//
// Keys added since the first files of the schema are optional, with the meaning those files had:
// "complete" (absent: true, a file written once at the end), a scene's "failure" (absent: none)
// and "totals.failed_scenes" (absent: 0).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

namespace shadowcert::cli {

constexpr const char* kBenchSchema = "shadowcert-bench/1";

struct BenchFileStatus {
  bool complete = true;            // false: written while the run went on (it was interrupted)
  std::uint64_t scenes = 0;        // scenes the file holds
  std::uint64_t shard_scenes = 0;  // scenes of its shard: `scenes` when complete
};

// Throws InputError(file, ...) naming the first key that is missing, of the wrong type or
// inconsistent.
BenchFileStatus check_bench_file(const nlohmann::json& bench, const std::string& file);

// The number of indices i in [0, scene_count) with i % n == k - 1 (shard K of N).
[[nodiscard]] constexpr std::uint64_t shard_scene_count(std::uint64_t scene_count, std::uint64_t k, std::uint64_t n) {
  return scene_count < k ? 0 : (scene_count - k) / n + 1;
}

}  // namespace shadowcert::cli
