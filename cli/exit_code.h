#pragma once
// The CLI's exit codes (only cli/ turns errors into exit codes).
namespace shadowcert::cli {

enum ExitCode : int {
  kExitOk = 0,           // everything ran and every check passed
  kExitCheckFailed = 1,  // ran, but a check that must hold did not
  kExitUsage = 2,        // usage, input or environment error
};

}  // namespace shadowcert::cli
