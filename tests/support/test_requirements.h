#pragma once
// What a test does when its environment lacks something (test code only): the switches that
// turn a skip into a failure. CI sets both (.ci/run), so a broken EGL or missing test data
// turns CI red instead of quietly green (docs/development.md#tests-that-cannot-skip).
//   SHADOWCERT_REQUIRE_GL=1           no EGL device fails every test that renders
//                                     (support/gl_test_support.h, tests/cli/cli_run.h)
//   SHADOWCERT_REQUIRE_SHARED_DATA=1  a missing shared (developer) mesh fails its test
//                                     (support/mesh_data.h; the bundled meshes always must be there)
#include <cstdlib>
#include <string_view>

namespace shadowcert::test {

// Whether the environment variable NAME is "1".
inline bool environment_flag(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr && std::string_view(value) == "1";
}

inline bool gl_required() { return environment_flag("SHADOWCERT_REQUIRE_GL"); }
inline bool shared_data_required() { return environment_flag("SHADOWCERT_REQUIRE_SHARED_DATA"); }

}  // namespace shadowcert::test
