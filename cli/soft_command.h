#pragma once
// `shadowcert soft SCENE [--radius R] [--samples K] [--seed S] [--light N] [--size WxH] [--out FILE.png]
// [--regions FILE.png] [--json FILE]`: the exact soft reference of a disk light
// (pipeline/soft_reference.h, docs/smoothies.md#the-exact-soft-reference).
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

// Registers the subcommand; when it runs, it stores its exit code in `exit_code`.
void add_soft_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
