#version 450 core
// Depth pass of the shadow map: receivers seen from the light (light_to_clip is fitted to the
// scene's bounds, gpu/shadow_map_renderer.cpp). Attribute 0 of ShadedSoupMesh only.
layout(location = 0) in vec4 position;
layout(location = 0) uniform mat4 light_to_clip;

void main() { gl_Position = light_to_clip * position; }
