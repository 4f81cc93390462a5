#version 450 core
// The `gs` shadow volume (gpu/geometry_shader_volume.h): Milet 2014's reference-edge
// multiplicities (§2.2) evaluated in a geometry shader and the chain of DESIGN.md §3 emitted
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
// The sign evaluation is compute_volume.comp.glsl's, copied operation for operation (sort by
// canonical index, core/light_side_formula.h's order, `precise`, parity): the volumes of `cs`
// and `gs` are made of the same signs, equal to exact/'s float32 refedge.
layout(points) in;
// |m| <= kOppositesPerRecord quads of two 3-vertex strips each; caps need 6.
layout(triangle_strip, max_vertices = 24) out;

const uint kOppositesPerRecord = 4u;  // == kOppositesPerRecord in gpu/geometry_shader_volume.cpp
const uint kRecordWords = 4u + kOppositesPerRecord;  // u, v, count, unused, opposites

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };        // w = 1, float
layout(std430, binding = 1) readonly buffer Records { uint records[]; };          // kRecordWords each
layout(std430, binding = 2) readonly buffer Triangles { uint triangle_index[]; }; // 3 per triangle

layout(location = 0) uniform vec4 light;          // (l, w), rounded once to float
layout(location = 1) uniform uint record_count;   // items before the triangles

flat in uint item_id[];
// Captured (GL_INTERLEAVED, one vec4 per vertex): what StencilShadowRenderer draws.
layout(xfb_buffer = 0, xfb_offset = 0) out vec4 volume_vertex;

#include "light_side_formula.glsl"

// Sign of D on an ascending index triple (a < b < c): the one evaluation a triangle gets.
int sorted_side(uint a, uint b, uint c) {
  const float value = light_side_value(vertices[a].xyz, vertices[b].xyz, vertices[c].xyz);
  return value > 0.0 ? 1 : (value < 0.0 ? -1 : 0);
}

// x_inf = (x - l, 0) for a point light, (-l, 0) for a directional one (DESIGN.md §3).
vec4 far_vertex(vec4 x) {
  if (light.w == 0.0) return vec4(-light.xyz, 0.0);
  precise vec3 d = x.xyz - light.xyz;
  return vec4(d, 0.0);
}

void put(vec4 x) {
  volume_vertex = x;
  EmitVertex();
}

void edge_record(uint r) {
  const uint base = r * kRecordWords;
  const uint u = records[base];
  const uint v = records[base + 1u];
  const uint count = records[base + 2u];
  int m = 0;
  for (uint i = 0u; i < count; ++i) {
    const uint o = records[base + 4u + i];
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
  if (m == 0) return;
  const vec4 p = vertices[m > 0 ? u : v];
  const vec4 q = vertices[m > 0 ? v : u];
  const vec4 p_inf = far_vertex(p);
  const vec4 q_inf = far_vertex(q);
  const int copies = abs(m);
  for (int k = 0; k < copies; ++k) {
    if (light.w == 0.0) {
      // A directional light's quad is the triangle (p, q, inf).
      put(p);
      put(q);
      put(q_inf);
    } else {
      // Two 3-vertex strips, (p, q, q_inf) and (p, q_inf, p_inf): the cs and cpu triangles
      // vertex for vertex. One 4-vertex strip would capture (q, q_inf, p) for the first,
      // which llvmpipe's near/depth clipping of w = 0 vertices rasterises differently on
      // boundary pixels (hundreds on default.json), so the counts would no longer match.
      put(p);
      put(q);
      put(q_inf);
      EndPrimitive();
      put(p);
      put(q_inf);
      put(p_inf);
    }
    EndPrimitive();
  }
}

void triangle_caps(uint t) {
  const uint a = triangle_index[3u * t];
  const uint b = triangle_index[3u * t + 1u];
  const uint c = triangle_index[3u * t + 2u];
  if (a == b || b == c || c == a) return;  // no edges, casts nothing
  const uint lo = min(a, min(b, c));
  const uint hi = max(a, max(b, c));
  const uint mid = a + b + c - lo - hi;  // exact in uint arithmetic (wraps cancel)
  const int inversions = int(a > b) + int(a > c) + int(b > c);
  const int sorted = sorted_side(lo, mid, hi);
  const int s = (inversions % 2 == 0) ? sorted : -sorted;  // D(a, b, c) from D(lo, mid, hi)
  if (s == 0) return;
  // Front cap t' (normal towards the light), back cap t' at infinity, reversed.
  const vec4 f0 = vertices[a];
  const vec4 f1 = vertices[s > 0 ? b : c];
  const vec4 f2 = vertices[s > 0 ? c : b];
  put(f0);
  put(f1);
  put(f2);
  EndPrimitive();
  if (light.w != 0.0) {
    put(far_vertex(f0));
    put(far_vertex(f2));
    put(far_vertex(f1));
    EndPrimitive();
  }
}

void main() {
  const uint id = item_id[0];
  if (id < record_count) {
    edge_record(id);
  } else {
    triangle_caps(id - record_count);
  }
}
