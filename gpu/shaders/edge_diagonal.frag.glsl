#version 450 core
// The diagonal filter (Nienhaus & Doellner §4.1.2, first variant; gpu/edge_map.h): the two
// diagonal pairs (A, H) and (C, F) of the 3 x 3 neighbourhood.
//   I_Z = (1 - |z_A - z_H| / 2)^2 (1 - |z_C - z_F| / 2)^2   profile = 1 - I_Z
//   I_N = (n_A . n_H + n_C . n_F) / 2                      inner   = (1 - I_N) / 2
layout(location = 0) out vec4 edge;

#include "edge_g_buffer.glsl"

void main() {
  vec4 a = g_at(ivec2(-1, 1)), c = g_at(ivec2(1, 1)), f = g_at(ivec2(-1, -1)), h = g_at(ivec2(1, -1));
  float ah = 1.0 - 0.5 * depth_step(a, h);
  float cf = 1.0 - 0.5 * depth_step(c, f);
  float i_z = ah * ah * cf * cf;
  float i_n = 0.5 * (normal_cosine(a, h) + normal_cosine(c, f));
  edge = edge_texel(1.0 - i_z, 0.5 * (1.0 - i_n), g_covered(g_at(ivec2(0))));
}
