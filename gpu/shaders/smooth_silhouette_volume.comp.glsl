#version 450 core
// The `smooth-gpu` shadow volume (gpu/smooth_silhouette_volume.h; docs/smooth-silhouettes.md):
// contour/smooth_volume.h's closed smooth volume (Mattausch et al. 2012 §3-§4) built by one
// invocation per caster triangle, with no loop tracing. Everything a triangle emits depends on
// its own corners and on the triangles across its edges only:
//   - its accurate segment (Hertzmann-Zorin): the points on the two edges where the corner
//     values f = n . (l - w v) change sign, each computed from the edge's lower vertex index to
//     its higher one, so both triangles of an edge get the same bits;
//   - that segment's smooth contour: each end displaced onto its edge's cubic Hermite curve
//     (Eq. 1), subdivided at u = 1/2 while the displacement is >= epsilon (Eq. 2, Listing 1),
//     each new point's partner the midpoint of its parents' partners;
//   - its caps (X): the lit part as it is and the unlit part reversed, cut along the segment
//     with every partner point a vertex, and the gap strip (p'_k+1, p'_k, p_k, p_k+1) twice;
//   - the extrusion of the edges of X's boundary it owns: the contour (twice), the strip's ends
//     on a border, the lit and unlit parts of its border edges;
//   - the back cap: its X triangles at infinity, reversed (none for a directional light).
// Along a crease the two sides' values differ: the part of the edge lit on one side only is
// boundary too (contour/silhouette_loop.h). Both sides evaluate that edge the same way, from
// the lower-index side's frame, so they agree on its pieces; the lit side owns each piece
// (strip and sides) and both insert its partners into their caps.
// Interior edges are never extruded: both sides' caps carry the same points there (the same
// bits), so X's edges cancel and the volume is closed by construction, as the CPU's is.
// Every quantity shared across triangles is computed by one function from the same inputs, and
// everything is `precise`, so no FMA contraction or reassociation makes two invocations round
// one point apart.
//
// A triangle runs its emission twice: counting, then (after one atomic reservation of exactly
// that many vertices, volume_reservation.glsl) writing.
layout(local_size_x = 64) in;

// Welded caster vertices (the eye's frame, rounded once to float), w = 1.
layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };
// One unit normal per wedge (a vertex with one normal; contour/smooth_caster.h), w = 0.
layout(std430, binding = 1) readonly buffer WedgeNormals { vec4 wedge_normals[]; };
// Per triangle three uvec4: (v0, v1, v2, crease bits: edge k = (corner k, corner k + 1) is a
// crease iff bit k), (w0, w1, w2, bits of the mesh's cap offset), (across0, across1, across2,
// bits of the mesh's epsilon); across = kBorder where no triangle is across.
layout(std430, binding = 2) readonly buffer Triangles { uvec4 triangle_records[]; };
layout(std430, binding = 3) coherent buffer Command {
  uint vertex_count;
  uint instance_count;
  uint first_vertex;
  uint base_instance;
  uint requested;
};
layout(std430, binding = 4) writeonly buffer Volume { vec4 volume[]; };  // triangles, 3 vec4 each

layout(location = 0) uniform vec4 light;       // (l, w), rounded once to float
layout(location = 1) uniform uint pass_kind;   // 0 triangles, 1 finish
layout(location = 2) uniform uint item_count;  // triangles
layout(location = 3) uniform uint capacity;    // vertices the Volume buffer holds

#include "volume_reservation.glsl"

// SHADOWCERT_MAX_SUBDIVISION_DEPTH is defined by gpu/smooth_silhouette_volume.cpp: halvings of
// one contour segment at most (contour/smooth_contour.h's kMaxSubdivisionDepth).
const uint kMaxDepth = uint(SHADOWCERT_MAX_SUBDIVISION_DEPTH);
const uint kBorder = 0xFFFFFFFFu;
// Point names (contour/detail/lit_boundary.h's PointKey): (kind, i, j, side).
const uint kVertexKey = 0u, kSmoothEdgeKey = 1u, kCreaseSideKey = 2u;

// ------------------------------------------------------------------------------ the mesh

struct Tri {
  uvec3 v;       // welded vertex indices
  uvec3 w;       // wedge indices
  uvec3 across;  // the triangles across edges 0, 1, 2, or kBorder
  uint crease;   // bit k: edge k is a crease
  vec3 f;        // corner values
  float cap_offset;
  float epsilon;
};

float corner_value(uint v, uint w) {
  precise vec3 p = vertices[v].xyz;
  precise vec3 n = wedge_normals[w].xyz;
  precise float f = n.x * (light.x - light.w * p.x) + n.y * (light.y - light.w * p.y) +
                    n.z * (light.z - light.w * p.z);
  return f;
}

