// Included (cmake/EmbedShaders.cmake resolves the include directive naming this file at build
// time) by every shader that takes a sign or builds a far vertex: cs, gs, ts (control and
// geometry) and pertri. Milet 2014's reference edge (§2.2, Algorithms 3-4): a triple of
// vertices is evaluated once, on its canonical indices sorted ascending (index order is the
// vertex order, scene/canonical_soup.h), with light_side_sign.glsl, and any other order
// of the same triple takes that sign times its permutation's parity. One copy, so the signs
// of the GPU methods equal each other and exact/'s: the exact signs of the float-rounded scene
// (glsign) by default, float32 refedge bit for bit under `--sign float`.
// The including shader declares, before the include, `uniform vec4 light` ((l, w), rounded
// once to float) and a storage buffer `vec4 vertices[]` (canonical vertices, float, w = 1).
#include "light_side_sign.glsl"

// Sign of D on an ascending index triple (a < b < c): the one evaluation a triangle gets.
int sorted_side(uint a, uint b, uint c) {
  return light_side_sign(vertices[a].xyz, vertices[b].xyz, vertices[c].xyz);
}

// sign D(u, v, o) for an opposite vertex o of the edge u < v (o != u, v): Algorithm 3's three
// places o can take relative to u and v. One call of sorted_side, so that the exact stage is
// compiled once here, not three times.
int opposite_side(uint u, uint v, uint o) {
  // (u, v, o) is a rotation of (o, u, v) (even) or of (u, v, o) itself; (u, o, v) is one
  // transposition away (odd).
  const bool middle = o > u && o < v;
  const uint lo = o < u ? o : u;
  const uint mid = o < u ? u : (middle ? o : v);
  const uint hi = o < v ? v : o;
  const int sorted = sorted_side(lo, mid, hi);
  return middle ? -sorted : sorted;
}

// s(t) = sign D(a, b, c) of the triangle (a, b, c) from the sorted evaluation, undone by the
// parity of the sort; 0 for a triangle with a repeated index (no edges: it casts nothing).
int triangle_side(uint a, uint b, uint c) {
  if (a == b || b == c || c == a) return 0;
  const uint lo = min(a, min(b, c));
  const uint hi = max(a, max(b, c));
  const uint mid = a + b + c - lo - hi;  // exact in uint arithmetic (wraps cancel)
  const int inversions = int(a > b) + int(a > c) + int(b > c);
  const int sorted = sorted_side(lo, mid, hi);
  return (inversions % 2 == 0) ? sorted : -sorted;  // D(a, b, c) from D(lo, mid, hi)
}

// x_inf = (x - l, 0) for a point light, (-l, 0) for a directional one (docs/definitions.md#counts); x - l
// is `precise`, one float rounding per coordinate, as every method forms it.
vec4 far_vertex(vec4 x) {
  if (light.w == 0.0) return vec4(-light.xyz, 0.0);
  precise vec3 d = x.xyz - light.xyz;
  return vec4(d, 0.0);
}
