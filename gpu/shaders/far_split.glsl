// Included (cmake/EmbedShaders.cmake) after reference_edge.glsl by every shader that builds a
// point light's far geometry: cs, pertri, and gs and ts through volume_capture.glsl. The GPU
// twin of exact/chain_mesh.cpp's wide far edges (docs/gpu.md "Wide far edges"): a far edge
// far(p) - far(q) whose directions p - l and q - l make more than a right angle (the light
// between the edge's ends, seen along it) is split at the bisecting directions, three levels
// deep at most, so that no far triangle spans an angle the rasteriser's clip-space
// interpolation cannot follow (between nearly antipodal far vertices it passes near the zero
// vector and shades a third of the frame). The split reads only the two directions and every
// operation on them is commutative in IEEE arithmetic (`precise`), so a side quad and the
// back caps on both sides of one far edge split it into the same vertices: the chain stays
// closed. A back cap with a split edge is fanned from the far vertex of its plane's normal
// that points away from the light, which no direction to the plane makes a wide angle with.

// The far direction of a split: the unit bisector of a and b, where a and b make more than a
// right angle; false when they do not, or when they are antipodal to the last bit (the light on
// the edge itself, whose triangles cast nothing). In double: a wide edge's directions are
// nearly antipodal exactly when the light is near the edge's line (one ulp off it in the
// campaign's off_edge_line placement), where the sum of the two unit vectors cancels; in
// float its direction would be rounding noise, out of the side's plane, and the fan over it
// would shade a wedge wrong (a 1,847-pixel strip on tests/regressions/gl/
// light_between_edge_ends.json at 256x192). Double keeps it in the plane to about 2^-53 over
// the cancellation, as exact/chain_mesh.cpp's bisector is.
bool far_bisector(dvec3 a, dvec3 b, out dvec3 m) {
  m = dvec3(0.0);
  precise double cosine = dot(a, b);
  if (!(cosine < 0.0)) return false;
  precise dvec3 sum = normalize(a) + normalize(b);
  if (sum == dvec3(0.0)) return false;
  m = normalize(sum);
  return true;
}

vec4 far_direction(dvec3 m) { return vec4(vec3(m), 0.0); }

// The far vertices strictly between far(p) and far(q) of a point light (w = 0), in order from
// p to q; returns how many (0 to 7). The directions p - l and q - l are formed in double from
// the float inputs (exact unless their exponents are more than 29 apart).
int far_between(vec4 p, vec4 q, out vec4 between[7]) {
  const dvec3 l = dvec3(light.xyz);
  precise dvec3 a = dvec3(p.xyz) - l;
  precise dvec3 b = dvec3(q.xyz) - l;
  for (int i = 0; i < 7; ++i) between[i] = vec4(0.0);
  dvec3 m;
  if (light.w == 0.0 || !far_bisector(a, b, m)) return 0;
  dvec3 left, right, x;
  const bool split_left = far_bisector(a, m, left);
  const bool split_right = far_bisector(m, b, right);
  int n = 0;
  if (split_left) {
    if (far_bisector(a, left, x)) between[n++] = far_direction(x);
    between[n++] = far_direction(left);
    if (far_bisector(left, m, x)) between[n++] = far_direction(x);
  }
  between[n++] = far_direction(m);
  if (split_right) {
    if (far_bisector(m, right, x)) between[n++] = far_direction(x);
    between[n++] = far_direction(right);
    if (far_bisector(right, b, x)) between[n++] = far_direction(x);
  }
  return n;
}

// Whether far(p) - far(q) is split at all: the fast path of every face.
bool far_edge_is_wide(vec4 p, vec4 q) {
  if (light.w == 0.0) return false;
  precise float cosine = dot(far_vertex(p).xyz, far_vertex(q).xyz);
  return cosine < 0.0;
}

// The far vertex a back cap (f0, f1, f2 finite, any order) is fanned from: its plane's normal,
// turned away from the light (in double, like the bisectors: a sliver's cross product cancels).
vec4 away_normal(vec4 f0, vec4 f1, vec4 f2) {
  const dvec3 x = dvec3(f0.xyz);
  precise dvec3 n = cross(dvec3(f1.xyz) - x, dvec3(f2.xyz) - x);
  precise double towards = dot(n, x - dvec3(light.xyz));
  return vec4(vec3(towards < 0.0 ? -n : n), 0.0);
}

// The including shader defines how a triangle of the volume is written (a storage buffer for
// cs, transform feedback for gs and ts); declared here so that the fans below can emit.
void volume_triangle(vec4 a, vec4 b, vec4 c);

// One copy of the side quad (p, q, q_inf, p_inf), where (p, q) is an edge of the chain oriented
// by its multiplicity: (p, q, q_inf), then (p, q_inf, p_inf), or, when that far edge is wide,
// the fan from p over the far polyline q_inf, ..., p_inf; exactly exact/chain_mesh.cpp's
// triangles, vertex for vertex. A directional light's quad is the triangle (p, q, inf).
uint side_quad_triangle_count(vec4 p, vec4 q) {
  if (light.w == 0.0) return 1u;
  if (!far_edge_is_wide(q, p)) return 2u;
  vec4 between[7];
  return 2u + uint(far_between(q, p, between));
}

void side_quad_triangles(vec4 p, vec4 q) {
  const vec4 q_inf = far_vertex(q);
  volume_triangle(p, q, q_inf);
  if (light.w == 0.0) return;
  vec4 between[7];
  const int n = far_edge_is_wide(q, p) ? far_between(q, p, between) : 0;
  vec4 previous = q_inf;
  for (int i = 0; i < n; ++i) {
    volume_triangle(p, previous, between[i]);
    previous = between[i];
  }
  volume_triangle(p, previous, far_vertex(p));
}

// The back cap of a triangle whose front cap t' is (f0, f1, f2): (far f0, far f2, far f1), or,
// when one of its far edges is wide, its boundary with those edges split, fanned from
// away_normal (a fan from a point outside the polygon covers the outside twice with opposite
// orientations, which cancels in the stencil count and in the closure).
bool back_cap_is_split(vec4 f0, vec4 f1, vec4 f2) {
  return far_edge_is_wide(f0, f2) || far_edge_is_wide(f2, f1) || far_edge_is_wide(f1, f0);
}

uint back_cap_triangle_count(vec4 f0, vec4 f1, vec4 f2) {
  if (light.w == 0.0) return 0u;
  if (!back_cap_is_split(f0, f1, f2)) return 1u;
  vec4 between[7];
  return 3u + uint(far_between(f0, f2, between) + far_between(f2, f1, between) + far_between(f1, f0, between));
}

// The fan from g over far(x), the far vertices between, far(y).
void back_cap_fan(vec4 g, vec4 x, vec4 y) {
  vec4 between[7];
  const int n = far_between(x, y, between);
  vec4 previous = far_vertex(x);
  for (int i = 0; i < n; ++i) {
    volume_triangle(g, previous, between[i]);
    previous = between[i];
  }
  volume_triangle(g, previous, far_vertex(y));
}

void back_cap_triangles(vec4 f0, vec4 f1, vec4 f2) {
  if (light.w == 0.0) return;
  if (!back_cap_is_split(f0, f1, f2)) {
    volume_triangle(far_vertex(f0), far_vertex(f2), far_vertex(f1));
    return;
  }
  const vec4 g = away_normal(f0, f2, f1);
  back_cap_fan(g, f0, f2);
  back_cap_fan(g, f2, f1);
  back_cap_fan(g, f1, f0);
}
