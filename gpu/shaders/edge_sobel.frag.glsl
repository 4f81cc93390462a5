#version 450 core
// The Sobel operator, the usual baseline (gpu/edge_map.h): the 3 x 3 gradient of depth
// (differences to X, clamped to [-1, 1]) and of the normal field (each component, differences
// to n_X; an uncovered tap adds nothing):
//   profile = min(1, |G_z| / 4)   inner = min(1, |G_n| / 8)   (inner 0 where X is uncovered)
layout(location = 0) out vec4 edge;

#include "edge_g_buffer.glsl"

void main() {
  vec4 x = g_at(ivec2(0));
  bool x_covered = g_covered(x);
  vec2 g_z = vec2(0.0);
  vec3 g_nx = vec3(0.0), g_ny = vec3(0.0);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      // Sobel's weights: 1 on the diagonals, 2 on the axes, the sign of the offset.
      vec2 weight = vec2(float(dx) * (dy == 0 ? 2.0 : 1.0), float(dy) * (dx == 0 ? 2.0 : 1.0));
      vec4 t = g_at(ivec2(dx, dy));
      g_z += weight * clamp(t.w - x.w, -1.0, 1.0);
      if (x_covered && g_covered(t)) {
        vec3 dn = t.xyz - x.xyz;
        g_nx += weight.x * dn;
        g_ny += weight.y * dn;
      }
    }
  }
  float inner = x_covered ? sqrt(dot(g_nx, g_nx) + dot(g_ny, g_ny)) / 8.0 : 0.0;
  edge = edge_texel(length(g_z) / 4.0, inner, x_covered);
}
