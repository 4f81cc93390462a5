#version 450 core
// The `ts` volume's finish pass (gpu/tessellation_volume.h), one work group:
//   1. GL_PRIMITIVES_GENERATED, written into `requested` by glGetQueryBufferObjectuiv, becomes
//      vertices (every captured primitive is a triangle);
//   2. with exact signs, the edge records the control shader's float filter could not decide
//      (Deferred) get their partial multiplicity m from the exact signs (reference_edge.glsl with
//      light_side_sign.glsl's exact stage, as cs, gs and the geometry stage's caps take them) and
//      |m| copies of their side quad, split as far_split.glsl splits, appended after the
//      captured triangles. The chain is the same set of triangles as cs's; only their order in
//      the buffer differs.
//   3. the draw count is what was requested, clamped to the buffer (an overflow stays visible
//      through `requested`, never drawn past).
layout(local_size_x = 64) in;

const uint kOppositesPerRecord = 16u;  // == kTessellationOppositesPerRecord (tessellation_volume.h)
const uint kRecordWords = 4u + kOppositesPerRecord;  // u, v, count, kind, opposites
const uint kVerticesPerTriangle = 3u;

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };  // w = 1, float
layout(std430, binding = 1) coherent buffer Deferred {
  uint deferred_count;
  uint deferred_records[];
};
layout(std430, binding = 2) coherent buffer Command {
  uint vertex_count;
  uint instance_count;
  uint first_vertex;
  uint base_instance;
  uint requested;
};
layout(std430, binding = 3) readonly buffer Records { uint record_words[]; };
layout(std430, binding = 4) writeonly buffer Volume { vec4 volume[]; };  // the capture buffer

layout(location = 0) uniform vec4 light;     // (l, w), rounded once to float
layout(location = 1) uniform uint capacity;  // vertices the capture buffer holds, a multiple of 3

#include "reference_edge.glsl"

#include "volume_reservation.glsl"
#include "far_split.glsl"

void deferred_record(uint record) {
  const uint first = record * kRecordWords;
  const uint u = record_words[first];
  const uint v = record_words[first + 1u];
  const uint count = record_words[first + 2u];
  int m = 0;
  for (uint i = 0u; i < count; ++i) m -= opposite_side(u, v, record_words[first + 4u + i]);
  if (m == 0) return;
  const vec4 p = vertices[m > 0 ? u : v];
  const vec4 q = vertices[m > 0 ? v : u];
  const uint copies = uint(abs(m));
  const uint base = reserve(copies * 3u * side_quad_triangle_count(p, q));
  if (base == kNoRoom) return;
  volume_cursor = base;
  for (uint k = 0u; k < copies; ++k) side_quad_triangles(p, q);
}

void main() {
  const uint id = gl_LocalInvocationID.x;
  if (id == 0u) requested *= kVerticesPerTriangle;
  memoryBarrierBuffer();
  barrier();
  for (uint d = id; d < deferred_count; d += gl_WorkGroupSize.x) deferred_record(deferred_records[d]);
  memoryBarrierBuffer();
  barrier();
  if (id == 0u) vertex_count = min(requested, capacity);
}
