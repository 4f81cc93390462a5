#include "scene/edge_table.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <stdexcept>
#include <string>

namespace shadowcert {
namespace {

// One use of an undirected edge {lower, upper} by a triangle, with its opposite vertex.
struct EdgeUse {
  std::uint32_t lower;
  std::uint32_t upper;
  std::uint32_t opposite;
  std::uint32_t triangle;
};

bool has_repeated_index(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

// The table is a sort of all edge uses by (lower, upper, triangle), done as a two-level
// counting sort on `lower`: a first pass scatters the uses into a few thousand coarse buckets
// of consecutive lower vertices (few write streams: cache-friendly, unlike a direct scatter
// into one bucket per vertex), a second sorts each coarse bucket, small enough to stay in
// cache, by lower vertex and then by upper vertex. Both passes are stable and triangles are
// read in ascending order, so uses of one edge end up in ascending triangle order.
struct CoarseBuckets {
  unsigned shift = 0;                 // coarse bucket of vertex u: u >> shift
  std::vector<std::uint32_t> start;   // offsets into the use array, size buckets + 1
};

CoarseBuckets count_coarse_buckets(const Soup& canonical) {
  const std::size_t n = canonical.vertices.size();
  if (canonical.triangles.size() > std::numeric_limits<std::uint32_t>::max() / 3)
    throw std::invalid_argument("build_edge_table: more than 2^32 / 3 triangles do not fit 32-bit entry offsets");
  CoarseBuckets buckets;
  constexpr unsigned kCoarseBits = 12;  // at most 4096 buckets: write streams the caches can hold
  const auto bits = static_cast<unsigned>(std::bit_width(n));
  buckets.shift = bits > kCoarseBits ? bits - kCoarseBits : 0;
  buckets.start.assign((n >> buckets.shift) + 2, 0);
  for (std::size_t t = 0; t < canonical.triangles.size(); ++t) {
    const Triangle& tri = canonical.triangles[t];
    for (std::uint32_t v : tri)
      if (v >= n)
        throw std::invalid_argument("build_edge_table: triangle " + std::to_string(t) + " has index " +
                                    std::to_string(v) + " but the soup has " + std::to_string(n) + " vertices");
    if (has_repeated_index(tri)) continue;  // no edges (edge_table.h)
    for (int k = 0; k < 3; ++k) ++buckets.start[(std::min(tri[k], tri[(k + 1) % 3]) >> buckets.shift) + 1];
  }
  for (std::size_t i = 1; i < buckets.start.size(); ++i) buckets.start[i] += buckets.start[i - 1];
  return buckets;
}

std::vector<EdgeUse> scatter_coarse(const Soup& canonical, const CoarseBuckets& buckets) {
  std::vector<EdgeUse> uses(buckets.start.back());
  std::vector<std::uint32_t> cursor(buckets.start.begin(), buckets.start.end() - 1);
  for (std::uint32_t t = 0; t < canonical.triangles.size(); ++t) {
    const Triangle& tri = canonical.triangles[t];
    if (has_repeated_index(tri)) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3], o = tri[(k + 2) % 3];
      const std::uint32_t lower = std::min(a, b);
      uses[cursor[lower >> buckets.shift]++] = {lower, std::max(a, b), o, t};
    }
  }
  return uses;
}

// Stable sort of the uses of one lower vertex by upper vertex. A vertex has about six uses on
// a manifold mesh, so insertion sort is the fast case; a vertex shared by very many triangles
// (a fan, a cone apex) takes the O(k log k) path.
void sort_by_upper(EdgeUse* first, EdgeUse* last) {
  constexpr std::ptrdiff_t kInsertionLimit = 48;
  const auto by_upper = [](const EdgeUse& x, const EdgeUse& y) { return x.upper < y.upper; };
  if (last - first > kInsertionLimit) {
    std::stable_sort(first, last, by_upper);
    return;
  }
  for (EdgeUse* i = first + 1; i < last; ++i) {
    const EdgeUse moving = *i;
    EdgeUse* j = i;
    for (; j > first && moving.upper < (j - 1)->upper; --j) *j = *(j - 1);
    *j = moving;
  }
}

// Appends the uses of one coarse bucket, whose lower vertices lie in [base, base + 2^shift),
// to the table: a local counting sort by lower vertex, then by upper, then the rows.
class BucketSorter {
 public:
  explicit BucketSorter(unsigned shift) : count_((std::size_t{1} << shift) + 1) {}

  void append(const EdgeUse* first, const EdgeUse* last, std::uint32_t base, std::uint32_t offset,
              EdgeTable& table) {
    std::fill(count_.begin(), count_.end(), 0u);
    for (const EdgeUse* e = first; e < last; ++e) ++count_[e->lower - base + 1];
    for (std::size_t i = 1; i < count_.size(); ++i) count_[i] += count_[i - 1];
    sorted_.resize(static_cast<std::size_t>(last - first));
    for (const EdgeUse* e = first; e < last; ++e) sorted_[count_[e->lower - base]++] = *e;
    // count_[i] is now the end of lower vertex base + i.
    std::uint32_t begin = 0;
    for (std::size_t i = 0; i + 1 < count_.size() && begin < sorted_.size(); ++i) {
      sort_by_upper(sorted_.data() + begin, sorted_.data() + count_[i]);
      begin = count_[i];
    }
    for (std::size_t j = 0; j < sorted_.size(); ++j) {
      const EdgeUse& e = sorted_[j];
      if (j == 0 || e.upper != sorted_[j - 1].upper || e.lower != sorted_[j - 1].lower) {
        table.edges.push_back({e.lower, e.upper});
        table.first_opposite.push_back(offset + static_cast<std::uint32_t>(j));
      }
      table.opposite_vertex[offset + j] = e.opposite;
      table.opposite_triangle[offset + j] = e.triangle;
    }
  }

 private:
  std::vector<std::uint32_t> count_;
  std::vector<EdgeUse> sorted_;
};

}  // namespace

EdgeTable build_edge_table(const Soup& canonical) {
  const CoarseBuckets buckets = count_coarse_buckets(canonical);
  const std::vector<EdgeUse> uses = scatter_coarse(canonical, buckets);

  EdgeTable table;
  table.opposite_vertex.resize(uses.size());
  table.opposite_triangle.resize(uses.size());
  // A closed manifold mesh has exactly two uses per edge: a good first guess.
  table.edges.reserve(uses.size() / 2 + 1);
  table.first_opposite.reserve(uses.size() / 2 + 2);
  BucketSorter sorter(buckets.shift);
  for (std::size_t c = 0; c + 1 < buckets.start.size(); ++c) {
    if (buckets.start[c] == buckets.start[c + 1]) continue;
    sorter.append(uses.data() + buckets.start[c], uses.data() + buckets.start[c + 1],
                  static_cast<std::uint32_t>(c << buckets.shift), buckets.start[c], table);
  }
  table.first_opposite.push_back(static_cast<std::uint32_t>(uses.size()));
  return table;
}

}  // namespace shadowcert
