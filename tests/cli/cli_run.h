#pragma once
// What the tests of cli/ share (tests/cli/): they run the real `shadowcert` executable, as users
// run it, named by the SHADOWCERT_CLI definition that tests/CMakeLists.txt gives every test of
// tests/cli/ (and only those: this header needs it). Its exit code and its output, stdout and
// stderr together; the JSON and text files it writes; a folder of each test's own under the
// system's temporary folder; and whether a command that renders found no EGL device. Test code
// only.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <string_view>

#include "support/test_requirements.h"

namespace shadowcert::cli_test {

struct RunResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// `shadowcert ARGUMENTS 2>&1` through the shell; exit_code is -1 when it did not exit normally.
inline RunResult run_cli(const std::string& arguments) {
  const std::string command = std::string(SHADOWCERT_CLI) + " " + arguments + " 2>&1";
  RunResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) result.output += buffer;
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// The temporary folder of one test program, shadowcert_TESTNAME_PID, created if need be (and
// left as it is when it exists).
inline std::filesystem::path temp_dir(std::string_view test_name) {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("shadowcert_" + std::string(test_name) + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

// The folder NAME of temp_dir(test_name), emptied: what an earlier run left there is removed.
inline std::filesystem::path empty_temp_dir(std::string_view test_name, std::string_view name) {
  const std::filesystem::path dir = temp_dir(test_name) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline nlohmann::json read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The commands that render need EGL (a GPU's or Mesa's llvmpipe); without an EGL device they
// exit 2 naming EGL. Tests use SHADOWCERT_SKIP_WITHOUT_GL below, never this alone.
inline bool render_unavailable(const RunResult& r) {
  return r.exit_code == 2 && r.output.find("EGL") != std::string::npos;
}

}  // namespace shadowcert::cli_test

// In a test body (or SetUp), after a command that renders: when it found no EGL device, skip
// the test on a machine with no GL at all, or fail it under SHADOWCERT_REQUIRE_GL=1 (CI), so a
// broken EGL cannot turn the CLI's tests into skips (support/test_requirements.h).
#define SHADOWCERT_SKIP_WITHOUT_GL(run)                                                         \
  do {                                                                                          \
    const ::shadowcert::cli_test::RunResult& shadowcert_run = (run);                            \
    if (::shadowcert::cli_test::render_unavailable(shadowcert_run)) {                           \
      if (::shadowcert::test::gl_required()) FAIL() << "SHADOWCERT_REQUIRE_GL=1 but: " << shadowcert_run.output; \
      GTEST_SKIP() << shadowcert_run.output;                                                    \
    }                                                                                           \
  } while (false)
