#pragma once
// `shadowcert render SCENE --method cpu`: stencil shadow volumes drawn with OpenGL 4.5 core
// through headless EGL (gpu/stencil_shadow_renderer.h, DESIGN.md §3, §5). The volume comes
// from exact/'s chain; cli/ converts it to gpu/'s ShadowVolumeGeometry (gpu/ knows nothing
// of exact/). Errors of the GL environment (no EGL, no 4.5 core) reach main as exceptions:
// exit code 2.
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

void add_render_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
