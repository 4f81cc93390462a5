#pragma once
// `shadowcert fuzz`: the random-soup campaign (docs/campaign.md). Seeded soups and adversarial
// lights, every method run certified (closure and counts), failures shrunk to reproducers that
// `shadowcert certify` replays, a summary and an optional JSON report.
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

// Registers the subcommand; when it runs, it stores its exit code in `exit_code`: 1 when a run
// that must not fail (exact, peciva, refedge) failed on some case, 0 otherwise (kim's failures
// are findings, reported). `--gl` is a usage error until the GL methods are wired in (exit 2).
void add_fuzz_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
