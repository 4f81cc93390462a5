#pragma once
// A shadow-volume chain as the GPU draws it (docs/definitions.md#counts): homogeneous vertices and
// outward-oriented triangles (core/homogeneous_mesh.h). gpu/ does not build exact chains:
// exact/chain_mesh.h converts exact/'s symbolic chain into this form and the caller uploads it.
//
// Vertices: w = 1 for finite points x; w = 0 for points at infinity, x_inf = (x - l, 0) for
// a point light at l and (-l, 0) for a directional light towards l. The projection's far
// plane is at infinity (gpu/camera_transform.h) and GL_DEPTH_CLAMP is on while volumes are
// drawn, so w = 0 vertices are never clipped: caps at infinity reach depth 1.
// Triangles: oriented outwards (normal by the right-hand rule), side quads split in two.
#include "core/homogeneous_mesh.h"
#include "gpu/gl_object.h"

namespace shadowcert::gpu {


// The geometry in a vertex array (attribute 0 = vec4 position), ready for glDrawElements.
class ShadowVolumeMesh {
 public:
  // Throws std::invalid_argument on an index out of range or too many triangles.
  explicit ShadowVolumeMesh(const HomogeneousMesh& geometry);

  [[nodiscard]] GLuint vertex_array() const { return vertex_array_.name(); }
  [[nodiscard]] GLsizei index_count() const { return index_count_; }

 private:
  Buffer positions_;
  Buffer indices_;
  VertexArray vertex_array_;
  GLsizei index_count_ = 0;
};

}  // namespace shadowcert::gpu
