#version 450 core
// The `ts` shadow volume (gpu/tessellation_volume.h): Milet 2014 §2.2, Algorithms 3-4, in a
// tessellation control shader. One patch per RECORD of kRecordWords words:
//   kind 0, an EDGE RECORD (u, v, count, 0, up to kOppositesPerRecord opposite vertices; an
//           edge with more opposites has several records): partial multiplicity
//           m = - sum of the refedge signs of its opposites, and |m| isolines, one per copy of
//           the side quad (the geometry shader makes each line a quad oriented by sign(m));
//           m = 0 discards the patch (outer level 0).
//   kind 1, a TRIANGLE (a, b, c, 1, unused): one isoline, on which the geometry shader emits
//           gs's caps.
// The sign evaluation is geometry_shader_volume.geom.glsl's (itself compute_volume.comp.glsl's),
// copied operation for operation (sort by canonical index, core/light_side_formula.h's order,
// `precise`, parity): the volumes of cs, gs and ts are made of the same signs.
layout(vertices = 1) out;

const uint kOppositesPerRecord = 16u;  // == kTessellationOppositesPerRecord (tessellation_volume.h)
const uint kRecordWords = 4u + kOppositesPerRecord;  // u, v, count, kind, opposites
const uint kTriangleKind = 1u;

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };  // w = 1, float

layout(location = 0) uniform vec4 light;  // (l, w), rounded once to float

flat in uint record_word[];
// x, y, z: u, v (edge) or a, b, c (triangle); w: kind. multiplicity: m (edge), unused (triangle).
patch out uvec4 item;
patch out int multiplicity;

#include "light_side_formula.glsl"

// Sign of D on an ascending index triple (a < b < c): the one evaluation a triangle gets.
int sorted_side(uint a, uint b, uint c) {
  const float value = light_side_value(vertices[a].xyz, vertices[b].xyz, vertices[c].xyz);
  return value > 0.0 ? 1 : (value < 0.0 ? -1 : 0);
}

void main() {
  const uint u = record_word[0];
  const uint v = record_word[1];
  const uint count = record_word[2];
  const uint kind = record_word[3];
  item = uvec4(u, v, count, kind);
  multiplicity = 0;
  float lines = 1.0;
  if (kind != kTriangleKind) {
    int m = 0;
    for (uint i = 0u; i < count; ++i) {
      const uint o = record_word[4u + i];
      // Milet 2014, Algorithm 3: the three places o can take relative to u < v.
      int s;
      if (o < u) {
        s = sorted_side(o, u, v);   // (u, v, o) is a rotation of (o, u, v): even
      } else if (o < v) {
        s = -sorted_side(u, o, v);  // one transposition: odd
      } else {
        s = sorted_side(u, v, o);
      }
      m -= s;
    }
    multiplicity = m;
    lines = float(abs(m));  // 0 discards the patch
  }
  // Isolines: outer[0] lines (|m| copies), outer[1] = 1 segment each.
  gl_TessLevelOuter[0] = lines;
  gl_TessLevelOuter[1] = 1.0;
}
