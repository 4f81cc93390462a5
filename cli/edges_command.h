#pragma once
// `shadowcert edges SCENE [--filter diagonal|c1|sobel] [--threshold T] [--style edges|gooch|toon]
// [--shadows METHOD] [--crease-angle DEG] [--out IMG.png] [--edge-map FILE.png] [--json FILE]
// [--timing]`: edge maps (Nienhaus & Doellner 2003; docs/edge-maps.md) by gpu/edge_map.h, a
// style over them by gpu/edge_style.h, with the shadows of any `render` method
// (gpu/shadow_method_renderer.h) when asked. This file only composes: it loads the scene,
// prepares the shadow method's inputs as render does, and writes the images, the JSON and the
// pass times. Errors of the GL environment reach main as exceptions: exit code 2.
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

void add_edges_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
