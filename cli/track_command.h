#pragma once
// `shadowcert track MESH|SCENE [--frames N] [--variant LIST] [--orbit-radius R] [--orbit-height H]
// [--orbit-turns T | --path FILE] [--per-frame] [--json FILE]`: silhouette tracking (Chen and
// Tsai, §2.1) along a light path, each frame held to the exact silhouette
// (pipeline/silhouette_tracking.h; docs/smoothies.md, "Silhouette tracking").
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

// Registers the subcommand; when it runs, it stores its exit code in `exit_code`.
void add_track_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