Tri load_triangle(uint t) {
  const uvec4 r0 = triangle_records[3u * t];
  const uvec4 r1 = triangle_records[3u * t + 1u];
  const uvec4 r2 = triangle_records[3u * t + 2u];
  Tri x;
  x.v = r0.xyz;
  x.crease = r0.w;
  x.w = r1.xyz;
  x.cap_offset = uintBitsToFloat(r1.w);
  x.across = r2.xyz;
  x.epsilon = uintBitsToFloat(r2.w);
  for (uint k = 0u; k < 3u; ++k) x.f[k] = corner_value(x.v[k], x.w[k]);
  return x;
}

bool lit(float f) { return f >= 0.0; }  // the fixed rule: f = 0 counts as lit

uint corner_of(Tri x, uint vertex) {
  return x.v[0] == vertex ? 0u : (x.v[1] == vertex ? 1u : 2u);
}

// ------------------------------------------------------------------------------ contour points

struct ContourPoint {
  vec3 position;  // p, on the smooth surface (a mesh vertex stays where it is)
  vec3 normal;    // unit
  vec3 partner;   // p', on the mesh
  bool vertex;    // p' is a mesh vertex: caps keep it on the surface (no offset)
};

// An accurate silhouette point with its name: on edge (i, j), i < j, at u from i.
struct EdgePoint {
  uvec4 key;
  ContourPoint point;
  uint i;
  float u;
};

// contour/smooth_contour.h's hermite_tangent: e - (n . e) n, normalised, scaled by |e|.
vec3 hermite_tangent(vec3 p0, vec3 p1, vec3 n) {
  precise vec3 e = p1 - p0;
  precise float e_length = sqrt(dot(e, e));
  precise vec3 t = e - n * dot(n, e);
  precise float t_length = sqrt(dot(t, t));
  if (!(e_length > 0.0) || !(t_length > 0.0)) return vec3(0.0);
  precise vec3 scaled = t * (e_length / t_length);
  return scaled;
}

vec3 hermite_point(vec3 p0, vec3 p1, vec3 t0, vec3 t1, float u) {
  precise float u2 = u * u;
  precise float u3 = u2 * u;
  precise float h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
  precise float h01 = -2.0 * u3 + 3.0 * u2;
  precise float h10 = u3 - 2.0 * u2 + u;
  precise float h11 = u3 - u2;
  precise vec3 p = h00 * p0 + h01 * p1 + h10 * t0 + h11 * t1;
  return p;
}

vec3 unit(vec3 n) {
  precise float length_squared = dot(n, n);
  precise vec3 u = n / sqrt(length_squared);
  return u;
}

ContourPoint vertex_point(Tri x, uint corner) {
  const vec3 p = vertices[x.v[corner]].xyz;
  return ContourPoint(p, wedge_normals[x.w[corner]].xyz, p, true);
}

// The accurate point on edge k of x (its corners' lit states differ; contour/detail/
// lit_boundary.h's edge_point), displaced onto the edge's Hermite curve with x's corner normals
// (smooth_contour.h's step b). `t` is x's index (a crease side's name).
EdgePoint edge_point(Tri x, uint t, uint k) {
  uint ci = k, cj = (k + 1u) % 3u;
  if (x.v[ci] > x.v[cj]) {
    const uint swap = ci;
    ci = cj;
    cj = swap;
  }
  const uint i = x.v[ci], j = x.v[cj];
  precise float fi = x.f[ci];
  precise float fj = x.f[cj];
  precise float u = fi / (fi - fj);  // nonzero denominator: the states differ
  EdgePoint e;
  e.i = i;
  e.u = u;
  if (u == 0.0 || u == 1.0) {
    const uint c = u == 0.0 ? ci : cj;
    e.key = uvec4(kVertexKey, x.v[c], x.v[c], 0u);
    e.point = vertex_point(x, c);
    return e;
  }
  const vec3 vi = vertices[i].xyz, vj = vertices[j].xyz;
  const vec3 ni = wedge_normals[x.w[ci]].xyz, nj = wedge_normals[x.w[cj]].xyz;
  precise float one_minus_u = 1.0 - u;
  precise vec3 p = one_minus_u * vi + u * vj;
  precise vec3 n = one_minus_u * ni + u * nj;
  e.point.partner = p;
  e.point.normal = unit(n);
  e.point.position = hermite_point(vi, vj, hermite_tangent(vi, vj, ni), hermite_tangent(vi, vj, nj), u);
  e.point.vertex = false;
  e.key = ((x.crease >> k) & 1u) != 0u ? uvec4(kCreaseSideKey, i, j, t) : uvec4(kSmoothEdgeKey, i, j, 0u);
  return e;
}

// Where the partner p' is stored: a cut point behind the surface by the mesh's cap offset along
// -n (contour/smooth_volume.h, SmoothVolumeOptions::cap_offset), a mesh vertex where it is.
float g_cap_offset = 0.0;
vec3 stored_partner(ContourPoint p) {
  if (p.vertex) return p.partner;
  precise vec3 behind = p.partner - g_cap_offset * p.normal;
  return behind;
}

