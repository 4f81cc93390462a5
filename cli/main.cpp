// shadowcert: certify, render and diff-compare shadow volumes on triangle soups.
// This file only composes: each subcommand lives in its own cli/*_command.cpp, and this is
// the one place that turns exceptions into exit codes (cli/exit_code.h, docs/cli.md "Exit
// codes"). Bad input and a missing environment are the user's to fix (2) and say so; anything
// else that escapes a subcommand is a bug of ours (3), reported as one, as pbrt keeps CHECK
// failures apart from ErrorExit: a precondition's std::invalid_argument or std::logic_error
// naming the function, a GL error, an invariant broken.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <new>

#include "cli/bench_command.h"
#include "cli/certify_command.h"
#include "cli/diff_command.h"
#include "cli/edges_command.h"
#include "cli/exit_code.h"
#include "cli/fuzz_command.h"
#include "cli/inspect_command.h"
#include "cli/merge_command.h"
#include "cli/render_command.h"
#include "cli/view_command.h"
#include "cli/soft_command.h"
#include "cli/track_command.h"
#include "core/input_error.h"
#include "gpu/gl_environment_error.h"
#include "gpu/gl_error.h"

int main(int argc, char** argv) {
  using namespace shadowcert::cli;
  CLI::App app{"shadowcert: exact certificates and GL renderings of shadow volumes on triangle soups"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "shadowcert 0.1.0");

  int exit_code = kExitOk;
  add_inspect_command(app, exit_code);
  add_certify_command(app, exit_code);
  add_render_command(app, exit_code);
  add_diff_command(app, exit_code);
  add_fuzz_command(app, exit_code);
  add_soft_command(app, exit_code);
  add_track_command(app, exit_code);
  add_merge_command(app, exit_code);
  add_edges_command(app, exit_code);
  add_bench_command(app, exit_code);
  add_view_command(app, exit_code);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0 in CLI11.
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  } catch (const shadowcert::InputError& e) {
    std::cerr << "shadowcert: error: " << e.what() << '\n';
    return kExitUsage;
  } catch (const shadowcert::gpu::GlEnvironmentError& e) {
    std::cerr << "shadowcert: error: " << e.what() << '\n';
    return kExitUsage;
  } catch (const std::bad_alloc&) {
    std::cerr << "shadowcert: error: out of memory\n";
    return kExitUsage;
  } catch (const shadowcert::gpu::GlError& e) {
    std::cerr << "shadowcert: internal error: " << e.what()
              << "\n(an OpenGL call failed: a bug in shadowcert or in the driver; please report it with the command)\n";
    return kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "shadowcert: internal error: " << e.what()
              << "\n(a bug in shadowcert, not in the input; please report it with the command)\n";
    return kExitInternal;
  }
  return exit_code;
}
