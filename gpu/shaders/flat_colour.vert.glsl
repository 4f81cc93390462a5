#version 450 core
// World-space soup positions to clip space with one matrix (projection * view, built in
// double on the CPU by gpu/camera_transform.h and rounded once to float).
layout(location = 0) in vec3 position;
layout(location = 0) uniform mat4 world_to_clip;

void main() {
  gl_Position = world_to_clip * vec4(position, 1.0);
}
