#version 450 core
// The `ts` volume (gpu/tessellation_volume.h): each isoline of the tessellator becomes, for
// transform-feedback capture, one copy of an edge's side quad (u, v, v_inf, u_inf) oriented by
// sign(m), or a triangle's caps, emitted as gs emits them (volume_capture.glsl's side_quad and
// triangle_caps, with reference_edge.glsl's signs).
layout(lines) in;
// One quad copy: at most 9 triangles (far_split.glsl); caps: the front cap and a back cap fanned
// into at most 24 triangles. 3-vertex strips each.
layout(triangle_strip, max_vertices = 75) out;

const uint kTriangleKind = 1u;

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };  // w = 1, float

layout(location = 0) uniform vec4 light;  // (l, w), rounded once to float

flat in uvec4 line_item[];
flat in int line_multiplicity[];

#include "reference_edge.glsl"
#include "volume_capture.glsl"

void main() {
  const uvec4 item = line_item[0];
  if (item.w == kTriangleKind) {
    triangle_caps(item.x, item.y, item.z);
  } else if (line_multiplicity[0] != 0) {
    const int m = line_multiplicity[0];  // one isoline per copy: this is one of the |m|
    side_quad(vertices[m > 0 ? item.x : item.y], vertices[m > 0 ? item.y : item.x]);
  }
}
