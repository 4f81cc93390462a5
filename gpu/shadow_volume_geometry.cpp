#include "gpu/shadow_volume_geometry.h"

#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/gl_error.h"

namespace shadowcert::gpu {

ShadowVolumeMesh::ShadowVolumeMesh(const HomogeneousMesh& geometry)
    : positions_(Buffer::create()), indices_(Buffer::create()), vertex_array_(VertexArray::create()) {
  if (geometry.triangles.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max() / 3)) {
    throw std::invalid_argument("ShadowVolumeMesh: too many triangles for one draw call");
  }
  for (const auto& t : geometry.triangles) {
    for (std::uint32_t id : t) {
      if (id >= geometry.vertices.size()) {
        throw std::invalid_argument("ShadowVolumeMesh: vertex index " + std::to_string(id) + " out of range (" +
                                    std::to_string(geometry.vertices.size()) + " vertices)");
      }
    }
  }
  // glNamedBufferStorage rejects size 0: an empty volume still gets a valid (tiny) buffer.
  const std::array<float, 4> origin{0.0f, 0.0f, 0.0f, 1.0f};
  const std::uint32_t no_index = 0;
  glNamedBufferStorage(positions_.name(),
                       geometry.vertices.empty() ? sizeof origin
                                                 : static_cast<GLsizeiptr>(geometry.vertices.size() * sizeof origin),
                       geometry.vertices.empty() ? origin.data() : geometry.vertices.front().data(), 0);
  glNamedBufferStorage(indices_.name(),
                       geometry.triangles.empty()
                           ? sizeof no_index
                           : static_cast<GLsizeiptr>(geometry.triangles.size() * sizeof geometry.triangles.front()),
                       geometry.triangles.empty() ? static_cast<const void*>(&no_index) : geometry.triangles.data(), 0);
  index_count_ = static_cast<GLsizei>(geometry.triangles.size() * 3);

  glVertexArrayVertexBuffer(vertex_array_.name(), 0, positions_.name(), 0, sizeof origin);
  glVertexArrayAttribFormat(vertex_array_.name(), 0, 4, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vertex_array_.name(), 0, 0);
  glEnableVertexArrayAttrib(vertex_array_.name(), 0);
  glVertexArrayElementBuffer(vertex_array_.name(), indices_.name());
  check_gl_errors("ShadowVolumeMesh upload");
}

}  // namespace shadowcert::gpu
