#pragma once
// The CLI's exit codes (only cli/ turns errors into exit codes).
namespace shadowcert::cli {

enum ExitCode : int {
  kExitOk = 0,           // everything ran and every check passed
  kExitCheckFailed = 1,  // ran, but a check that must hold did not
  kExitUsage = 2,        // usage, input or environment error: the user can fix it
  kExitInternal = 3,     // a bug in shadowcert (a broken precondition or invariant, an
                         // unexpected GL error): nothing the input did; please report it
};

}  // namespace shadowcert::cli
