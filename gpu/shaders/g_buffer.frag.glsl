#version 450 core
// The G-buffer (gpu/g_buffer.h; Nienhaus & Doellner §4.1.1): the eye-space unit normal turned
// towards the eye in rgb, the linear view depth normalised to the fitted depth range in a.
layout(location = 0) in vec3 view_position;
layout(location = 1) in vec3 view_normal;
layout(location = 2) uniform vec2 depth_range;  // (near, far) view depths stored as 0 and 1
layout(location = 0) out vec4 g_buffer;

#include "facing_normal.glsl"

void main() {
  vec3 n = facing_normal(view_position, view_normal, vec3(0.0));  // the eye is the origin
  float view_depth = -view_position.z;  // the camera looks down -z
  g_buffer = vec4(n, (view_depth - depth_range.x) / (depth_range.y - depth_range.x));
}
