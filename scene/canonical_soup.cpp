#include "scene/canonical_soup.h"

#include <algorithm>
#include <numeric>

#include "scene/welded_soup.h"

namespace shadowcert {

CanonicalSoup canonical_soup(const Soup& soup) {
  WeldedSoup welded = weld_soup(soup);
  const std::vector<Vec3>& p = welded.soup.vertices;

  // Welded positions are pairwise distinct (with -0 == +0, which compares equal here too),
  // so this lexicographic order is strict.
  std::vector<std::uint32_t> order(p.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&p](std::uint32_t a, std::uint32_t b) { return p[a] < p[b]; });

  std::vector<std::uint32_t> rank(p.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) rank[order[i]] = i;

  CanonicalSoup out;
  out.soup.vertices.reserve(p.size());
  for (std::uint32_t old : order) out.soup.vertices.push_back(p[old]);
  if (!welded.soup.normals.empty()) {
    out.soup.normals.reserve(p.size());
    for (std::uint32_t old : order) out.soup.normals.push_back(welded.soup.normals[old]);
  }
  out.soup.triangles.reserve(welded.soup.triangles.size());
  for (const Triangle& t : welded.soup.triangles) out.soup.triangles.push_back({rank[t[0]], rank[t[1]], rank[t[2]]});
  out.canonical_id.resize(welded.welded_id.size());
  for (std::size_t i = 0; i < welded.welded_id.size(); ++i) out.canonical_id[i] = rank[welded.welded_id[i]];
  return out;
}

}  // namespace shadowcert
