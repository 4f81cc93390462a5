#version 450 core
// A host's vertex positions into the canonical soup's vertices (gpu/host_shadow_volumes.h):
// canonical vertex i takes the host's vertex host_index[i], read as three floats or three
// doubles from the host's buffer (words of 4 bytes from first_word, stride_words apart) and
// rounded once to float (round to nearest, as the CPU's static_cast<float> in
// ComputeVolumeSoup), w = 1. One invocation per canonical vertex.
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer HostWords { uint words[]; };
layout(std430, binding = 1) readonly buffer HostIndex { uint host_index[]; };
layout(std430, binding = 2) writeonly buffer Vertices { vec4 vertices[]; };
layout(location = 0) uniform uint first_word;
layout(location = 1) uniform uint stride_words;
layout(location = 2) uniform uint doubles;  // 1: GL_DOUBLE components, 0: GL_FLOAT
layout(location = 3) uniform uint vertex_count;

void main() {
  uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u + gl_GlobalInvocationID.x;
  if (i >= vertex_count) return;
  uint w = first_word + host_index[i] * stride_words;
  vec3 p;
  if (doubles != 0u) {
    for (uint k = 0u; k < 3u; ++k) p[k] = float(packDouble2x32(uvec2(words[w + 2u * k], words[w + 2u * k + 1u])));
  } else {
    p = vec3(uintBitsToFloat(words[w]), uintBitsToFloat(words[w + 1u]), uintBitsToFloat(words[w + 2u]));
  }
  vertices[i] = vec4(p, 1.0);
}
