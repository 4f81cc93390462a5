#version 450 core
// The `ts` volume (gpu/tessellation_volume.h): each isoline of the tessellator becomes, for
// transform-feedback capture, one copy of an edge's side quad (u, v, v_inf, u_inf) oriented by
// sign(m), as gs's two 3-vertex strips (p, q, q_inf), (p, q_inf, p_inf), or a triangle's caps.
// The caps are geometry_shader_volume.geom.glsl's triangle_caps with the same sorted sign
// evaluation, copied operation for operation: gs's own program cannot draw into the same
// capture (a transform-feedback session keeps its program, and a second session would write
// from the buffer's start again), so it is reused as source rather than as a pass.
layout(lines) in;
layout(triangle_strip, max_vertices = 6) out;

const uint kTriangleKind = 1u;

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };  // w = 1, float

layout(location = 0) uniform vec4 light;  // (l, w), rounded once to float

flat in uvec4 line_item[];
flat in int line_multiplicity[];
// Captured (GL_INTERLEAVED, one vec4 per vertex): what StencilShadowRenderer draws.
layout(xfb_buffer = 0, xfb_offset = 0) out vec4 volume_vertex;

#include "light_side_formula.glsl"

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

// One of the |m| copies of the edge's side quad.
void side_quad(uint u, uint v, int m) {
  const vec4 p = vertices[m > 0 ? u : v];
  const vec4 q = vertices[m > 0 ? v : u];
  if (light.w == 0.0) {
    put(p);  // a directional light's quad is the triangle (p, q, inf)
    put(q);
    put(far_vertex(q));
  } else {
    put(p);
    put(q);
    put(far_vertex(q));
    EndPrimitive();
    put(p);
    put(far_vertex(q));
    put(far_vertex(p));
  }
  EndPrimitive();
}

void triangle_caps(uint a, uint b, uint c) {
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
  const uvec4 item = line_item[0];
  if (item.w == kTriangleKind) {
    triangle_caps(item.x, item.y, item.z);
  } else if (line_multiplicity[0] != 0) {
    side_quad(item.x, item.y, line_multiplicity[0]);
  }
}
