#pragma once
// Shrinking a failing soup to a small one that still fails: delta debugging over its triangles
// (Zeller and Hildebrandt 2002, "Simplifying and isolating failure-inducing input", ddmin),
// then dropping the vertices no triangle uses. The random-soup campaign (docs/campaign.md) shrinks
// every reproducer it writes this way; the test is any predicate, so tests plant faults too.
#include <cstddef>
#include <functional>

#include "core/soup.h"

namespace shadowcert {

struct ShrinkResult {
  Soup soup;              // the smallest failing soup found
  std::size_t tests = 0;  // calls of the predicate
  bool minimal = false;   // 1-minimal: removing any one of its triangles makes it pass
};

// `still_fails` must be deterministic. When it does not hold for `soup` itself, the soup comes
// back unchanged (tests = 1, minimal = false). Otherwise the result's triangles are a subset of
// the soup's, in their order, and its vertices, in their order, only those its triangles use
// (unless renumbering them made the failure go away); shading normals are dropped. At most
// `max_tests` predicate calls (>= 1); minimal is false when they ran out first.
[[nodiscard]] ShrinkResult shrink_soup(const Soup& soup, const std::function<bool(const Soup&)>& still_fails,
                                       std::size_t max_tests = 4000);

}  // namespace shadowcert
