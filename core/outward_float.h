#pragma once
// Outward roundings of a double to float: round_down_to_float(x) <= x <= round_up_to_float(x)
// for every finite x of magnitude below 2^127 (beyond it the float is infinite, still outside
// x). Used where a float copy of a double only encloses it: the box tree's 4-wide float nodes
// (exact/box_tree.cpp) and the exact image's per-ray hit-point boxes
// (reference/detail/hit_point_boxes.h); every exact answer is decided on the doubles.
//
// In arithmetic (no libm call, no comparison): the nearest float d moved out by
// |d| 2^-22 + 2^-149, more than its rounding (2^-24 |x| for a normal float, 2^-150 for a
// subnormal) and the step's own. Were the round trip through float folded away (GCC has been
// seen to, core/float_rounding.h), the move in double and its final rounding to float (2^-24)
// would still stay outside x. So the bound is loose by about 2^-22 relative: fine for a filter.
#include <cmath>

namespace shadowcert {

[[nodiscard]] inline float round_down_to_float(double x) {
  const float d = static_cast<float>(x);
  return d - (std::fabs(d) * 0x1p-22f + 0x1p-149f);
}

[[nodiscard]] inline float round_up_to_float(double x) {
  const float d = static_cast<float>(x);
  return d + (std::fabs(d) * 0x1p-22f + 0x1p-149f);
}

}  // namespace shadowcert
