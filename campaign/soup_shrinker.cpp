#include "campaign/soup_shrinker.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace shadowcert {
namespace {

using Subset = std::vector<std::size_t>;  // indices of the input's triangles, ascending

Soup with_triangles(const Soup& soup, const Subset& subset) {
  Soup s;
  s.vertices = soup.vertices;
  s.triangles.reserve(subset.size());
  for (std::size_t i : subset) s.triangles.push_back(soup.triangles[i]);
  return s;
}

// Only the vertices the triangles use, in their original order.
Soup compacted(const Soup& soup) {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> id(soup.vertices.size(), kUnused);
  for (const Triangle& t : soup.triangles)
    for (std::uint32_t i : t) id[i] = 0;
  Soup s;
  for (std::size_t i = 0; i < id.size(); ++i) {
    if (id[i] == kUnused) continue;
    id[i] = static_cast<std::uint32_t>(s.vertices.size());
    s.vertices.push_back(soup.vertices[i]);
  }
  for (const Triangle& t : soup.triangles) s.triangles.push_back({id[t[0]], id[t[1]], id[t[2]]});
  return s;
}

// The n near-equal consecutive chunks of `subset` (n <= size).
std::vector<Subset> chunks(const Subset& subset, std::size_t n) {
  std::vector<Subset> out(n);
  for (std::size_t k = 0; k < n; ++k)
    out[k].assign(subset.begin() + static_cast<std::ptrdiff_t>(subset.size() * k / n),
                  subset.begin() + static_cast<std::ptrdiff_t>(subset.size() * (k + 1) / n));
  return out;
}

Subset without(const Subset& subset, const Subset& removed) {
  Subset out;
  std::set_difference(subset.begin(), subset.end(), removed.begin(), removed.end(), std::back_inserter(out));
  return out;
}

}  // namespace

ShrinkResult shrink_soup(const Soup& soup, const std::function<bool(const Soup&)>& still_fails, std::size_t max_tests) {
  if (max_tests == 0) throw std::invalid_argument("shrink_soup: max_tests must be at least 1");
  require_indices_in_range(soup, "shrink_soup");
  ShrinkResult result;
  Soup plain = soup;
  plain.normals.clear();
  result.tests = 1;
  if (!still_fails(plain)) {
    result.soup = soup;
    return result;
  }
  bool out_of_tests = false;
  auto fails = [&](const Subset& subset) {
    if (result.tests >= max_tests) {
      out_of_tests = true;
      return false;
    }
    ++result.tests;
    return still_fails(with_triangles(plain, subset));
  };
  Subset current(plain.triangles.size());
  for (std::size_t i = 0; i < current.size(); ++i) current[i] = i;
  // ddmin: try each of n chunks alone, then (for n > 2, where they differ from the chunks)
  // each complement; on success restart coarser, otherwise split finer, until the chunks are
  // single triangles and none can go.
  std::size_t n = 2;
  while (current.size() >= 2 && !out_of_tests) {
    const std::vector<Subset> parts = chunks(current, std::min(n, current.size()));
    bool reduced = false;
    for (const Subset& part : parts) {
      if (fails(part)) {
        current = part;
        n = 2;
        reduced = true;
        break;
      }
    }
    if (!reduced && parts.size() > 2) {
      for (const Subset& part : parts) {
        Subset rest = without(current, part);
        if (fails(rest)) {
          current = std::move(rest);
          n = std::max<std::size_t>(parts.size() - 1, 2);
          reduced = true;
          break;
        }
      }
    }
    if (reduced) continue;
    if (parts.size() >= current.size()) break;  // single triangles, none removable: 1-minimal
    n = std::min(2 * parts.size(), current.size());
  }
  result.minimal = !out_of_tests;
  result.soup = with_triangles(plain, current);
  const Soup small = compacted(result.soup);
  if (small.vertices.size() < result.soup.vertices.size() && result.tests < max_tests) {
    ++result.tests;
    if (still_fails(small)) result.soup = small;
  }
  return result;
}

}  // namespace shadowcert
