#version 450 core
// The `pertri` shadow volume (gpu/per_triangle_volume.h): Milet 2014 §2.1's per-triangle
// volumes, no silhouette. One invocation per triangle t; where s(t) != 0 it writes the whole
// V(t) of docs/definitions.md#counts: front cap t' (t, reversed when s = -1), for each directed edge (u, v)
// of t' the side quad (v, u, u_inf, v_inf) as two triangles, and the back cap (t' at
// infinity, reversed). Side quads are written in one vertex order per edge, some into the
// reversed part of the output (triangle_pass). s(t) is taken ONCE, by the reference-edge evaluation of
// compute_volume.comp.glsl's triangle pass (reference_edge.glsl's triangle_side: sorted
// canonical indices, `precise` light-side value, parity), and used for caps and sides alike: each V(t) is closed on its own, whatever
// the rounding (a per-edge re-evaluation could flip one side and open it).
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };       // w = 1, float
layout(std430, binding = 1) readonly buffer Triangles { uint triangle_index[]; };  // 3 per triangle
layout(std430, binding = 2) writeonly buffer Signs { int signs[]; };             // s(t) per triangle
// Two DrawArraysIndirectCommands (IndirectVolumeDraw::reversed, gpu/stencil_shadow_renderer.h),
// then the vertices each part asked for. The forward part fills the volume from its start, the
// reversed part from its end: [capacity - reversed_requested, capacity).
layout(std430, binding = 3) coherent buffer Command {
  uint vertex_count;  // the forward part: drawn as it is
  uint instance_count;
  uint first_vertex;
  uint base_instance;
  uint reversed_count;  // the reversed part: each triangle counted as its own reversal
  uint reversed_instance_count;
  uint reversed_first_vertex;
  uint reversed_base_instance;
  uint requested;
  uint reversed_requested;
};
// The output volume through four windows of one buffer: one storage block may address only
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE (llvmpipe 128 MiB = 8M vertices) but 1M triangles need
// 24M vertices. Vertex i lives in window i / window_vertices.
layout(std430, binding = 4) writeonly buffer Volume0 { vec4 volume0[]; };
layout(std430, binding = 5) writeonly buffer Volume1 { vec4 volume1[]; };
layout(std430, binding = 6) writeonly buffer Volume2 { vec4 volume2[]; };
layout(std430, binding = 7) writeonly buffer Volume3 { vec4 volume3[]; };

layout(location = 0) uniform vec4 light;             // (l, w), rounded once to float
layout(location = 1) uniform uint pass_kind;         // 0 triangles, 1 finish
layout(location = 2) uniform uint item_count;        // triangles
layout(location = 3) uniform uint capacity;          // vertices the windows hold together
layout(location = 4) uniform uint window_vertices;   // vertices per window

const uint kNoRoom = 0xFFFFFFFFu;

#include "reference_edge.glsl"

void store(uint at, vec4 x) {
  const uint window = at / window_vertices;
  const uint i = at - window * window_vertices;
  if (window == 0u) {
    volume0[i] = x;
  } else if (window == 1u) {
    volume1[i] = x;
  } else if (window == 2u) {
    volume2[i] = x;
  } else {
    volume3[i] = x;
  }
}

// Where volume_triangle writes next (set after each reservation).
uint volume_cursor = 0u;

void volume_triangle(vec4 a, vec4 b, vec4 c) {
  store(volume_cursor, a);
  store(volume_cursor + 1u, b);
  store(volume_cursor + 2u, c);
  volume_cursor += 3u;
}

#include "far_split.glsl"

// The side quad of the edge {lo, hi} in the one vertex order both triangles on that edge emit
// it in (pertri's pairs, below): as the directed edge (hi, lo) of a t' has it, the quad
// (lo, hi, hi_inf, lo_inf) fanned from lo: (p_lo, p_hi, f_hi), then (p_lo, f_hi, f_lo), or,
// where that far edge is wide, the fan over the far vertices between (far_split.glsl); a
// directional light's (p_lo, p_hi, inf).
uint side_vertex_count(vec4 p_hi, vec4 p_lo) {
  if (light.w == 0.0) return 3u;
  vec4 between[7];
  return 6u + (far_edge_is_wide(p_hi, p_lo) ? 3u * uint(far_between(p_hi, p_lo, between)) : 0u);
}

void canonical_side(vec4 p_hi, vec4 p_lo) {
  const vec4 f_hi = far_vertex(p_hi);
  volume_triangle(p_lo, p_hi, f_hi);
  if (light.w == 0.0) return;
  vec4 between[7];
  const int m = far_edge_is_wide(p_hi, p_lo) ? far_between(p_hi, p_lo, between) : 0;
  vec4 previous = f_hi;
  for (int i = 0; i < m; ++i) {
    volume_triangle(p_lo, previous, between[i]);
    previous = between[i];
  }
  volume_triangle(p_lo, previous, far_vertex(p_lo));
}

