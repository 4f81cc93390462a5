#pragma once
// `shadowcert render SCENE --method cpu|cs|gs|ts|pertri|shadowmap`: shadows drawn with OpenGL
// 4.5 core through headless EGL (docs/definitions.md#counts, docs/definitions.md#pixel-protocol) by gpu/shadow_method_renderer.h. This file
// only composes: it loads the scene, builds cpu's exact chains with exact/ (converted by
// exact/chain_mesh.h: gpu/ knows nothing of exact/), and writes the images, the captured
// volume, the JSON and, with --timing, the GPU stage times. Errors of the GL environment (no
// EGL, no 4.5 core, no timer queries) reach main as exceptions: exit code 2.
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

void add_render_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
