#pragma once
// `shadowcert view SCENE`: a GLFW window that draws the scene's shadows live through the host
// layer (gpu/host_shadow_volumes.h, gpu/viewer_frame.h): orbit and zoom the camera, drag the
// light, switch the method and the stencil mode, overlay the exact image's verdicts (computed
// in a background thread), the frame time in the title. `--screenshot FILE --frames N` draws N
// frames, writes the last one as PNG and exits (for tests and machines without a display:
// `xvfb-run -a shadowcert view ...`); at the scene's size it equals `shadowcert render --out`
// pixel for pixel. No display, or no GL 4.5 core through it: exit 2 with GLFW's message.
#include <CLI/CLI.hpp>

namespace shadowcert::cli {

void add_view_command(CLI::App& app, int& exit_code);

}  // namespace shadowcert::cli