void triangle_pass(uint t) {
  const uint a = triangle_index[3u * t];
  const uint b = triangle_index[3u * t + 1u];
  const uint c = triangle_index[3u * t + 2u];
  const int s = triangle_side(a, b, c);  // 0 for a repeated index: no edges, casts nothing
  signs[t] = s;
  if (s == 0) return;
  // t' = (p0, p1, p2): its normal faces the light.
  uint id[3];
  id[0] = a;
  id[1] = s > 0 ? b : c;
  id[2] = s > 0 ? c : b;
  vec4 p[3];
  for (int k = 0; k < 3; ++k) p[k] = vertices[id[k]];
  // Point light: front cap, 3 quads (2 triangles each, more where a far edge is wide:
  // far_split.glsl), back cap (one triangle, or a fan) = 24 vertices unless split.
  // Directional: all far vertices are (-l, 0), so a quad is the one triangle (v, u, inf) and
  // the back cap collapses to a point: front cap + 3 triangles = 12 vertices.
  //
  // Each edge (u, v) of t' has the side quad (v, u, u_inf, v_inf). Across an interior edge the
  // neighbour's t' runs the edge the other way and emits the same quad reversed: the pair must
  // cancel at every pixel. Both are written in one vertex order, canonical_side's, and the copy
  // whose edge runs from the lower index to the higher goes to the reversed part, drawn with
  // the facings' stencil operations swapped (gpu/stencil_shadow_renderer.h): one primitive
  // twice, the same fragments and depths, +1 and -1. Written in opposite orders, the two
  // rasterised depths round apart by a unit here and there (llvmpipe interpolates from the
  // first vertex); where the visible surface lay between them the pair counted 1 (the
  // tolerance hard_case_render_test had for pertri), and on a side seen nearly edge-on, whose
  // exact face a grazing angle puts beyond the diff's depth band while its float copies lie a
  // few depth steps from the surface, that was a hard error of pertri alone with every volume
  // closed (issue 27: tests/regressions/gl/pertri_edge_on_pair_*, docs/gpu.md "Per-triangle
  // volumes"). The quad is
  // fanned from the edge's lower end: split by orientation instead (first to third vertex, as
  // cs and cpu split a chain quad), the two halves of a rounded, not quite planar quad
  // disagree near the edge with the depth of the lit surface and leave shadow acne along every
  // edge (measured on sphere_grid_1m.json: 8189 more shadowed pixels than cpu).
  uint forward = 3u + 3u * back_cap_triangle_count(p[0], p[1], p[2]);
  uint reversed = 0u;
  for (int k = 0; k < 3; ++k) {
    const int u = k, v = (k + 1) % 3;
    const bool forward_edge = id[u] > id[v];  // (u, v) = (hi, lo): canonical_side's own order
    const uint n = forward_edge ? side_vertex_count(p[u], p[v]) : side_vertex_count(p[v], p[u]);
    if (forward_edge)
      forward += n;
    else
      reversed += n;
  }
  const uint base = atomicAdd(requested, forward);
  const uint reversed_base = reversed > 0u ? atomicAdd(reversed_requested, reversed) : 0u;
  // Overflow, reported through the counters: the finish pass then draws nothing.
  if (forward > capacity || base > capacity - forward || reversed > capacity || reversed_base > capacity - reversed)
    return;
  volume_cursor = base;
  volume_triangle(p[0], p[1], p[2]);
  for (int k = 0; k < 3; ++k)
    if (id[k] > id[(k + 1) % 3]) canonical_side(p[k], p[(k + 1) % 3]);
  back_cap_triangles(p[0], p[1], p[2]);
  volume_cursor = capacity - reversed_base - reversed;
  for (int k = 0; k < 3; ++k)
    if (id[k] < id[(k + 1) % 3]) canonical_side(p[(k + 1) % 3], p[k]);
}

void main() {
  // Rows of work groups past GL_MAX_COMPUTE_WORK_GROUP_COUNT's guaranteed 65535 in x.
  const uint id = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
  if (pass_kind == 1u) {
    if (id == 0u) {
      // The two parts met (an overflow): draw nothing rather than what either overwrote.
      const bool fits = requested <= capacity && reversed_requested <= capacity - requested;
      vertex_count = fits ? requested : 0u;
      reversed_count = fits ? reversed_requested : 0u;
      reversed_first_vertex = fits ? capacity - reversed_requested : 0u;
    }
    return;
  }
  if (id >= item_count) return;
  triangle_pass(id);
}
