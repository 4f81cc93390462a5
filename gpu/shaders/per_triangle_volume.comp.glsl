#version 450 core
// The `pertri` shadow volume (gpu/per_triangle_volume.h): Milet 2014 §2.1's per-triangle
// volumes, no silhouette. One invocation per triangle t; where s(t) != 0 it writes the whole
// V(t) of docs/definitions.md#counts: front cap t' (t, reversed when s = -1), for each directed edge (u, v)
// of t' the side quad (v, u, u_inf, v_inf) as two triangles, and the back cap (t' at
// infinity, reversed). s(t) is taken ONCE, by the reference-edge evaluation of
// compute_volume.comp.glsl's triangle pass (reference_edge.glsl's triangle_side: sorted
// canonical indices, `precise` light-side value, parity), and used for caps and sides alike: each V(t) is closed on its own, whatever
// the rounding (a per-edge re-evaluation could flip one side and open it).
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };       // w = 1, float
layout(std430, binding = 1) readonly buffer Triangles { uint triangle_index[]; };  // 3 per triangle
layout(std430, binding = 2) writeonly buffer Signs { int signs[]; };             // s(t) per triangle
// DrawArraysIndirectCommand followed by the number of vertices the triangles asked for.
layout(std430, binding = 3) coherent buffer Command {
  uint vertex_count;
  uint instance_count;
  uint first_vertex;
  uint base_instance;
  uint requested;
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
  vec4 f[3];
  for (int k = 0; k < 3; ++k) f[k] = far_vertex(p[k]);
  // Point light: front cap, 3 quads (2 triangles each, more where a far edge is wide:
  // far_split.glsl), back cap (one triangle, or a fan) = 24 vertices unless split.
  // Directional: all far vertices are (-l, 0), so a quad is the one triangle (v, u, inf) and
  // the back cap collapses to a point: front cap + 3 triangles = 12 vertices.
  const bool point = light.w != 0.0;
  vec4 between[7];
  int splits[3];
  uint n = 3u + 3u * back_cap_triangle_count(p[0], p[1], p[2]);
  for (int k = 0; k < 3; ++k) {
    const vec4 pu = p[k];
    const vec4 pv = p[(k + 1) % 3];
    splits[k] = point && far_edge_is_wide(pu, pv) ? far_between(pu, pv, between) : 0;
    n += point ? 6u + 3u * uint(splits[k]) : 3u;
  }
  const uint base = atomicAdd(requested, n);
  if (n > capacity || base > capacity - n) return;  // overflow: reported through `requested`
  volume_cursor = base;
  volume_triangle(p[0], p[1], p[2]);
  for (int k = 0; k < 3; ++k) {
    const int u = k;
    const int v = (k + 1) % 3;
    // Quad (v, u, u_inf, v_inf) fanned from the edge's lower canonical index, whatever the
    // orientation: the neighbour across an interior edge then emits the very same triangles
    // reversed, so the pair cancels pixel for pixel. Split by orientation instead (first to
    // third vertex, as cs and cpu split a chain quad), the two halves of a rounded, not quite
    // planar quad disagree near the edge with the depth of the lit surface and leave shadow
    // acne along every edge (measured on sphere_grid_1m.json: 8189 more shadowed pixels than
    // cpu). A wide far edge (far_split.glsl) puts its far vertices between f_u and f_v.
    if (!point) {
      volume_triangle(p[v], p[u], f[u]);
      continue;
    }
    const int m = splits[k] > 0 ? far_between(p[u], p[v], between) : 0;
    const bool from_v = id[v] < id[u];
    const vec4 apex = from_v ? p[v] : p[u];
    if (from_v) volume_triangle(p[v], p[u], f[u]);
    vec4 previous = f[u];
    for (int i = 0; i < m; ++i) {
      volume_triangle(apex, previous, between[i]);
      previous = between[i];
    }
    volume_triangle(apex, previous, f[v]);
    if (!from_v) volume_triangle(p[u], f[v], p[v]);
  }
  back_cap_triangles(p[0], p[1], p[2]);
}

void main() {
  // Rows of work groups past GL_MAX_COMPUTE_WORK_GROUP_COUNT's guaranteed 65535 in x.
  const uint id = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
  if (pass_kind == 1u) {
    if (id == 0u) vertex_count = min(requested, capacity);
    return;
  }
  if (id >= item_count) return;
  triangle_pass(id);
}
