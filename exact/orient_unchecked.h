#pragma once
// Internal to exact/: `orient` of exact/light_orientation.h without its argument validation,
// for inner loops (crossing tests) whose points were validated once: soup vertices, sample
// points and a checked light. Same stages, same answers.
// Preconditions (unchecked): finite coordinates, every w in {0, 1}, at most one w = 0, and no
// (0, 0, 0, 0).
#include "core/sign.h"
#include "exact/light_orientation.h"

namespace shadowcert::detail {

[[nodiscard]] Sign orient_unchecked(const HomogeneousPoint& p, const HomogeneousPoint& q, const HomogeneousPoint& r,
                                    const HomogeneousPoint& s);

}  // namespace shadowcert::detail
