#pragma once
// When may a float method's sign of D(a, b, c, L) differ from the exact one (docs/definitions.md#orientation, docs/definitions.md#counts)?
// Only where its own precision cannot decide it. A float method (kim, peciva, refedge; CPU or
// shader) rounds a, b, c and the light to its precision, then evaluates
// core/light_side_formula.h, in some vertex order. Forward error analysis of that evaluation
// (input rounding and eleven rounded operations, unit roundoff u = 2^-24 for float, 2^-53 for
// double) bounds the difference between the value it computes and the exact determinant D:
//
//   |value - D| <= 12 u M + A,   M = max over the first vertex a of perm(X, Y, Z),
//
// perm the permanent (the determinant with every sign +; it is symmetric in the two other
// vertices, so the first vertex is the only choice that matters) of the rows' magnitudes
//   float  (inputs rounded to float first): X_i = |c_i| + |a_i|, Y_i = |l_i| + w |a_i|,
//          Z_i = |b_i| + |a_i|: rounding an input moves it relative to its own magnitude;
//   double (inputs used as they are):       X_i = |c_i - a_i|, Y_i = |l_i - w a_i|,
//          Z_i = |b_i - a_i|: only the difference rounds, relative to itself;
// and A a generous allowance for underflow (16 * the smallest normal of the precision, scaled
// by the magnitudes). The terms: input rounding and the differences give each row entry a
// relative error (to its magnitude above) of at most 2u + u^2, so at most (1 + 2u + u^2)^3 - 1
// < 6.1u on a product of three; the cross and dot products add at most gamma_5 < 5.1u per
// monomial; 11.2u < 12u.
//
// So wherever |D| > 12 u M + A, every evaluation in that precision, in any order, has the exact
// sign: the triangle is *decided* at that precision, and a method whose sign differs there has
// a bug, not a rounding. Where |D| is within the bound the triangle is *undecided*: a float
// method may legitimately give it any sign (docs/campaign.md, "right counts").
#include "core/light.h"
#include "core/soup.h"
#include "exact/edge_multiplicity.h"

namespace shadowcert {

// True iff |D(a, b, c, L)| certainly exceeds the bound above for `precision` (the test is done in
// interval arithmetic on the input doubles: "certainly" is exact, never rounded towards true).
// A degenerate triangle (D = 0) is never decided. Throws std::invalid_argument
// ("float_sign_is_decided: ...") on a light with a non-finite coordinate or w not 0 or 1.
[[nodiscard]] bool float_sign_is_decided(const Vec3& a, const Vec3& b, const Vec3& c, const Light& light,
                                         Precision precision);

}  // namespace shadowcert
