#include "gpu/egl_context.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <iostream>

#include "support/gl_test_support.h"
#include "gpu/gl_error.h"
#include "gpu/gl_object.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;
// The GL context fixture (support/gl_test_support.h) under this unit's name, for
// --gtest_filter=EglContextTest.*
class EglContextTest : public GlTest {};

TEST_F(EglContextTest, ReportsDeviceRendererAndVersion) {
  EXPECT_FALSE(context_->device().empty());
  EXPECT_FALSE(context_->renderer().empty());
  EXPECT_FALSE(context_->version().empty());
  EXPECT_TRUE(context_->debug());
  GLint major = 0;
  GLint minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 45);
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
  // Seen in the test log: which GL the suite really ran on.
  std::cout << "device: " << context_->device() << "\nGL_RENDERER: " << context_->renderer()
            << "\nGL_VERSION: " << context_->version() << "\n";
  if (!context_->fallback_reason().empty()) std::cout << "fallback: " << context_->fallback_reason() << "\n";
}

TEST_F(EglContextTest, ListsDevicesWithDescriptions) {
  for (const EglDeviceInfo& device : list_egl_devices()) {
    EXPECT_NE(device.describe().find("EGL device " + std::to_string(device.index)), std::string::npos);
    std::cout << device.describe() << "\n";
  }
}

TEST_F(EglContextTest, MovedContextKeepsWorkingAndMovedFromRefuses) {
  EglContext moved = std::move(*context_);
  EXPECT_THROW(context_->make_current(), std::logic_error);
  moved.make_current();
  EXPECT_NE(glGetString(GL_RENDERER), nullptr);
  EglContext assigned(EglContextOptions{std::nullopt, false});  // a second, current context
  assigned = std::move(moved);  // destroys the second one, takes the first
  assigned.make_current();
  EXPECT_NE(glGetString(GL_VERSION), nullptr);
  EXPECT_TRUE(assigned.debug());
  check_gl_errors("after moves");
}

TEST_F(EglContextTest, UnknownDeviceIndexThrowsEnvironmentError) {
  try {
    EglContext bad(EglContextOptions{999, false});
    FAIL() << "device 999 should not exist";
  } catch (const GlEnvironmentError& error) {
    EXPECT_NE(std::string(error.what()).find("999"), std::string::npos) << error.what();
  }
}

TEST_F(EglContextTest, EveryListedDeviceIndexIsAccepted) {
  // The explicit --device path: each index either gives a 4.5 context or says why.
  for (const EglDeviceInfo& device : list_egl_devices()) {
    try {
      EglContext explicit_device(EglContextOptions{device.index, false});
      EXPECT_FALSE(explicit_device.renderer().empty());
    } catch (const GlEnvironmentError& error) {
      std::cout << device.describe() << ": " << error.what() << "\n";
    }
  }
}

TEST_F(EglContextTest, CheckGlErrorsIsQuietWithoutErrors) { EXPECT_NO_THROW(check_gl_errors("idle")); }

TEST_F(EglContextTest, GlErrorBecomesExceptionWithWhereAndDriverMessage) {
  // A name never generated: core profile makes binding it GL_INVALID_OPERATION.
  glBindBuffer(GL_ARRAY_BUFFER, 0xBAD);
  try {
    check_gl_errors("binding a bogus buffer");
    FAIL() << "expected GlError";
  } catch (const GlError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("binding a bogus buffer"), std::string::npos) << what;
    EXPECT_NE(what.find("GL_INVALID_OPERATION"), std::string::npos) << what;
    EXPECT_NE(what.find("driver:"), std::string::npos) << what;  // the debug callback's text
  }
  EXPECT_NO_THROW(check_gl_errors("errors are consumed once reported"));
}

}  // namespace
}  // namespace shadowcert::gpu