// ------------------------------------------------------------------------------ emission

bool g_counting = true;
uint g_vertices = 0u;  // counted

void put_triangle(vec4 a, vec4 b, vec4 c) {
  if (g_counting) g_vertices += 3u;
  else volume_triangle(a, b, c);
}

vec4 far_point(vec3 p) {
  if (light.w == 0.0) return vec4(-light.xyz, 0.0);
  precise vec3 d = p - light.xyz;
  return vec4(d, 0.0);
}

// A triangle of X (facing the light) and, for a point light, its back cap.
void x_triangle(vec3 a, vec3 b, vec3 c) {
  if (a == b || b == c || c == a) return;  // no area; its edges cancel among themselves
  put_triangle(vec4(a, 1.0), vec4(b, 1.0), vec4(c, 1.0));
  if (light.w != 0.0) put_triangle(far_point(a), far_point(c), far_point(b));
}

// The extrusion of X's boundary edge a -> b: (b, a, a_inf, b_inf), or (b, a, inf).
void side(vec3 a, vec3 b) {
  if (a == b) return;
  put_triangle(vec4(b, 1.0), vec4(a, 1.0), far_point(a));
  if (light.w != 0.0) put_triangle(vec4(b, 1.0), far_point(a), far_point(b));
}

// A cap polygon's ring, streamed point by point (smooth_volume.cpp's ring: repeated points
// dropped). As caps (g_ring_sides false) it is fanned from its first point, reversed for the
// unlit part. As sides (a triangle that casts nothing, triangle_pass says why) each ring edge
// flagged by the caller is X's boundary in reverse: the cap the triangle does not draw would have
// cancelled it there, so its reverse is extruded.
vec3 g_ring_first, g_ring_previous;
uint g_ring_points = 0u;
bool g_ring_reversed = false;
bool g_ring_sides = false;
// Sides only: the ring runs along a crease piece this triangle owns (its strip is its own), and
// whether the previous and the first point lie on the contour as well (the strip has no width
// there).
bool g_ring_owned_piece = false;
bool g_ring_previous_on_contour = false, g_ring_first_on_contour = false;

// Whether a flagged ring edge is extruded: not where it runs along its own crease piece's strip
// where that strip has no width (both ends on the contour): the strip's side is that edge's
// extrusion already (strip_segment).
bool ring_edge_extruded(bool flagged, bool from_on_contour, bool to_on_contour) {
  return flagged && !(g_ring_owned_piece && from_on_contour && to_on_contour);
}

void ring_begin(bool reversed, bool sides) {
  g_ring_points = 0u;
  g_ring_reversed = reversed;
  g_ring_sides = sides;
}

// The next ring point; `flagged`: the ring edge that ends at it is to be extruded (sides only);
// `on_contour`: the point is its own contour point as well (a mesh vertex, or a partner with no
// displacement).
void ring_point(vec3 p, bool flagged, bool on_contour) {
  if (g_ring_points > 0u && p == g_ring_previous) return;
  if (g_ring_points == 0u) {
    g_ring_first = p;
    g_ring_first_on_contour = on_contour;
  } else if (g_ring_sides) {
    if (ring_edge_extruded(flagged, g_ring_previous_on_contour, on_contour)) side(p, g_ring_previous);
  } else if (g_ring_points >= 2u) {
    if (g_ring_reversed) x_triangle(g_ring_first, p, g_ring_previous);
    else x_triangle(g_ring_first, g_ring_previous, p);
  }
  g_ring_previous = p;
  g_ring_previous_on_contour = on_contour;
  ++g_ring_points;
}

// The ring's last edge, back to its first point.
void ring_close(bool flagged) {
  if (g_ring_sides && g_ring_points > 1u && g_ring_first != g_ring_previous &&
      ring_edge_extruded(flagged, g_ring_previous_on_contour, g_ring_first_on_contour))
    side(g_ring_first, g_ring_previous);
}

bool g_casts = true;  // the triangle being emitted draws caps (casts_caps)

// One piece of the strip, between consecutive contour points p and q, twice (once for the lit
// part, once for the unlit one), and its outer edge p -> q extruded twice. Where the strip has
// no width and its triangle draws no caps (its owner casts nothing), that edge is also its own
// missing cap's, whose reverse the owner does not extrude (ring_edge_extruded): once then, as
// the CPU's cancellation leaves it.
void strip_segment(ContourPoint p, ContourPoint q) {
  const vec3 p0 = stored_partner(p), q0 = stored_partner(q);
  for (uint copy = 0u; copy < 2u; ++copy) {
    x_triangle(q0, p0, p.position);
    x_triangle(q0, p.position, q.position);
  }
  side(p.position, q.position);
  if (g_casts || p0 != p.position || q0 != q.position) side(p.position, q.position);
}

