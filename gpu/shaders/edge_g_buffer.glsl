// Shared by the edge filters (edge_diagonal, edge_c1, edge_sobel .frag.glsl; gpu/edge_map.h):
// reading the G-buffer around the fragment and writing an edge-map texel.
// Taps are named as in the paper's Fig. 2, row A B C above X, F G H below (GL's y points up):
//   A (-1, 1)  B (0, 1)  C (1, 1)
//   D (-1, 0)  X         E (1, 0)
//   F (-1,-1)  G (0,-1)  H (1,-1)
layout(binding = 0) uniform sampler2D g_buffer;

// The G-buffer texel at the fragment plus `offset`; beyond the image the border texel repeats
// (no edge at the frame).
vec4 g_at(ivec2 offset) {
  ivec2 last = textureSize(g_buffer, 0) - ivec2(1);
  return texelFetch(g_buffer, clamp(ivec2(gl_FragCoord.xy) + offset, ivec2(0), last), 0);
}

// Covered texels hold a unit normal, uncovered ones the zero vector (gpu/g_buffer.h).
bool g_covered(vec4 g) { return dot(g.xyz, g.xyz) > 0.25; }

// |z_a - z_b| clamped to 1: covered depths lie in [0, 1], the background (kBackgroundDepth)
// lies a full step behind every surface.
float depth_step(vec4 a, vec4 b) { return min(abs(a.w - b.w), 1.0); }

// n_a . n_b clamped to [-1, 1]; 1 (no normal discontinuity) when either is uncovered: that
// boundary is a profile edge, reported by depth.
float normal_cosine(vec4 a, vec4 b) {
  return g_covered(a) && g_covered(b) ? clamp(dot(a.xyz, b.xyz), -1.0, 1.0) : 1.0;
}

// The edge-map texel (gpu/edge_map.h): profile, inner, coverage, 1.
vec4 edge_texel(float profile, float inner, bool covered) {
  return vec4(clamp(profile, 0.0, 1.0), clamp(inner, 0.0, 1.0), covered ? 1.0 : 0.0, 1.0);
}
