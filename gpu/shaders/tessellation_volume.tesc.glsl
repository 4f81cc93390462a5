#version 450 core
// The `ts` shadow volume (gpu/tessellation_volume.h): Milet 2014 §2.2, Algorithms 3-4, in a
// tessellation control shader. One patch per RECORD of kRecordWords words:
//   kind 0, an EDGE RECORD (u, v, count, 0, up to kOppositesPerRecord opposite vertices; an
//           edge with more opposites has several records): partial multiplicity
//           m = - sum of the refedge signs of its opposites, and |m| isolines, one per copy of
//           the side quad (the geometry shader makes each line a quad oriented by sign(m));
//           m = 0 discards the patch (outer level 0).
//   kind 1, a TRIANGLE (a, b, c, 1, unused): one isoline, on which the geometry shader emits
//           gs's caps.
// The signs are reference_edge.glsl's, as in cs and gs (sort by canonical index,
// core/light_side_formula.h's order, `precise`, parity): the volumes of cs, gs and ts are made
// of the same signs. With exact signs this stage runs light_side_sign.glsl's float filter only
// (SHADOWCERT_SIGN_FILTER_ONLY): a record with an opposite the filter cannot decide draws
// nothing here and is appended to Deferred, whose records tessellation_volume_finish.comp.glsl
// evaluates exactly and appends to the capture. The exact stage in this shader, never run on
// the sphere grid, still cost ts 2.4x its float time on llvmpipe (docs/gpu.md, "Exact signs").
layout(vertices = 1) out;

const uint kOppositesPerRecord = 16u;  // == kTessellationOppositesPerRecord (tessellation_volume.h)
const uint kRecordWords = 4u + kOppositesPerRecord;  // u, v, count, kind, opposites
const uint kTriangleKind = 1u;

layout(std430, binding = 0) readonly buffer Vertices { vec4 vertices[]; };  // w = 1, float

layout(location = 0) uniform vec4 light;  // (l, w), rounded once to float

#ifdef SHADOWCERT_SIGN_FILTER_ONLY
// The edge records (patch numbers) left to the finish shader's exact stage.
layout(std430, binding = 1) coherent buffer Deferred {
  uint deferred_count;
  uint deferred_records[];
};
#endif

flat in uint record_word[];
flat in uint word_index[];  // of each record word in the draw (gl_VertexID)
// x, y, z: u, v (edge) or a, b, c (triangle); w: kind. multiplicity: m (edge), unused (triangle).
patch out uvec4 item;
patch out int multiplicity;

#include "reference_edge.glsl"

void main() {
  const uint u = record_word[0];
  const uint v = record_word[1];
  const uint count = record_word[2];
  const uint kind = record_word[3];
  item = uvec4(u, v, count, kind);
  multiplicity = 0;
  float lines = 1.0;
  if (kind != kTriangleKind) {
    int m = 0;
    for (uint i = 0u; i < count; ++i) {
      m -= opposite_side(u, v, record_word[4u + i]);
    }
#ifdef SHADOWCERT_SIGN_FILTER_ONLY
    if (light_side_undecided) {  // the finish shader draws this record's quads
      // The record by its first word's index: gl_PrimitiveID restarts with each batch llvmpipe
      // splits a large draw into (446 open volumes in fuzz --gl --seed 303 when it was used).
      deferred_records[atomicAdd(deferred_count, 1u)] = word_index[0] / kRecordWords;
      m = 0;
    }
#endif
    multiplicity = m;
    lines = float(abs(m));  // 0 discards the patch
  }
  // Isolines: outer[0] lines (|m| copies), outer[1] = 1 segment each.
  gl_TessLevelOuter[0] = lines;
  gl_TessLevelOuter[1] = 1.0;
}