// ------------------------------------------------------------------------------ subdivision

float g_epsilon = 0.01;

// smooth_contour.cpp's subdivide step: the midpoint of a -> b on its Hermite curve, when it is
// at least epsilon from the chord's midpoint.
bool refine(ContourPoint a, ContourPoint b, out ContourPoint mid) {
  const vec3 t0 = hermite_tangent(a.position, b.position, a.normal);
  const vec3 t1 = hermite_tangent(a.position, b.position, b.normal);
  precise vec3 p = hermite_point(a.position, b.position, t0, t1, 0.5);
  precise vec3 chord_mid = 0.5 * (a.position + b.position);
  precise vec3 d = p - chord_mid;
  precise float displacement = sqrt(dot(d, d));
  if (!(displacement >= g_epsilon)) return false;
  precise vec3 n = a.normal + b.normal;
  precise float n2 = dot(n, n);
  precise vec3 partner = 0.5 * (a.partner + b.partner);
  mid = ContourPoint(p, n2 > 0.0 ? unit(n) : a.normal, partner, false);
  return true;
}

const uint kToCap = 0u, kToStrip = 1u;
ContourPoint g_strip_previous;

bool g_ring_flag = false;  // what ring_point's partners from consume() are flagged with

void consume(uint consumer, ContourPoint p) {
  if (consumer == kToCap) {
    const vec3 stored = stored_partner(p);
    ring_point(stored, g_ring_flag, stored == p.position);
  } else {
    strip_segment(g_strip_previous, p);
    g_strip_previous = p;
  }
}

// The points the subdivision of a -> b adds strictly between them, in order (reversed: from b
// to a), each handed to `consumer`. Always computed from a to b, whichever way it is walked, so
// both walks produce the same bits. An explicit stack replaces Listing 1's recursion.
ContourPoint g_stack_a[kMaxDepth + 1u], g_stack_b[kMaxDepth + 1u], g_stack_mid[kMaxDepth + 1u];
uint g_stack_state[kMaxDepth + 1u];

void walk(ContourPoint a, ContourPoint b, bool reversed, uint consumer) {
  int top = 0;
  g_stack_a[0] = a;
  g_stack_b[0] = b;
  g_stack_state[0] = 0u;
  while (top >= 0) {
    const uint depth = uint(top);
    if (g_stack_state[depth] == 0u) {
      ContourPoint mid;
      if (depth == kMaxDepth || !refine(g_stack_a[depth], g_stack_b[depth], mid)) {
        --top;
        continue;
      }
      g_stack_mid[depth] = mid;
      g_stack_state[depth] = 1u;
      g_stack_a[depth + 1u] = reversed ? mid : g_stack_a[depth];
      g_stack_b[depth + 1u] = reversed ? g_stack_b[depth] : mid;
      g_stack_state[depth + 1u] = 0u;
      ++top;
    } else if (g_stack_state[depth] == 1u) {
      consume(consumer, g_stack_mid[depth]);
      g_stack_state[depth] = 2u;
      g_stack_a[depth + 1u] = reversed ? g_stack_a[depth] : g_stack_mid[depth];
      g_stack_b[depth + 1u] = reversed ? g_stack_mid[depth] : g_stack_b[depth];
      g_stack_state[depth + 1u] = 0u;
      ++top;
    } else {
      --top;
    }
  }
}

// The whole strip of a contour piece from a to b.
void strip(ContourPoint a, ContourPoint b) {
  g_strip_previous = a;
  walk(a, b, false, kToStrip);
  strip_segment(g_strip_previous, b);
}

// ------------------------------------------------------------------------------ pieces

// A piece of the lit part's boundary, from -> to with the lit part on its left, whose subdivided
// partners the caps insert between its ends (contour/smooth_volume.cpp's Insertions).
const uint kMaxPieces = 16u;
uvec4 g_piece_from[kMaxPieces], g_piece_to[kMaxPieces];
ContourPoint g_piece_a[kMaxPieces], g_piece_b[kMaxPieces];
bool g_piece_owned[kMaxPieces];  // this triangle emits its strip
uint g_pieces = 0u;

void add_piece(uvec4 from, ContourPoint a, uvec4 to, ContourPoint b, bool owned) {
  if (g_pieces == kMaxPieces) return;  // cannot happen: one segment, 3 creases x 4, 3 edges
  g_piece_owned[g_pieces] = owned;
  g_piece_from[g_pieces] = from;
  g_piece_to[g_pieces] = to;
  g_piece_a[g_pieces] = a;
  g_piece_b[g_pieces] = b;
  ++g_pieces;
}

