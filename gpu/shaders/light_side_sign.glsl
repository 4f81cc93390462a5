// Included (cmake/EmbedShaders.cmake) by reference_edge.glsl: the sign of D(a, b, c, L) that
// every GL volume method takes (docs/definitions.md#orientation, docs/gpu.md "Exact signs").
// The including shader declares `uniform vec4 light` ((l, w), w = 0 or 1, rounded once to float).
//
// Default: the EXACT sign of the float inputs, the sign exact/ computes on the float-rounded
// scene (exact/edge_multiplicity.h, method glsign), in two stages:
//   1. a float filter: light_side_formula.glsl's value with a forward error bound (Shewchuk
//      1997's orient3d bound A, which covers the rounded differences, products and sums, taken
//      as 8u instead of 7u + 56u^2, u = 2^-24, so that the bound's own rounding is covered too),
//      plus an absolute allowance for flush-to-zero (GLSL need not keep denormals: every input or
//      intermediate flushed moves the value by less than 2^-126 times at most 54 (1 + M)^2,
//      M the largest row entry); decided when |value| exceeds that bound and M < 2^40 (so no
//      product overflows and no infinity or NaN reaches the comparison);
//   2. otherwise an exact evaluation in integer arithmetic, which GLSL specifies exactly
//      (umulExtended, uaddCarry, usubBorrow): D expanded into 24 products of three input
//      floats, each an exact 72-bit integer times a power of two, summed in a 864-bit
//      two's-complement fixed-point accumulator whose lowest bit is 2^-447 (three times the
//      smallest float exponent), so every product lands on it exactly and no sum overflows.
// With SHADOWCERT_FLOAT_SIGNS defined (the `--sign float` method), the sign is the float
// value's alone: Milet 2014's refedge, equal to exact/'s float32 refedge bit for bit. With
// SHADOWCERT_SIGN_FILTER_ONLY, stage 1 alone, 0 where it cannot decide (ts's control shader,
// which defers those records to a compute pass with stage 2).
#include "light_side_formula.glsl"

#ifndef SHADOWCERT_FLOAT_SIGNS

// Filter constants (see above): 8u = 2^-21; 2^-118 = 4 x 54 x 2^-126 rounded up to a power of
// two; 2^40 keeps |products| of three row entries below 2^121 (< the largest float).
const float kSignFilterRelative = 4.76837158203125e-07;       // 2^-21
const float kSignFilterFlushAllowance = 3.009265538105056e-36;  // 2^-118
const float kSignFilterLargestEntry = 1099511627776.0;        // 2^40

// Set by light_side_sign when the filter could not decide and the exact stage ran (read by
// the probe shader, light_side_probe.comp.glsl, to report the fallback rate).
bool light_side_used_fallback = false;

// 1 decided positive, -1 decided negative, 0 undecided.
int filtered_light_side(vec3 a, vec3 b, vec3 c) {
  precise float x0 = c.x - a.x;
  precise float x1 = c.y - a.y;
  precise float x2 = c.z - a.z;
  precise float y0 = light.x - a.x * light.w;
  precise float y1 = light.y - a.y * light.w;
  precise float y2 = light.z - a.z * light.w;
  precise float z0 = b.x - a.x;
  precise float z1 = b.y - a.y;
  precise float z2 = b.z - a.z;
  const float largest = max(max(max(abs(x0), abs(x1)), max(abs(x2), abs(y0))),
                            max(max(abs(y1), abs(y2)), max(abs(z0), max(abs(z1), abs(z2)))));
  if (!(largest < kSignFilterLargestEntry)) return 0;
  precise float value = light_side_value(a, b, c);
  precise float permanent = (abs(x1 * y2) + abs(x2 * y1)) * abs(z0) + (abs(x2 * y0) + abs(x0 * y2)) * abs(z1) +
                            (abs(x0 * y1) + abs(x1 * y0)) * abs(z2);
  precise float bound = kSignFilterRelative * permanent +
                        kSignFilterFlushAllowance * ((1.0 + largest) * (1.0 + largest));
  if (value > bound) return 1;
  if (-value > bound) return -1;
  return 0;
}

#ifdef SHADOWCERT_SIGN_FILTER_ONLY

// The filter alone (ts's control shader, tessellation_volume.tesc.glsl): 0 where it cannot
// decide, which sets light_side_undecided; the caller then defers the decision to a shader
// that has the exact stage.
bool light_side_undecided = false;

