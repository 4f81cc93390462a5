#version 450 core
// The G-buffer pass of edge maps (gpu/g_buffer.h): ShadedSoupMesh's vertices (attribute 0 the
// position, w = 1; attribute 1 the normal) to clip space, and to eye space for the fragment's
// normal and linear depth. Both matrices are built in double (gpu/camera_transform.h) and
// rounded once to float.
layout(location = 0) in vec4 position;
layout(location = 1) in vec3 normal;
layout(location = 0) uniform mat4 world_to_clip;
layout(location = 1) uniform mat4 world_to_view;

layout(location = 0) out vec3 view_position;
layout(location = 1) out vec3 view_normal;

void main() {
  gl_Position = world_to_clip * position;
  view_position = (world_to_view * position).xyz;
  // The view matrix is a rotation and a translation (core/pixel_ray.h's orthonormal frame), so
  // its upper 3 x 3 maps normals too.
  view_normal = mat3(world_to_view) * normal;
}
