#include "scene/canonical_soup.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace shadowcert {
namespace {

// One record per input vertex. Sorting records by (position, input index) welds and orders in
// one pass: bitwise-equal positions (and -0 == +0, which compare equal as doubles, docs/definitions.md#inputs
// ) become adjacent, and the lexicographic order of the groups is the canonical order.
// Readers have rejected NaN, so double comparison is a strict weak order here.
struct VertexRecord {
  Vec3 position;
  std::uint32_t input_index;
};

bool record_less(const VertexRecord& a, const VertexRecord& b) {
  if (a.position != b.position) return a.position < b.position;
  return a.input_index < b.input_index;
}

}  // namespace

CanonicalSoup canonical_soup(const Soup& soup) {
  const std::size_t n = soup.vertices.size();
  const bool has_normals = !soup.normals.empty();
  if (has_normals && soup.normals.size() != n)
    throw std::invalid_argument("canonical_soup: normals must be empty or one per vertex");

  std::vector<VertexRecord> records(n);
  for (std::size_t i = 0; i < n; ++i) records[i] = {soup.vertices[i], static_cast<std::uint32_t>(i)};
  std::sort(records.begin(), records.end(), record_less);

  CanonicalSoup out;
  out.canonical_id.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const VertexRecord& r = records[i];
    // A new group starts where the position changes; its first record has the smallest input
    // index, whose coordinates (and normal) are kept verbatim, as weld_soup keeps them.
    if (i == 0 || r.position != records[i - 1].position) {
      out.soup.vertices.push_back(r.position);
      if (has_normals) out.soup.normals.push_back(soup.normals[r.input_index]);
    }
    out.canonical_id[r.input_index] = static_cast<std::uint32_t>(out.soup.vertices.size() - 1);
  }

  out.soup.triangles.reserve(soup.triangles.size());
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    Triangle mapped{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = soup.triangles[t][k];
      if (v >= n)
        throw std::invalid_argument("canonical_soup: triangle " + std::to_string(t) + " has index " +
                                    std::to_string(v) + " but the soup has " + std::to_string(n) + " vertices");
      mapped[k] = out.canonical_id[v];
    }
    out.soup.triangles.push_back(mapped);
  }
  return out;
}

}  // namespace shadowcert
