#include "gpu/shader_compiler.h"

#include <gtest/gtest.h>

#include "support/gl_test_support.h"
#include "gpu/flat_soup_renderer.h"
#include "gpu/gl_error.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;
// The GL context fixture (support/gl_test_support.h) under this unit's name, for
// --gtest_filter=ShaderCompilerTest.*
class ShaderCompilerTest : public GlTest {};

TEST_F(ShaderCompilerTest, CompileErrorThrowsWithNameAndInfoLog) {
  const char* broken = "#version 450 core\nout vec4 c;\nvoid main() { c = undeclared_thing; }\n";
  try {
    (void)compile_shader(GL_FRAGMENT_SHADER, broken, "broken.frag.glsl");
    FAIL() << "expected GlError";
  } catch (const GlError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("broken.frag.glsl"), std::string::npos) << what;
    EXPECT_NE(what.find("compile error"), std::string::npos) << what;
    EXPECT_NE(what.find("undeclared_thing"), std::string::npos) << what;  // the driver's log
  }
}

TEST_F(ShaderCompilerTest, LinkErrorThrowsWithProgramName) {
  // A fragment shader without main(): compiles alone, fails to link.
  const Shader no_main = compile_shader(GL_FRAGMENT_SHADER, "#version 450 core\nout vec4 c;\n", "no_main.frag");
  try {
    (void)link_program({&no_main}, "lonely_program");
    FAIL() << "expected GlError";
  } catch (const GlError& error) {
    EXPECT_NE(std::string(error.what()).find("lonely_program"), std::string::npos) << error.what();
  }
}

TEST_F(ShaderCompilerTest, EmbeddedShadersCompileAndLink) { EXPECT_NO_THROW(FlatSoupRenderer{}); }

}  // namespace
}  // namespace shadowcert::gpu
