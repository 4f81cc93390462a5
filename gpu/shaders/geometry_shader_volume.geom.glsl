#version 450 core
// The `gs` shadow volume (gpu/geometry_shader_volume.h): Milet 2014's reference-edge
// multiplicities (§2.2) evaluated in a geometry shader and the chain of docs/definitions.md#counts emitted
// as triangle strips, captured by transform feedback. One input point per item:
//   item < record_count : an EDGE RECORD (u, v, up to kOppositesPerRecord opposite vertices;
//                         an edge with more opposites has several records). Its partial
//                         multiplicity m = - sum of the refedge signs of its opposites;
//                         |m| side quads (u, v, v_inf, u_inf) oriented by sign(m), each as
//                         two triangles in cs's vertex order. Partial
//                         quads of one edge add up to the edge's m copies (a copy of +1 and a
//                         copy of -1 cancel in every stencil count), so the chain stays closed.
//   otherwise           : triangle item - record_count: s(t) from the same sorted evaluation,
//                         front cap t' and back cap (t' at infinity, reversed) where s != 0.
// The signs are reference_edge.glsl's, as in compute_volume.comp.glsl (sort by canonical
// index, core/light_side_formula.h's order, `precise`, parity): the volumes of `cs` and `gs`
// are made of the same signs, equal to exact/'s float32 refedge.
layout(points) in;
// |m| <= kOppositesPerRecord quads of at most 9 triangles each (far_split.glsl: two, or a fan
// over a far edge split into 8), 3-vertex strips each: 108; caps need at most 3 + 72.
layout(triangle_strip, max_vertices = 108) out;

const uint kOppositesPerRecord = 4u;  // == kOppositesPerRecord in gpu/geometry_shader_volume.cpp
const uint kRecordWords = 4u + kOppositesPerRecord;  // u, v, count, unused, opposites

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };        // w = 1, float
layout(std430, binding = 1) readonly buffer Records { uint records[]; };          // kRecordWords each
layout(std430, binding = 2) readonly buffer Triangles { uint triangle_index[]; }; // 3 per triangle

layout(location = 0) uniform vec4 light;          // (l, w), rounded once to float
layout(location = 1) uniform uint record_count;   // items before the triangles

flat in uint item_id[];

#include "reference_edge.glsl"
#include "volume_capture.glsl"

void edge_record(uint r) {
  const uint base = r * kRecordWords;
  const uint u = records[base];
  const uint v = records[base + 1u];
  const uint count = records[base + 2u];
  int m = 0;
  for (uint i = 0u; i < count; ++i) {
    m -= opposite_side(u, v, records[base + 4u + i]);
  }
  if (m == 0) return;
  const vec4 p = vertices[m > 0 ? u : v];
  const vec4 q = vertices[m > 0 ? v : u];
  for (int k = 0; k < abs(m); ++k) side_quad(p, q);
}

void triangle(uint t) {
  triangle_caps(triangle_index[3u * t], triangle_index[3u * t + 1u], triangle_index[3u * t + 2u]);
}

void main() {
  const uint id = item_id[0];
  if (id < record_count) {
    edge_record(id);
  } else {
    triangle(id - record_count);
  }
}
