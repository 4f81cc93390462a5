#pragma once
// `shadowcert merge FILES... --json OUT` (docs/batch-runs.md): the --json files of the shards
// of one `fuzz` campaign (schema shadowcert-fuzz/1), or the bench.json files of the shards of
// one `bench` run (shadowcert-bench/1, docs/bench.md), merged into the file that the whole run
// writes: the same totals, checked shard by shard.
namespace CLI {
class App;
}

namespace shadowcert::cli {

// Registers the subcommand; when it runs, it stores its exit code in `exit_code`.
void add_merge_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
