#include "gpu/soup_mesh.h"

#include <limits>
#include <stdexcept>
#include <vector>

#include "gpu/gl_error.h"

namespace shadowcert::gpu {

SoupMesh::SoupMesh(const Soup& soup)
    : positions_(Buffer::create()), indices_(Buffer::create()), vertex_array_(VertexArray::create()) {
  if (soup.triangles.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max() / 3)) {
    throw std::invalid_argument("SoupMesh: too many triangles for one draw call");
  }
  std::vector<float> xyz;
  xyz.reserve(soup.vertices.size() * 3);
  for (const Vec3& v : soup.vertices) {
    for (double c : v) xyz.push_back(static_cast<float>(c));
  }
  // glNamedBufferStorage rejects size 0: an empty soup still gets a valid (tiny) buffer.
  const float zero = 0.0f;
  glNamedBufferStorage(positions_.name(), xyz.empty() ? sizeof zero : static_cast<GLsizeiptr>(xyz.size() * sizeof(float)),
                       xyz.empty() ? &zero : xyz.data(), 0);
  const std::uint32_t no_index = 0;
  glNamedBufferStorage(indices_.name(),
                       soup.triangles.empty() ? sizeof no_index
                                              : static_cast<GLsizeiptr>(soup.triangles.size() * sizeof(Triangle)),
                       soup.triangles.empty() ? static_cast<const void*>(&no_index) : soup.triangles.data(), 0);
  index_count_ = static_cast<GLsizei>(soup.triangles.size() * 3);

  glVertexArrayVertexBuffer(vertex_array_.name(), 0, positions_.name(), 0, 3 * sizeof(float));
  glVertexArrayAttribFormat(vertex_array_.name(), 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vertex_array_.name(), 0, 0);
  glEnableVertexArrayAttrib(vertex_array_.name(), 0);
  glVertexArrayElementBuffer(vertex_array_.name(), indices_.name());
  check_gl_errors("SoupMesh upload");
}

}  // namespace shadowcert::gpu