// The partners between consecutive cap points named `x` -> `y`, when a piece runs between them;
// g_ring_owned_piece says whether this triangle owns it.
void insert_partners(uvec4 x, uvec4 y) {
  g_ring_owned_piece = false;
  for (uint k = 0u; k < g_pieces; ++k) {
    if (g_piece_from[k] == x && g_piece_to[k] == y) {
      g_ring_owned_piece = g_piece_owned[k];
      walk(g_piece_a[k], g_piece_b[k], false, kToCap);
      return;
    }
    if (g_piece_from[k] == y && g_piece_to[k] == x) {
      g_ring_owned_piece = g_piece_owned[k];
      walk(g_piece_a[k], g_piece_b[k], true, kToCap);
      return;
    }
  }
}

// The segment of triangle x (index t) inside it, from the edge where its corners go lit to
// unlit (in its order) to the edge where they go back; false when it has none.
bool own_segment(Tri x, uint t, out EdgePoint from, out EdgePoint to, out uint from_edge, out uint to_edge) {
  uint leaving = 3u, entering = 3u;
  for (uint k = 0u; k < 3u; ++k) {
    const bool here = lit(x.f[k]), next = lit(x.f[(k + 1u) % 3u]);
    if (here && !next) leaving = k;
    if (!here && next) entering = k;
  }
  if (leaving == 3u) return false;
  from = edge_point(x, t, leaving);
  to = edge_point(x, t, entering);
  from_edge = leaving;
  to_edge = entering;
  return from.key != to.key;
}

// One side of a crease edge a -> b (the frame of its lower-index triangle): its lit state at a
// and at b, and where it changes (parameter s from a to b, -1 when it does not).
struct CreaseSide {
  bool at_a, at_b;
  float s;
  EdgePoint point;
};

CreaseSide crease_side(Tri x, uint t, uint corner_a, uint corner_b, uint edge, uint a) {
  CreaseSide c;
  c.at_a = lit(x.f[corner_a]);
  c.at_b = lit(x.f[corner_b]);
  c.s = -1.0;
  if (c.at_a != c.at_b) {
    c.point = edge_point(x, t, edge);
    c.s = c.point.i == a ? c.point.u : 1.0 - c.point.u;
    if (c.point.key.x == kVertexKey) c.s = c.point.key.y == a ? 0.0 : 1.0;
  }
  return c;
}

bool lit_at(CreaseSide c, float s) {
  if (c.at_a == c.at_b) return c.at_a;
  return c.at_a ? s < c.s : s > c.s;
}

// The crease edge k of triangle `t` and the pieces of the lit part's boundary along it
// (contour/detail/lit_boundary.cpp, step 2), evaluated from the lower-index side's frame so that
// both sides get the same pieces. Adds every piece to the insertion list; the pieces `t` owns
// (it is their lit side; the lower side owns the zero-length piece) get their strip when
// `emit_strips`.
void crease_pieces(Tri here, uint t, uint k, bool emit_strips) {
  const uint other = here.across[k];
  const Tri there = load_triangle(other);
  const bool here_is_one = t < other;
  const Tri one = here_is_one ? here : there;
  const Tri two = here_is_one ? there : here;
  const uint t_one = here_is_one ? t : other, t_two = here_is_one ? other : t;
  // one's edge a -> b; two runs it b -> a.
  const uint k1 = here_is_one ? k : corner_of(there, here.v[(k + 1u) % 3u]);
  const uint a = one.v[k1], b = one.v[(k1 + 1u) % 3u];
  const uint k2 = corner_of(two, b);
  const CreaseSide s1 = crease_side(one, t_one, k1, (k1 + 1u) % 3u, k1, a);
  const CreaseSide s2 = crease_side(two, t_two, corner_of(two, a), k2, k2, a);
  const uvec4 key_a = uvec4(kVertexKey, a, a, 0u), key_b = uvec4(kVertexKey, b, b, 0u);

  // The cuts 0, s1, s2, 1 in order, repeats dropped (s = -1: no change on that side). Written
  // out rather than sorted in a loop: llvmpipe miscompiled an in-place sort of this local array
  // (the crease sphere of tests/gpu/smooth_silhouette_volume_test.cpp lost a strip piece).
  const float low = s2.s < 0.0 ? s1.s : (s1.s < 0.0 ? s2.s : min(s1.s, s2.s));
  const float high = max(s1.s, s2.s);
  float cuts[4];
  cuts[0] = 0.0;
  uint m = 1u;
  if (low > 0.0 && low < 1.0) {
    cuts[m] = low;
    m += 1u;
  }
  if (high > 0.0 && high < 1.0 && high != low) {
    cuts[m] = high;
    m += 1u;
  }
  cuts[m] = 1.0;
  m += 1u;

  for (uint c = 0u; c + 1u < m; ++c) {
    precise float mid = 0.5 * (cuts[c] + cuts[c + 1u]);
    const bool lit_one = lit_at(s1, mid), lit_two = lit_at(s2, mid);
    if (lit_one == lit_two) continue;
    // The points at both cuts; where both sides change at one s, the lit side's; at a mesh vertex,
    // with the lit side's corner normal (the side whose lit part the piece bounds;
    // contour/silhouette_loop.h's segment_triangles).
    const Tri lit_side = lit_one ? one : two;
    const ContourPoint point_a = vertex_point(lit_side, corner_of(lit_side, a));
    const ContourPoint point_b = vertex_point(lit_side, corner_of(lit_side, b));
    uvec4 key[2];
    ContourPoint point[2];
    for (uint e = 0u; e < 2u; ++e) {
      const float s = cuts[c + e];
      if (s == 0.0) {
        key[e] = key_a;
        point[e] = point_a;
      } else if (s == 1.0) {
        key[e] = key_b;
        point[e] = point_b;
      } else if (s == s1.s && (lit_one || s != s2.s)) {
        key[e] = s1.point.key;
        point[e] = s1.point.point;
      } else {
        key[e] = s2.point.key;
        point[e] = s2.point.point;
      }
    }
    // One's order a -> b when one is lit there, two's b -> a otherwise.
    const uint from = lit_one ? 0u : 1u, to = lit_one ? 1u : 0u;
    const bool owned = lit_one == here_is_one;
    add_piece(key[from], point[from], key[to], point[to], owned);
    if (emit_strips && owned) strip(point[from], point[to]);
  }
  if (s1.s >= 0.0 && s1.s == s2.s && s1.at_a == s2.at_a && emit_strips && here_is_one) {
    // Both sides change at one point with the same end lit: the zero-length piece between the
    // two sides' points, whose contour is not of zero length (each side's own normals). Its
    // partners are that one point: nothing to insert into the caps.
    if (s1.at_a) strip(s2.point.point, s1.point.point);
    else strip(s1.point.point, s2.point.point);
  }
}