int light_side_sign(vec3 a, vec3 b, vec3 c) {
  const int filtered = filtered_light_side(a, b, c);
  if (filtered == 0) light_side_undecided = true;
  return filtered;
}

#else

// The exact stage. 27 limbs of 32 bits, little-endian; bit 0 weighs 2^-447. Every access to
// the accumulator has a constant index (the limb loop is written out by a macro): a local
// array indexed by a variable is lowered by some compilers (llvmpipe's) to a ladder of
// selects per access, which made one shader take seconds to compile.
uint sign_accumulator[27];

// One limb of accumulate(): the word of the added value at limb i (complemented when
// subtracting), plus the carry.
#define SHADOWCERT_LIMB(i) { const int j = i - k; uint w = j == 0 ? w0 : (j == 1 ? w1 : (j == 2 ? w2 : (j == 3 ? w3 : 0u))); if (negative) w = ~w; uint c1, c2; const uint r = uaddCarry(sign_accumulator[i], w, c1); sign_accumulator[i] = uaddCarry(r, carry, c2); carry = c1 + c2; }

// Adds the 104-bit value (w3 w2 w1 w0) at limb k, or subtracts it (`negative`): adding
// ~X + 1 over all 864 bits is subtracting X modulo 2^864, and the true sum stays below 2^836
// in magnitude, so the top bit is its sign.
void accumulate(int k, uint w0, uint w1, uint w2, uint w3, bool negative) {
  uint carry = negative ? 1u : 0u;
  SHADOWCERT_LIMB(0) SHADOWCERT_LIMB(1) SHADOWCERT_LIMB(2) SHADOWCERT_LIMB(3) SHADOWCERT_LIMB(4) SHADOWCERT_LIMB(5) SHADOWCERT_LIMB(6) SHADOWCERT_LIMB(7) SHADOWCERT_LIMB(8) SHADOWCERT_LIMB(9) SHADOWCERT_LIMB(10) SHADOWCERT_LIMB(11) SHADOWCERT_LIMB(12) SHADOWCERT_LIMB(13) SHADOWCERT_LIMB(14) SHADOWCERT_LIMB(15) SHADOWCERT_LIMB(16) SHADOWCERT_LIMB(17) SHADOWCERT_LIMB(18) SHADOWCERT_LIMB(19) SHADOWCERT_LIMB(20) SHADOWCERT_LIMB(21) SHADOWCERT_LIMB(22) SHADOWCERT_LIMB(23) SHADOWCERT_LIMB(24) SHADOWCERT_LIMB(25) SHADOWCERT_LIMB(26)
}

// A float's bits as (negative, integer significand m < 2^24, exponent e): the value is
// (-1)^negative m 2^e with e >= -149 (floatBitsToUint reads the bits: no arithmetic, so a
// denormal input keeps its value).
void split_float(float f, out bool negative, out uint m, out int e) {
  const uint bits = floatBitsToUint(f);
  negative = (bits >> 31) != 0u;
  const uint biased = (bits >> 23) & 0xFFu;
  const uint fraction = bits & 0x7FFFFFu;
  m = biased == 0u ? fraction : (fraction | 0x800000u);
  e = biased == 0u ? -149 : int(biased) - 150;
}

// Accumulates +-(x y z) exactly.
void accumulate_product(float x, float y, float z, bool negative) {
  bool nx, ny, nz;
  uint mx, my, mz;
  int ex, ey, ez;
  split_float(x, nx, mx, ex);
  split_float(y, ny, my, ey);
  split_float(z, nz, mz, ez);
  if (mx == 0u || my == 0u || mz == 0u) return;
  // mx my (48 bits) as (h1, l1); times mz: l1 mz = (c1, c0), h1 mz = (d1, d0); 72 bits (r2 r1 r0).
  uint h1, l1, c1, c0, d1, d0, carry;
  umulExtended(mx, my, h1, l1);
  umulExtended(l1, mz, c1, c0);
  umulExtended(h1, mz, d1, d0);
  const uint r0 = c0;
  const uint r1 = uaddCarry(c1, d0, carry);
  const uint r2 = d1 + carry;
  const int position = ex + ey + ez + 447;  // in [0, 759]
  const uint s = uint(position & 31);
  // A shift by 32 is undefined in GLSL: s = 0 takes no bits from the word below.
  accumulate(position >> 5, r0 << s, (r1 << s) | (s == 0u ? 0u : r0 >> (32u - s)),
             (r2 << s) | (s == 0u ? 0u : r1 >> (32u - s)), s == 0u ? 0u : r2 >> (32u - s),
             negative != (nx != (ny != nz)));
}

