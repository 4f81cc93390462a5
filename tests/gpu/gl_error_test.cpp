// gpu/gl_error.h's error names: plain code, no GL context (check_gl_errors itself is tested
// with a context in egl_context_test).
#include "gpu/gl_error.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

namespace shadowcert::gpu {
namespace {

TEST(GlErrorName, NamesKnownAndUnknownCodes) {
  EXPECT_EQ(gl_error_name(GL_INVALID_ENUM), "GL_INVALID_ENUM");
  EXPECT_EQ(gl_error_name(0x1234), "GL error 0x1234");
}

}  // namespace
}  // namespace shadowcert::gpu