// Where the triangle across the non-crease edge k has its own segment lying along that edge
// (both ends at the edge's vertices: f = 0 there), its partners are vertices of our caps too.
void neighbour_piece_along(Tri here, uint k) {
  const uint other = here.across[k];
  const Tri there = load_triangle(other);
  EdgePoint from, to;
  uint from_edge, to_edge;
  if (!own_segment(there, other, from, to, from_edge, to_edge)) return;
  if (from.key.x != kVertexKey || to.key.x != kVertexKey) return;
  const uint a = here.v[k], b = here.v[(k + 1u) % 3u];
  if ((from.key.y == a && to.key.y == b) || (from.key.y == b && to.key.y == a))
    add_piece(from.key, from.point, to.key, to.point, false);
}

// ------------------------------------------------------------------------------ a triangle

// A cap polygon point: its name and where it is stored.
const uint kMaxPolygon = 12u;
uvec4 g_polygon_key[kMaxPolygon];
vec3 g_polygon_point[kMaxPolygon];
// The edge k whose part the point was found on, and whether it is that edge's first corner: the
// ring edge from a point to the next runs along edge k when the next one is on edge k too, or
// is the next edge's first corner (the part meets an edge in one interval).
uint g_polygon_edge[kMaxPolygon];
bool g_polygon_corner[kMaxPolygon];
bool g_polygon_on_contour[kMaxPolygon];  // a mesh vertex (a cut point is displaced off the mesh)
uint g_polygon_size = 0u;

void polygon_add(uvec4 key, vec3 p, uint edge, bool corner) {
  if (g_polygon_size < kMaxPolygon) {
    g_polygon_on_contour[g_polygon_size] = key.x == kVertexKey;
    g_polygon_key[g_polygon_size] = key;
    g_polygon_point[g_polygon_size] = p;
    g_polygon_edge[g_polygon_size] = edge;
    g_polygon_corner[g_polygon_size] = corner;
    ++g_polygon_size;
  }
}

// The edge of x that the ring runs along from polygon point i to the next, or 3 (across it).
uint polygon_edge_after(uint i) {
  const uint j = (i + 1u) % g_polygon_size;
  const uint k = g_polygon_edge[i];
  if (g_polygon_edge[j] == k && !g_polygon_corner[j]) return k;
  if (g_polygon_corner[j] && g_polygon_edge[j] == (k + 1u) % 3u) return k;
  return 3u;
}

// Swaps two cut points when they are out of order.
void order_cuts(inout float s0, inout uvec4 key0, inout vec3 p0, inout float s1, inout uvec4 key1, inout vec3 p1) {
  if (!(s0 > s1)) return;
  const float s = s0;
  const uvec4 key = key0;
  const vec3 p = p0;
  s0 = s1;
  key0 = key1;
  p0 = p1;
  s1 = s;
  key1 = key;
  p1 = p;
}

