#pragma once
// Move-only RAII owners of GL object names, created with GL 4.5's DSA functions
// (glCreate*: the object exists at once, so glIs* is true before any bind).
//
//   auto buffer = Buffer::create();
//   auto texture = Texture::create(GL_TEXTURE_2D);
//   auto shader = Shader::create(GL_VERTEX_SHADER);
//   auto sampler = Sampler::create();
//
// A default-constructed or moved-from owner holds name 0 and deletes nothing. Owners must
// be destroyed while their context is current (the name belongs to that context).
#include <epoxy/gl.h>

#include <utility>

namespace shadowcert::gpu {

// Traits: static GLuint create(args...) and static void destroy(GLuint).
template <class Traits>
class GlObject {
 public:
  GlObject() = default;
  template <class... Args>
  [[nodiscard]] static GlObject create(Args... args) {
    GlObject object;
    object.name_ = Traits::create(args...);
    return object;
  }
  ~GlObject() { reset(); }
  GlObject(GlObject&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
  GlObject& operator=(GlObject&& other) noexcept {
    if (this != &other) {
      reset();
      name_ = std::exchange(other.name_, 0);
    }
    return *this;
  }
  GlObject(const GlObject&) = delete;
  GlObject& operator=(const GlObject&) = delete;

  [[nodiscard]] GLuint name() const { return name_; }
  explicit operator bool() const { return name_ != 0; }
  void reset() {
    if (name_ != 0) Traits::destroy(std::exchange(name_, 0));
  }

 private:
  GLuint name_ = 0;
};

namespace gl_traits {

struct Buffer {
  static GLuint create() { GLuint n = 0; glCreateBuffers(1, &n); return n; }
  static void destroy(GLuint n) { glDeleteBuffers(1, &n); }
};
struct VertexArray {
  static GLuint create() { GLuint n = 0; glCreateVertexArrays(1, &n); return n; }
  static void destroy(GLuint n) { glDeleteVertexArrays(1, &n); }
};
struct Shader {
  static GLuint create(GLenum stage) { return glCreateShader(stage); }
  static void destroy(GLuint n) { glDeleteShader(n); }
};
struct Program {
  static GLuint create() { return glCreateProgram(); }
  static void destroy(GLuint n) { glDeleteProgram(n); }
};
struct Framebuffer {
  static GLuint create() { GLuint n = 0; glCreateFramebuffers(1, &n); return n; }
  static void destroy(GLuint n) { glDeleteFramebuffers(1, &n); }
};
struct Renderbuffer {
  static GLuint create() { GLuint n = 0; glCreateRenderbuffers(1, &n); return n; }
  static void destroy(GLuint n) { glDeleteRenderbuffers(1, &n); }
};
struct Texture {
  static GLuint create(GLenum target) { GLuint n = 0; glCreateTextures(target, 1, &n); return n; }
  static void destroy(GLuint n) { glDeleteTextures(1, &n); }
};
struct Query {
  static GLuint create(GLenum target) { GLuint n = 0; glCreateQueries(target, 1, &n); return n; }
  static void destroy(GLuint n) { glDeleteQueries(1, &n); }
};
struct Sampler {
  static GLuint create() { GLuint n = 0; glCreateSamplers(1, &n); return n; }
  static void destroy(GLuint n) { glDeleteSamplers(1, &n); }
};

}  // namespace gl_traits

using Buffer = GlObject<gl_traits::Buffer>;
using VertexArray = GlObject<gl_traits::VertexArray>;
using Shader = GlObject<gl_traits::Shader>;            // create(GL_VERTEX_SHADER ...)
using Program = GlObject<gl_traits::Program>;
using Framebuffer = GlObject<gl_traits::Framebuffer>;
using Renderbuffer = GlObject<gl_traits::Renderbuffer>;
using Texture = GlObject<gl_traits::Texture>;          // create(GL_TEXTURE_2D ...)
using Query = GlObject<gl_traits::Query>;              // create(GL_SAMPLES_PASSED ...)
using Sampler = GlObject<gl_traits::Sampler>;          // a texture unit's own sampling state

}  // namespace shadowcert::gpu
