#version 450 core
// The C1-discontinuity operator (Saito & Takahashi, Decaudin; Nienhaus & Doellner §4.1.2,
// second variant; gpu/edge_map.h) on depth, and the same weights over normals:
//   profile = (|A-X| + 2|B-X| + |C-X| + 2|D-X| + 2|E-X| + |F-X| + 2|G-X| + |H-X|) / 12
//   inner   = the same weights over (1 - n_i . n_X) / 2, / 12 (0 where X is uncovered)
// The paper divides by 8; 12, the weights' sum, keeps the value in [0, 1] so that the three
// passes below add up by blending without a clamp.
// `rows`: which rows of taps this pass adds: bit 0 the row A B C, bit 1 D E, bit 2 F G H; 7 in
// the one-pass form, 1, 2 and 4 in the paper's three passes (summed by GL_ONE, GL_ONE blending;
// only the first pass writes the coverage and alpha channels, the others add 0 there).
layout(location = 0) uniform int rows;
layout(location = 0) out vec4 edge;

#include "edge_g_buffer.glsl"

void main() {
  vec4 x = g_at(ivec2(0));
  bool x_covered = g_covered(x);
  float profile = 0.0, inner = 0.0;
  for (int dy = 1; dy >= -1; --dy) {
    int row = 1 - dy;  // 0: A B C, 1: D E, 2: F G H
    if ((rows & (1 << row)) == 0) continue;
    for (int dx = -1; dx <= 1; ++dx) {
      if (dx == 0 && dy == 0) continue;
      float weight = (dx == 0 || dy == 0) ? 2.0 : 1.0;
      vec4 t = g_at(ivec2(dx, dy));
      profile += weight * depth_step(t, x);
      if (x_covered) inner += weight * 0.5 * (1.0 - normal_cosine(t, x));
    }
  }
  bool first = (rows & 1) != 0;
  vec4 texel = edge_texel(profile / 12.0, inner / 12.0, x_covered);
  edge = first ? texel : vec4(texel.rg, 0.0, 0.0);
}
