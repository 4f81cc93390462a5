#version 450 core
// The `gs` volume's draw count (gpu/geometry_shader_volume.h): GL_PRIMITIVES_GENERATED was
// written into `requested` by glGetQueryBufferObjectuiv; every captured primitive is a
// triangle, so the request is 3 vertices each, drawn no further than transform feedback
// could write (an overflow stays visible through `requested`).
layout(local_size_x = 1) in;

layout(std430, binding = 0) coherent buffer Command {
  uint vertex_count;
  uint instance_count;
  uint first_vertex;
  uint base_instance;
  uint requested;
};

layout(location = 0) uniform uint capacity;  // vertices the capture buffer holds, a multiple of 3

const uint kVerticesPerTriangle = 3u;

void main() {
  requested *= kVerticesPerTriangle;
  vertex_count = min(requested, capacity);
}
