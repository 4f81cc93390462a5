#pragma once
// `shadowcert inspect MESH|SCENE [--json FILE]`: caster diagnostics (docs/definitions.md#caster-diagnostics).
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

// Registers the subcommand; when it runs, it stores its exit code in `exit_code`.
void add_inspect_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
