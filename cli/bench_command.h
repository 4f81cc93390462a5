#pragma once
// `shadowcert bench`: every GL method at each value of its swept parameter on the scenes of a
// suite, its time and its error by the measure that fits it (docs/bench.md): bench.json,
// bench.csv, bench.md, plots (tools/bench_plots.py, matplotlib) and report.html in --out.
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

// Registers the subcommand; when it runs, it stores its exit code in `exit_code`: 1 when a run
// held robust failed (a hard error or an open volume, as diff), 0 otherwise.
void add_bench_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
