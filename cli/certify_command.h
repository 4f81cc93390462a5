#pragma once
// `shadowcert certify MESH|SCENE`: exact multiplicities, closed shadow-volume chains and their
// certificates (closure and occluder counts, docs/definitions.md#certificates) for each requested method.
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

// Registers the subcommand; when it runs, it stores its exit code in `exit_code`:
// 1 when the exact method fails a certificate (a bug), 0 otherwise (float methods failing is
// a finding that is reported, not an error).
void add_certify_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
