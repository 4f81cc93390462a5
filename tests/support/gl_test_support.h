#pragma once
// A fixture that gives each GL test a current debug context, or skips the test when the
// machine has no EGL device at all (any other GL environment failure is a failure).
#include <gtest/gtest.h>

#include <optional>

#include "gpu/egl_context.h"
#include "gpu/gl_environment_error.h"
#include "support/test_requirements.h"

namespace shadowcert::gpu::test {

// SHADOWCERT_REQUIRE_GL=1 (CI): no EGL device is a failure, not a skip (support/test_requirements.h).
using ::shadowcert::test::gl_required;

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      // Debug on in every test: a GL error anywhere fails the test with the driver's text.
      context_.emplace(EglContextOptions{std::nullopt, true});
    } catch (const NoGlDeviceError& error) {
      if (gl_required()) FAIL() << "SHADOWCERT_REQUIRE_GL=1 but: " << error.what();
      GTEST_SKIP() << "no EGL device: " << error.what();
    }
  }
  std::optional<EglContext> context_;
};

}  // namespace shadowcert::gpu::test
