#pragma once
// A soup's vertices (rounded once to float) and triangle indices on the GPU, in a vertex
// array ready for glDrawElements. Attribute 0 = position (flat_soup_renderer draws it; the
// shaded receivers have their own mesh, gpu/stencil_shadow_renderer.h).
#include <cstdint>

#include "core/soup.h"
#include "gpu/gl_object.h"

namespace shadowcert::gpu {

class SoupMesh {
 public:
  explicit SoupMesh(const Soup& soup);

  [[nodiscard]] GLuint vertex_array() const { return vertex_array_.name(); }
  [[nodiscard]] GLsizei index_count() const { return index_count_; }

 private:
  Buffer positions_;
  Buffer indices_;
  VertexArray vertex_array_;
  GLsizei index_count_ = 0;
};

}  // namespace shadowcert::gpu
