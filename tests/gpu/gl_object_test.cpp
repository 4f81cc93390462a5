#include "gpu/gl_object.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <type_traits>
#include <unistd.h>
#include <vector>

#include "core/soup.h"
#include "support/gl_test_support.h"
#include "gpu/flat_soup_renderer.h"
#include "gpu/gl_error.h"
#include "gpu/offscreen_target.h"
#include "gpu/soup_mesh.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;

// One owner of every kind, and the glIs* that says whether its name is alive.
struct AllObjects {
  Buffer buffer = Buffer::create();
  VertexArray vertex_array = VertexArray::create();
  Shader shader = Shader::create(GL_VERTEX_SHADER);
  Program program = Program::create();
  Framebuffer framebuffer = Framebuffer::create();
  Renderbuffer renderbuffer = Renderbuffer::create();
  Texture texture = Texture::create(GL_TEXTURE_2D);
  Query query = Query::create(GL_SAMPLES_PASSED);

  struct Names {
    GLuint buffer, vertex_array, shader, program, framebuffer, renderbuffer, texture, query;
  };
  [[nodiscard]] Names names() const {
    return {buffer.name(), vertex_array.name(), shader.name(), program.name(),
            framebuffer.name(), renderbuffer.name(), texture.name(), query.name()};
  }
};

// How many of the names are still GL objects.
int alive(const AllObjects::Names& n) {
  return int{glIsBuffer(n.buffer) == GL_TRUE} + int{glIsVertexArray(n.vertex_array) == GL_TRUE} +
         int{glIsShader(n.shader) == GL_TRUE} + int{glIsProgram(n.program) == GL_TRUE} +
         int{glIsFramebuffer(n.framebuffer) == GL_TRUE} + int{glIsRenderbuffer(n.renderbuffer) == GL_TRUE} +
         int{glIsTexture(n.texture) == GL_TRUE} + int{glIsQuery(n.query) == GL_TRUE};
}

template <class T>
class GlObjectMoveTest : public GlTest {};

// Each owner type with the arguments its create() needs.
struct BufferKind { using Type = Buffer; static Type make() { return Type::create(); } };
struct VertexArrayKind { using Type = VertexArray; static Type make() { return Type::create(); } };
struct ShaderKind { using Type = Shader; static Type make() { return Type::create(GL_FRAGMENT_SHADER); } };
struct ProgramKind { using Type = Program; static Type make() { return Type::create(); } };
struct FramebufferKind { using Type = Framebuffer; static Type make() { return Type::create(); } };
struct RenderbufferKind { using Type = Renderbuffer; static Type make() { return Type::create(); } };
struct TextureKind { using Type = Texture; static Type make() { return Type::create(GL_TEXTURE_2D); } };
struct QueryKind { using Type = Query; static Type make() { return Type::create(GL_TIME_ELAPSED); } };

using Kinds = ::testing::Types<BufferKind, VertexArrayKind, ShaderKind, ProgramKind, FramebufferKind,
                               RenderbufferKind, TextureKind, QueryKind>;
TYPED_TEST_SUITE(GlObjectMoveTest, Kinds);

TYPED_TEST(GlObjectMoveTest, MoveTransfersOwnershipAndDeletesOnce) {
  static_assert(!std::is_copy_constructible_v<typename TypeParam::Type>);
  static_assert(!std::is_copy_assignable_v<typename TypeParam::Type>);
  static_assert(std::is_nothrow_move_constructible_v<typename TypeParam::Type>);

  typename TypeParam::Type a = TypeParam::make();
  const GLuint name = a.name();
  ASSERT_NE(name, 0u);

  typename TypeParam::Type b = std::move(a);  // construction
  EXPECT_EQ(a.name(), 0u);                    // NOLINT(bugprone-use-after-move): the contract
  EXPECT_FALSE(a);
  EXPECT_EQ(b.name(), name);

  typename TypeParam::Type c = TypeParam::make();
  const GLuint other = c.name();
  c = std::move(b);  // assignment deletes what c held
  EXPECT_EQ(c.name(), name);
  EXPECT_EQ(b.name(), 0u);  // NOLINT(bugprone-use-after-move)

  c = std::move(c);  // self-move keeps the object
  EXPECT_EQ(c.name(), name);

  c.reset();
  EXPECT_EQ(c.name(), 0u);
  EXPECT_NE(other, name);  // its deletion by the assignment is checked by GL: no error below
  check_gl_errors("move test");
}
// The GL context fixture (support/gl_test_support.h) under this unit's name, for
// --gtest_filter=GlObjectTest.*
class GlObjectTest : public GlTest {};

TEST_F(GlObjectTest, DeletedNamesAreNoLongerObjects) {
  AllObjects::Names names{};
  {
    AllObjects objects;
    names = objects.names();
    EXPECT_EQ(alive(names), 8);
  }
  EXPECT_EQ(alive(names), 0);
  check_gl_errors("glIs* probes");
}

long resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  long size = 0;
  long resident = 0;
  statm >> size >> resident;
  return resident * sysconf(_SC_PAGESIZE);
}

// Growth of the resident set over kCycles context + object lifetimes, after kWarmUpCycles
// have let the driver fill its caches (shader cache, thread pools, allocator arenas).
// It absorbs allocator fragmentation and driver bookkeeping (measured: under 1 MiB on
// llvmpipe). A leaked llvmpipe context costs about 2.6 MiB, so 100 of them would exceed it
// sixteen times over. Objects leaked inside a context die with it: glIs* catches those.
constexpr long kMaxRssGrowthBytes = 16L << 20;
constexpr int kWarmUpCycles = 5;
constexpr int kCycles = 100;

TEST(GlObjectLeaks, HundredContextAndObjectCyclesLeakNothing) {
  const Soup triangle{{{-1.0, -1.0, 0.0}, {1.0, -1.0, 0.0}, {0.0, 1.0, 0.0}}, {{0, 1, 2}}, {}};
  Camera camera;
  camera.width = 64;
  camera.height = 64;
  auto cycle = [&] {
    EglContext context(EglContextOptions{std::nullopt, true});
    AllObjects::Names names{};
    {
      AllObjects objects;
      names = objects.names();
      OffscreenTarget target(64, 64);
      SoupMesh mesh(triangle);
      FlatSoupRenderer renderer;
      target.bind();
      target.clear();
      renderer.draw(mesh, camera);
      (void)target.read_stencil();
      ASSERT_EQ(alive(names), 8);
    }
    ASSERT_EQ(alive(names), 0);
    check_gl_errors("leak cycle");
  };
  try {
    for (int i = 0; i < kWarmUpCycles; ++i) cycle();
  } catch (const NoGlDeviceError& error) {
    if (test::gl_required()) FAIL() << error.what();
    GTEST_SKIP() << "no EGL device: " << error.what();
  }
  const long before = resident_bytes();
  for (int i = 0; i < kCycles; ++i) {
    cycle();
    if (HasFatalFailure()) return;
  }
  const long growth = resident_bytes() - before;
  std::cout << "RSS growth over " << kCycles << " cycles: " << growth / 1024 << " KiB\n";
  EXPECT_LT(growth, kMaxRssGrowthBytes);
}

}  // namespace
}  // namespace shadowcert::gpu
