#pragma once
// `shadowcert diff SCENE [--methods LIST] [--stencil zfail|zpass|auto] [--size WxH] [--out DIR]
//                        [--json FILE] [--report FILE.html]`
// What users run to certify a renderer (docs/definitions.md#pixel-protocol, docs/diff.md): the exact image
// (reference/exact_image.h) against every chosen GL method (gpu/shadow_method_renderer.h), light
// by light, pixel by pixel (reference/pixel_comparison.h), plus the exact closure of each volume
// method's captured volume (io/volume_file.h). Exit 1 when a robust method (cpu, cs,
// gs, ts, pertri) has a hard error or an open volume; the shadow map is a baseline whose
// errors are reported, never a failure.
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

// Registers the subcommand; when it runs, it stores its exit code in `exit_code`.
void add_diff_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
