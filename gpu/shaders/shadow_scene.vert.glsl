#version 450 core
// Shared by every pass of the stencil shadow pipeline (depth/ambient, volume, lit): one
// program, one matrix, one expression, so a front cap and the occluder triangle it
// coincides with, and the lit pass and the depth pass, rasterise to bit-identical depths
// (GL_EQUAL in the lit pass, GL_LESS in the volume pass rely on it; no polygon offset).
// Positions are homogeneous: w = 0 for shadow-volume vertices at infinity (docs/definitions.md#counts).
layout(location = 0) in vec4 position;
layout(location = 1) in vec3 normal;   // shading only; (0, 0, 0) for volumes
layout(location = 2) in vec3 albedo;
layout(location = 0) uniform mat4 world_to_clip;

invariant gl_Position;
layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 world_normal;
layout(location = 2) out vec3 surface_albedo;

void main() {
  precise vec4 clip = world_to_clip * position;
  gl_Position = clip;
  world_position = position.xyz;
  world_normal = normal;
  surface_albedo = albedo;
}