// Triangle x's lit part (`want_lit`) or unlit part as a polygon, in x's order
// (smooth_volume.cpp's part_polygon): its corners of that state, its cut points, the corner
// where the state changes exactly at it (f = 0), and on a crease the other side's point where it
// falls inside this part of the edge.
void part_polygon(Tri x, uint t, bool want_lit) {
  g_polygon_size = 0u;
  for (uint k = 0u; k < 3u; ++k) {
    const uint k1 = (k + 1u) % 3u;
    const uint a = x.v[k], b = x.v[k1];
    const bool lit_a = lit(x.f[k]), lit_b = lit(x.f[k1]);
    const bool in_a = lit_a == want_lit, in_b = lit_b == want_lit;
    if (in_a) polygon_add(uvec4(kVertexKey, a, a, 0u), vertices[a].xyz, k, true);
    // Cut points on this edge inside the part, by s from a to b (at most three).
    float cut_s[3];
    uvec4 cut_key[3];
    vec3 cut_point[3];
    uint cuts = 0u;
    float lo = in_a ? 0.0 : 1.0, hi = in_b ? 1.0 : 0.0;
    if (lit_a != lit_b) {
      const EdgePoint e = edge_point(x, t, k);
      const float s = e.i == a ? e.u : 1.0 - e.u;
      if (e.key.x != kVertexKey) {
        if (in_a) hi = s;
        else lo = s;
        cut_s[cuts] = s;
        cut_key[cuts] = e.key;
        cut_point[cuts] = stored_partner(e.point);
        ++cuts;
      } else {
        const bool at_a = e.key.y == a;
        if (in_a) hi = at_a ? 0.0 : 1.0;
        else lo = at_a ? 0.0 : 1.0;
        if ((at_a && !in_a) || (!at_a && !in_b)) {
          cut_s[cuts] = at_a ? 0.0 : 1.0;
          cut_key[cuts] = e.key;
          cut_point[cuts] = e.point.partner;
          ++cuts;
        }
      }
    }
    const uint other = x.across[k];
    if (((x.crease >> k) & 1u) != 0u && other != kBorder) {
      const Tri y = load_triangle(other);
      const uint oa = corner_of(y, a), ob = corner_of(y, b);
      if (lit(y.f[oa]) != lit(y.f[ob])) {
        const EdgePoint e = edge_point(y, other, ob);  // y's edge from b to a starts at its corner b
        const float s = e.i == a ? e.u : 1.0 - e.u;
        if (e.key.x != kVertexKey && s > lo && s < hi) {
          cut_s[cuts] = s;
          cut_key[cuts] = e.key;
          cut_point[cuts] = stored_partner(e.point);
          ++cuts;
        }
      }
    }
    // In order of s: a sorting network on constant indices (llvmpipe miscompiled a loop that
    // sorted a local array in place; tests/gpu/smooth_silhouette_volume_test.cpp caught it).
    if (cuts >= 2u) order_cuts(cut_s[0], cut_key[0], cut_point[0], cut_s[1], cut_key[1], cut_point[1]);
    if (cuts == 3u) {
      order_cuts(cut_s[1], cut_key[1], cut_point[1], cut_s[2], cut_key[2], cut_point[2]);
      order_cuts(cut_s[0], cut_key[0], cut_point[0], cut_s[1], cut_key[1], cut_point[1]);
    }
    for (uint i = 0u; i < cuts; ++i) polygon_add(cut_key[i], cut_point[i], k, false);
  }
}

// The lit part's or the unlit part's border edge k: extruded a -> b where the part is lit, b -> a
// where it is unlit (reversed), split at the cut.
void border_sides(Tri x, uint t, uint k) {
  const uint k1 = (k + 1u) % 3u;
  const vec3 a = vertices[x.v[k]].xyz, b = vertices[x.v[k1]].xyz;
  const bool lit_a = lit(x.f[k]), lit_b = lit(x.f[k1]);
  if (lit_a == lit_b) {
    if (lit_a) side(a, b);
    else side(b, a);
    return;
  }
  const EdgePoint e = edge_point(x, t, k);
  const vec3 c = e.key.x == kVertexKey ? e.point.partner : stored_partner(e.point);
  if (lit_a) side(a, c);
  else side(c, a);
  if (lit_b) side(c, b);
  else side(b, c);
}

// Whether a triangle draws caps: not when the light lies in the plane its corner normals
// describe at every corner (f = 0 at all three; as the exact side 0, it casts nothing).
bool casts_caps(Tri x) { return !(x.f[0] == 0.0 && x.f[1] == 0.0 && x.f[2] == 0.0); }

