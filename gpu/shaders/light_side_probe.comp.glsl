#version 450 core
// The probe of gpu/light_side_probe.h: light_side_sign.glsl on given vertex triples, one
// invocation each, writing the sign and whether the exact stage ran (the filter could not
// decide). Tests compare the signs with exact/'s; benchmarks report the fallback rate.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };      // 3 per triple, w unused
layout(std430, binding = 1) writeonly buffer Results { ivec2 results[]; };  // (sign, fallback)

layout(location = 0) uniform vec4 light;  // (l, w), rounded once to float
layout(location = 1) uniform uint triple_count;

#include "light_side_sign.glsl"

void main() {
  const uint id = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
  if (id >= triple_count) return;
  const int s = light_side_sign(points[3u * id].xyz, points[3u * id + 1u].xyz, points[3u * id + 2u].xyz);
#ifdef SHADOWCERT_FLOAT_SIGNS
  results[id] = ivec2(s, 0);
#else
  results[id] = ivec2(s, light_side_used_fallback ? 1 : 0);
#endif
}