// det[b - a, c - a, l - w a] = det[b, c, l] - det[a, c, l] + det[a, b, l] - w det[a, b, c]
// (multilinearity: the terms with two rows `a` vanish): 4 determinants of 6 products each,
// one loop over a table (one copy of the accumulation in the compiled shader, not 24).
const int kDeterminantRows[12] = int[12](1, 2, 3, 0, 2, 3, 0, 1, 3, 0, 1, 2);  // a b c l = 0 1 2 3
const bool kDeterminantNegative[4] = bool[4](false, true, false, true);
// The six permutations (i, j, k) of the columns and whether each is odd.
const int kPermutationColumns[18] = int[18](0, 1, 2, 0, 2, 1, 1, 0, 2, 1, 2, 0, 2, 0, 1, 2, 1, 0);
const bool kPermutationOdd[6] = bool[6](false, true, true, false, false, true);

int exact_light_side(vec3 a, vec3 b, vec3 c) {
  sign_accumulator[0] = 0u; sign_accumulator[1] = 0u; sign_accumulator[2] = 0u; sign_accumulator[3] = 0u; sign_accumulator[4] = 0u; sign_accumulator[5] = 0u; sign_accumulator[6] = 0u; sign_accumulator[7] = 0u; sign_accumulator[8] = 0u; sign_accumulator[9] = 0u; sign_accumulator[10] = 0u; sign_accumulator[11] = 0u; sign_accumulator[12] = 0u; sign_accumulator[13] = 0u; sign_accumulator[14] = 0u; sign_accumulator[15] = 0u; sign_accumulator[16] = 0u; sign_accumulator[17] = 0u; sign_accumulator[18] = 0u; sign_accumulator[19] = 0u; sign_accumulator[20] = 0u; sign_accumulator[21] = 0u; sign_accumulator[22] = 0u; sign_accumulator[23] = 0u; sign_accumulator[24] = 0u; sign_accumulator[25] = 0u; sign_accumulator[26] = 0u;
  const vec3 points[4] = vec3[4](a, b, c, light.xyz);
  const int determinants = light.w != 0.0 ? 4 : 3;  // w is 0 or 1
  for (int term = 0; term < 6 * determinants; ++term) {
    const int d = term / 6;
    const int p = term - 6 * d;
    const vec3 r0 = points[kDeterminantRows[3 * d]];
    const vec3 r1 = points[kDeterminantRows[3 * d + 1]];
    const vec3 r2 = points[kDeterminantRows[3 * d + 2]];
    accumulate_product(r0[kPermutationColumns[3 * p]], r1[kPermutationColumns[3 * p + 1]],
                       r2[kPermutationColumns[3 * p + 2]], kDeterminantNegative[d] != kPermutationOdd[p]);
  }
  if ((sign_accumulator[26] >> 31) != 0u) return -1;
  return (sign_accumulator[26] | sign_accumulator[0] | sign_accumulator[1] | sign_accumulator[2] | sign_accumulator[3] | sign_accumulator[4] | sign_accumulator[5] | sign_accumulator[6] | sign_accumulator[7] | sign_accumulator[8] | sign_accumulator[9] | sign_accumulator[10] | sign_accumulator[11] | sign_accumulator[12] | sign_accumulator[13] | sign_accumulator[14] | sign_accumulator[15] | sign_accumulator[16] | sign_accumulator[17] | sign_accumulator[18] | sign_accumulator[19] | sign_accumulator[20] | sign_accumulator[21] | sign_accumulator[22] | sign_accumulator[23] | sign_accumulator[24] | sign_accumulator[25]) != 0u ? 1 : 0;
}

int light_side_sign(vec3 a, vec3 b, vec3 c) {
  const int filtered = filtered_light_side(a, b, c);
  if (filtered != 0) return filtered;
  light_side_used_fallback = true;
  return exact_light_side(a, b, c);
}

#endif  // SHADOWCERT_SIGN_FILTER_ONLY

#else

int light_side_sign(vec3 a, vec3 b, vec3 c) {
  const float value = light_side_value(a, b, c);
  return value > 0.0 ? 1 : (value < 0.0 ? -1 : 0);
}

#endif
