#pragma once
// A host's vertex attribute in one of its GL buffers (docs/engine-integration.md#gl-layer):
// where the host layer (gpu/host_shadow_volumes.h) reads positions, normals or colours from,
// without copying them to the CPU.
#include <epoxy/gl.h>

namespace shadowcert::gpu {

struct HostVertexBuffer {
  GLuint buffer = 0;       // a buffer name of the host's (current) context
  GLintptr offset = 0;     // bytes from the buffer's start to vertex 0's first component
  GLsizei stride = 0;      // bytes from one vertex to the next; 0: tightly packed components
  GLenum type = GL_FLOAT;  // GL_FLOAT or GL_DOUBLE
  GLint components = 3;    // 3 (x, y, z; a position's w is then 1) or 4
};

}  // namespace shadowcert::gpu
