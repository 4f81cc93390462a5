#include "gpu/smoothie_map.h"

#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gpu/detail/gl_readback.h"
#include "gpu/embedded_shaders.h"
#include "gpu/gl_error.h"
#include "gpu/shader_compiler.h"

namespace shadowcert::gpu {
namespace {

// Uniform locations of smoothie_map.vert.glsl.
constexpr GLint kLightToClipLocation = 0;
constexpr GLint kLightViewLocation = 1;

}  // namespace

SmoothieQuads::SmoothieQuads(const SmoothieMesh& mesh)
    : vertices_(Buffer::create()), indices_(Buffer::create()), vertex_array_(VertexArray::create()) {
  if (mesh.alpha.size() != mesh.vertices.size())
    throw std::invalid_argument("SmoothieQuads: " + std::to_string(mesh.alpha.size()) + " alphas for " +
                                std::to_string(mesh.vertices.size()) + " vertices");
  if (3 * mesh.triangles.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max()))
    throw std::invalid_argument("SmoothieQuads: too many triangles for one draw call");
  std::vector<std::array<float, 4>> vertices;
  vertices.reserve(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const auto& p = mesh.vertices[i];
    vertices.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]), mesh.alpha[i]});
  }
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (std::uint32_t i : t) {
      if (i >= mesh.vertices.size())
        throw std::invalid_argument("SmoothieQuads: index " + std::to_string(i) + " out of range (" +
                                    std::to_string(mesh.vertices.size()) + " vertices)");
      indices.push_back(i);
    }
  // Buffers of at least one element: GL refuses empty storage; nothing is drawn then.
  const std::array<float, 4> none_vertex{};
  const std::uint32_t none_index = 0;
  glNamedBufferStorage(vertices_.name(),
                       vertices.empty() ? sizeof none_vertex
                                        : static_cast<GLsizeiptr>(vertices.size() * sizeof(vertices[0])),
                       vertices.empty() ? none_vertex.data() : vertices.front().data(), 0);
  glNamedBufferStorage(indices_.name(),
                       indices.empty() ? sizeof none_index : static_cast<GLsizeiptr>(indices.size() * sizeof(indices[0])),
                       indices.empty() ? &none_index : indices.data(), 0);
  index_count_ = static_cast<GLsizei>(indices.size());
  const GLuint vao = vertex_array_.name();
  glVertexArrayVertexBuffer(vao, 0, vertices_.name(), 0, sizeof(std::array<float, 4>));
  glVertexArrayElementBuffer(vao, indices_.name());
  glVertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  glEnableVertexArrayAttrib(vao, 0);
  check_gl_errors("SmoothieQuads upload");
}

SmoothieMap::SmoothieMap(std::uint32_t size) : size_(size) {
  if (size == 0) throw std::invalid_argument("SmoothieMap: size 0");
  const auto side = static_cast<GLsizei>(size);
  texture_ = Texture::create(GL_TEXTURE_2D);
  glTextureStorage2D(texture_.name(), 1, GL_RG32F, side, side);
  // texelFetch only; nearest so that no driver filters alphas of different smoothies together.
  glTextureParameteri(texture_.name(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture_.name(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(texture_.name(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture_.name(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  depth_ = Renderbuffer::create();
  glNamedRenderbufferStorage(depth_.name(), GL_DEPTH_COMPONENT32F, side, side);
  framebuffer_ = Framebuffer::create();
  glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT0, texture_.name(), 0);
  glNamedFramebufferRenderbuffer(framebuffer_.name(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.name());
  if (glCheckNamedFramebufferStatus(framebuffer_.name(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("SmoothieMap: the " + std::to_string(size) + "^2 framebuffer is incomplete");
  check_gl_errors("SmoothieMap: texture");
  const Shader vertex = compile_shader(GL_VERTEX_SHADER, shaders::smoothie_map_vert, "smoothie_map.vert.glsl");
  const Shader fragment = compile_shader(GL_FRAGMENT_SHADER, shaders::smoothie_map_frag, "smoothie_map.frag.glsl");
  program_ = link_program({&vertex, &fragment}, "smoothie_map");
}

void SmoothieMap::render(const SmoothieQuads& quads, const glm::mat4& light_to_clip,
                         const glm::mat4& light_view) const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.name());
  glViewport(0, 0, static_cast<GLsizei>(size_), static_cast<GLsizei>(size_));
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  const std::array<float, 4> empty{kNoSmoothieAlpha, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(framebuffer_.name(), GL_COLOR, 0, empty.data());
  glClearNamedFramebufferfv(framebuffer_.name(), GL_DEPTH, 0, std::array<float, 1>{1.0f}.data());
  if (quads.index_count() == 0) return;
  const GLuint program = program_.name();
  glProgramUniformMatrix4fv(program, kLightToClipLocation, 1, GL_FALSE, glm::value_ptr(light_to_clip));
  glProgramUniformMatrix4fv(program, kLightViewLocation, 1, GL_FALSE, glm::value_ptr(light_view));
  glUseProgram(program);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_BLEND);  // the nearest smoothie's alpha, never a sum (§2.4)
  glDisable(GL_CULL_FACE);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_DEPTH_CLAMP);
  glBindVertexArray(quads.vertex_array());
  glDrawElements(GL_TRIANGLES, quads.index_count(), GL_UNSIGNED_INT, nullptr);
  glDisable(GL_DEPTH_CLAMP);
  glBindVertexArray(0);
  check_gl_errors("SmoothieMap::render");
}

std::vector<float> SmoothieMap::read() const {
  return detail::read_texture<float>(texture_.name(), GL_RG, GL_FLOAT, {size_, size_, 2}, detail::RowOrder::gl,
                                     "SmoothieMap::read");
}

}  // namespace shadowcert::gpu