// `casts`: casts_caps(x). A triangle that does not still owns its crease pieces' strips (the
// contour runs along its creases as the CPU's loops do) and closes the gap its missing caps
// leave next to the triangles that cast.
void emit_triangle(Tri x, uint t, bool casts) {
  bool neighbour_casts[3];
  for (uint k = 0u; k < 3u; ++k)
    neighbour_casts[k] = !casts && x.across[k] != kBorder && casts_caps(load_triangle(x.across[k]));
  g_pieces = 0u;
  // 1. The pieces whose partners the caps insert: the own segment, the crease pieces (and their
  // strips when owned, emitted here), a neighbour's segment along a shared edge.
  EdgePoint from, to;
  uint from_edge = 3u, to_edge = 3u;
  const bool has_segment = own_segment(x, t, from, to, from_edge, to_edge);
  if (has_segment) add_piece(from.key, from.point, to.key, to.point, true);
  for (uint k = 0u; k < 3u; ++k) {
    const uint other = x.across[k];
    if (other == kBorder) continue;
    if (((x.crease >> k) & 1u) != 0u) {
      crease_pieces(x, t, k, true);
    } else {
      const uint k1 = (k + 1u) % 3u;
      if (lit(x.f[k]) == lit(x.f[k1]) && (x.f[k] == 0.0 || x.f[k1] == 0.0)) neighbour_piece_along(x, k);
    }
  }
  // 2. The caps: the lit part, then the unlit part reversed. A triangle that casts nothing
  // draws none, and extrudes the reverse of its ring's edges shared with a triangle that casts.
  for (uint part = 0u; part < 2u; ++part) {
    const bool want_lit = part == 0u;
    if (!casts && !want_lit) break;  // f = 0 everywhere counts as lit: no unlit part
    part_polygon(x, t, want_lit);
    if (g_polygon_size == 0u) continue;
    ring_begin(!want_lit, !casts);
    ring_point(g_polygon_point[0], false, g_polygon_on_contour[0]);
    for (uint i = 0u; i < g_polygon_size; ++i) {
      const uint along = polygon_edge_after(i);
      g_ring_flag = !casts && along != 3u && neighbour_casts[along];
      insert_partners(g_polygon_key[i], g_polygon_key[(i + 1u) % g_polygon_size]);
      if (i + 1u < g_polygon_size) ring_point(g_polygon_point[i + 1u], g_ring_flag, g_polygon_on_contour[i + 1u]);
      else ring_close(g_ring_flag);
    }
  }
  if (!casts) return;
  // 3. The own segment's strip and contour sides; its ends on a border are X's boundary too.
  if (has_segment) {
    strip(from.point, to.point);
    if (x.across[from_edge] == kBorder) {
      side(stored_partner(from.point), from.point.position);
      side(stored_partner(from.point), from.point.position);
    }
    if (x.across[to_edge] == kBorder) {
      side(to.point.position, stored_partner(to.point));
      side(to.point.position, stored_partner(to.point));
    }
  }
  // 4. Border edges.
  for (uint k = 0u; k < 3u; ++k)
    if (x.across[k] == kBorder) border_sides(x, t, k);
}

// Most triangles: every corner on one side of the light (none on it), no crease, no border.
// Such a triangle's parts are the whole triangle and nothing, with nothing inserted, and it
// owns no edge of X's boundary: emit_triangle would give just its cap (reversed where unlit)
// and back cap. Emitted here at once, without that general machinery twice over.
bool plain_triangle(Tri x) {
  const bool state = lit(x.f[0]);
  return x.crease == 0u && x.across[0] != kBorder && x.across[1] != kBorder && x.across[2] != kBorder &&
         x.f[0] != 0.0 && x.f[1] != 0.0 && x.f[2] != 0.0 && lit(x.f[1]) == state && lit(x.f[2]) == state;
}

void triangle_pass(uint t) {
  const Tri x = load_triangle(t);
  if (plain_triangle(x)) {
    const uint base = reserve(light.w != 0.0 ? 6u : 3u);
    if (base == kNoRoom) return;
    volume_cursor = base;
    g_counting = false;
    // Written whole, even without area (x_triangle would skip it): every reserved vertex is
    // written, and such a triangle rasterises nothing and cancels its own edges.
    const vec3 a = vertices[x.v[0]].xyz;
    const vec3 b = vertices[x.v[lit(x.f[0]) ? 1 : 2]].xyz;
    const vec3 c = vertices[x.v[lit(x.f[0]) ? 2 : 1]].xyz;
    put_triangle(vec4(a, 1.0), vec4(b, 1.0), vec4(c, 1.0));
    if (light.w != 0.0) put_triangle(far_point(a), far_point(c), far_point(b));
    return;
  }
  const bool casts = casts_caps(x);
  g_casts = casts;
  g_cap_offset = x.cap_offset;
  g_epsilon = x.epsilon;
  g_counting = true;
  g_vertices = 0u;
  emit_triangle(x, t, casts);
  if (g_vertices == 0u) return;
  const uint base = reserve(g_vertices);
  if (base == kNoRoom) return;
  volume_cursor = base;
  g_counting = false;
  emit_triangle(x, t, casts);
}

void main() {
  const uint id = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
  if (pass_kind == 1u) {
    if (id == 0u) vertex_count = min(requested, capacity);
    return;
  }
  if (id >= item_count) return;
  triangle_pass(id);
}
