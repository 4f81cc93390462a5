// Included (cmake/EmbedShaders.cmake) by the two geometry shaders whose output is captured by
// transform feedback, gs's (geometry_shader_volume.geom.glsl) and ts's
// (tessellation_volume.geom.glsl), after reference_edge.glsl: the captured output and the
// triangles both emit into it, so that gs and ts draw the same triangles as cs and cpu, vertex
// for vertex. (ts cannot run gs's program for its caps: a transform-feedback session keeps its
// program, and a second session would write from the buffer's start again; so the source is
// shared instead.)

// Captured (GL_INTERLEAVED, one vec4 per vertex): what StencilShadowRenderer draws.
layout(xfb_buffer = 0, xfb_offset = 0) out vec4 volume_vertex;

void put(vec4 x) {
  volume_vertex = x;
  EmitVertex();
}

// A triangle of the volume, as one 3-vertex strip: exactly the cs and cpu triangles vertex for
// vertex. (One 4-vertex strip per quad would capture (q, q_inf, p) for the first half, which
// llvmpipe's near/depth clipping of w = 0 vertices rasterises differently on boundary pixels,
// hundreds on default.json, so the counts would no longer match.)
void volume_triangle(vec4 a, vec4 b, vec4 c) {
  put(a);
  put(b);
  put(c);
  EndPrimitive();
}

#include "far_split.glsl"

// One copy of the side quad (p, q, q_inf, p_inf), where (p, q) is the edge (u, v) oriented by
// sign(m) (far_split.glsl: split where its far edge is wide).
void side_quad(vec4 p, vec4 q) { side_quad_triangles(p, q); }

// Where s(t) != 0 (reference_edge.glsl's triangle_side): the front cap t' (normal towards the
// light) and, for a point light, the back cap (t' at infinity, reversed; far_split.glsl).
void triangle_caps(uint a, uint b, uint c) {
  const int s = triangle_side(a, b, c);
  if (s == 0) return;  // in the light's plane, or a repeated index: casts nothing
  const vec4 f0 = vertices[a];
  const vec4 f1 = vertices[s > 0 ? b : c];
  const vec4 f2 = vertices[s > 0 ? c : b];
  volume_triangle(f0, f1, f2);
  back_cap_triangles(f0, f1, f2);
}
