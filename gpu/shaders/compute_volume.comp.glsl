#version 450 core
// The `cs` shadow volume (gpu/compute_volume.h): multiplicities by Milet 2014's reference
// edge (§2.2, Algorithms 2-4) and the chain of docs/definitions.md#counts, built in three dispatches of
// this one shader (pass_kind):
//   0 edges     : one invocation per edge (u, v), u < v: for every opposite vertex o, sort
//                 {u, v, o} by canonical INDEX (index order is the vertex order,
//                 scene/canonical_soup.h), evaluate the light-side value on the sorted
//                 positions, undo the permutation by parity; m = - sum. Writes m and |m|
//                 copies of the side quad (u, v, v_inf, u_inf) oriented by sign(m).
//   1 triangles : one invocation per triangle: the same sorted evaluation gives s(t); front
//                 cap t' and back cap (t' at infinity, reversed) where s != 0. Caps and sides
//                 of a triangle come from one value, so the chain is closed by construction.
//   2 finish    : one invocation: the draw count is what was reserved, clamped to the
//                 buffer (an overflow is reported through `requested`, never drawn past).
// The light-side value mirrors core/light_side_formula.h operation for operation; every
// intermediate is `precise` so no FMA or reassociation changes its rounding (the CPU side
// builds with -ffp-contract=off), which is what makes the signs equal the CPU's bit for bit.
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };       // w = 1, float
layout(std430, binding = 1) readonly buffer Edges { uvec2 edges[]; };            // (u, v), u < v
layout(std430, binding = 2) readonly buffer FirstOpposite { uint first_opposite[]; };  // CSR rows
layout(std430, binding = 3) readonly buffer OppositeVertex { uint opposite_vertex[]; };
layout(std430, binding = 4) readonly buffer Triangles { uint triangle_index[]; };  // 3 per triangle
// Edge multiplicities m at [0, edge_count), triangle cap signs s(t) after them.
layout(std430, binding = 5) writeonly buffer Signs { int signs[]; };
// DrawArraysIndirectCommand followed by the number of vertices the passes asked for.
layout(std430, binding = 6) coherent buffer Command {
  uint vertex_count;
  uint instance_count;
  uint first_vertex;
  uint base_instance;
  uint requested;
};
layout(std430, binding = 7) writeonly buffer Volume { vec4 volume[]; };  // triangles, 3 vec4 each

layout(location = 0) uniform vec4 light;       // (l, w), rounded once to float
layout(location = 1) uniform uint pass_kind;   // 0 edges, 1 triangles, 2 finish
layout(location = 2) uniform uint item_count;  // edges or triangles of this pass
layout(location = 3) uniform uint capacity;    // vertices the Volume buffer holds
layout(location = 4) uniform uint edge_count;  // where the triangle signs start in Signs

#include "reference_edge.glsl"

#include "volume_reservation.glsl"
#include "far_split.glsl"

void edge_pass(uint e) {
  const uint u = edges[e].x;
  const uint v = edges[e].y;
  int m = 0;
  for (uint i = first_opposite[e]; i < first_opposite[e + 1u]; ++i) {
    m -= opposite_side(u, v, opposite_vertex[i]);
  }
  signs[e] = m;
  if (m == 0) return;
  // m copies of (u, v, v_inf, u_inf), i.e. |m| copies of (p, q, q_inf, p_inf) with p, q
  // swapped when m < 0 (far_split.glsl: a directional light's quad is the triangle (p, q, inf),
  // a wide far edge is split).
  const vec4 p = vertices[m > 0 ? u : v];
  const vec4 q = vertices[m > 0 ? v : u];
  const uint copies = uint(abs(m));
  const uint per_copy = 3u * side_quad_triangle_count(p, q);
  const uint base = reserve(copies * per_copy);
  if (base == kNoRoom) return;
  volume_cursor = base;
  for (uint k = 0u; k < copies; ++k) side_quad_triangles(p, q);
}

void triangle_pass(uint t) {
  const uint a = triangle_index[3u * t];
  const uint b = triangle_index[3u * t + 1u];
  const uint c = triangle_index[3u * t + 2u];
  const int s = triangle_side(a, b, c);  // 0 for a repeated index: no edges, casts nothing
  signs[edge_count + t] = s;
  if (s == 0) return;
  // Front cap t' (normal towards the light), back cap t' at infinity, reversed.
  const vec4 f0 = vertices[a];
  const vec4 f1 = vertices[s > 0 ? b : c];
  const vec4 f2 = vertices[s > 0 ? c : b];
  const uint base = reserve(3u + 3u * back_cap_triangle_count(f0, f1, f2));
  if (base == kNoRoom) return;
  volume_cursor = base;
  volume_triangle(f0, f1, f2);
  back_cap_triangles(f0, f1, f2);
}

void main() {
  // Rows of work groups past GL_MAX_COMPUTE_WORK_GROUP_COUNT's guaranteed 65535 in x.
  const uint id = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
  if (pass_kind == 2u) {
    if (id == 0u) vertex_count = min(requested, capacity);
    return;
  }
  if (id >= item_count) return;
  if (pass_kind == 0u) {
    edge_pass(id);
  } else {
    triangle_pass(id);
  }
}
