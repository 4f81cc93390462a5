#include "scene/edge_table.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/huge_page_advice.h"

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
//
// In parallel: the triangles are cut into fixed chunks (their number depends on the soup, not
// on the threads), each chunk counts its uses per coarse bucket, and chunk c's uses of bucket b
// go after those of chunks before c: the scatter writes exactly what the sequential pass
// writes. The buckets are then sorted independently, and the rows written at offsets known from
// a prefix sum of each bucket's edge count. So the table is the same on any number of threads.
constexpr unsigned kCoarseBits = 12;  // at most 4096 buckets: write streams the caches can hold
constexpr std::size_t kChunkTriangles = std::size_t{1} << 16;

struct CoarseBuckets {
  unsigned shift = 0;                 // coarse bucket of vertex u: u >> shift
  std::size_t count = 0;              // number of buckets
  std::vector<std::uint32_t> start;   // offsets into the use array, size count + 1
  // cursor[c * count + b]: where chunk c writes its first use of bucket b.
  std::vector<std::uint32_t> cursor;
};

std::size_t chunk_count(std::size_t triangles) { return (triangles + kChunkTriangles - 1) / kChunkTriangles; }

// The first triangle with an index >= n (triangles.size() if none), as a sequential scan finds it.
std::size_t first_bad_triangle(const std::vector<Triangle>& triangles, std::size_t n) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, triangles.size(), kChunkTriangles), triangles.size(),
      [&](const tbb::blocked_range<std::size_t>& r, std::size_t found) {
        for (std::size_t t = r.begin(); t < r.end() && t < found; ++t)
          if (triangles[t][0] >= n || triangles[t][1] >= n || triangles[t][2] >= n) return t;
        return found;
      },
      [](std::size_t a, std::size_t b) { return std::min(a, b); });
}

CoarseBuckets count_coarse_buckets(const Soup& canonical) {
  const std::size_t n = canonical.vertices.size();
  const std::vector<Triangle>& triangles = canonical.triangles;
  if (triangles.size() > std::numeric_limits<std::uint32_t>::max() / 3)
    throw std::invalid_argument("build_edge_table: more than 2^32 / 3 triangles do not fit 32-bit entry offsets");
  const std::size_t bad = first_bad_triangle(triangles, n);
  if (bad < triangles.size()) {
    const Triangle& tri = triangles[bad];
    const std::uint32_t v = tri[0] >= n ? tri[0] : tri[1] >= n ? tri[1] : tri[2];
    throw std::invalid_argument("build_edge_table: triangle " + std::to_string(bad) + " has index " +
                                std::to_string(v) + " but the soup has " + std::to_string(n) + " vertices");
  }
  CoarseBuckets buckets;
  const auto bits = static_cast<unsigned>(std::bit_width(n));
  buckets.shift = bits > kCoarseBits ? bits - kCoarseBits : 0;
  buckets.count = (n >> buckets.shift) + 1;
  const std::size_t chunks = chunk_count(triangles.size());
  buckets.cursor.assign(chunks * buckets.count, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c < r.end(); ++c) {
      std::uint32_t* count = buckets.cursor.data() + c * buckets.count;
      const std::size_t last = std::min(triangles.size(), (c + 1) * kChunkTriangles);
      for (std::size_t t = c * kChunkTriangles; t < last; ++t) {
        const Triangle& tri = triangles[t];
        if (has_repeated_index(tri)) continue;  // no edges (edge_table.h)
        for (int k = 0; k < 3; ++k) ++count[std::min(tri[k], tri[(k + 1) % 3]) >> buckets.shift];
      }
    }
  });
  // Bucket-major prefix sum: bucket b's uses, chunk by chunk, then bucket b + 1's.
  buckets.start.assign(buckets.count + 1, 0);
  std::uint32_t offset = 0;
  for (std::size_t b = 0; b < buckets.count; ++b) {
    buckets.start[b] = offset;
    for (std::size_t c = 0; c < chunks; ++c) {
      std::uint32_t& slot = buckets.cursor[c * buckets.count + b];
      const std::uint32_t uses = slot;
      slot = offset;
      offset += uses;
    }
  }
  buckets.start[buckets.count] = offset;
  return buckets;
}

// Uninitialised: the scatter writes every entry.
HugePageBuffer<EdgeUse> scatter_coarse(const Soup& canonical, CoarseBuckets& buckets) {
  HugePageBuffer<EdgeUse> uses(buckets.start.back());
  const std::vector<Triangle>& triangles = canonical.triangles;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunk_count(triangles.size()), 1),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c < r.end(); ++c) {
                        std::uint32_t* cursor = buckets.cursor.data() + c * buckets.count;
                        const std::size_t last = std::min(triangles.size(), (c + 1) * kChunkTriangles);
                        for (std::size_t t = c * kChunkTriangles; t < last; ++t) {
                          const Triangle& tri = triangles[t];
                          if (has_repeated_index(tri)) continue;
                          for (int k = 0; k < 3; ++k) {
                            const std::uint32_t a = tri[k], b = tri[(k + 1) % 3], o = tri[(k + 2) % 3];
                            const std::uint32_t lower = std::min(a, b);
                            uses[cursor[lower >> buckets.shift]++] = {lower, std::max(a, b), o,
                                                                      static_cast<std::uint32_t>(t)};
                          }
                        }
                      }
                    });
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

bool same_edge(const EdgeUse& a, const EdgeUse& b) { return a.lower == b.lower && a.upper == b.upper; }

// Sorts the uses of one coarse bucket, whose lower vertices lie in [base, base + 2^shift), and
// writes its rows' opposite entries straight into the table: a local counting sort by lower
// vertex, then by upper. The bucket's edges are left compacted at the front of its own range of
// uses (lower, upper, and the index of the edge's first use in `opposite`), for build_edge_table
// to copy once their global numbers are known: the uses are not written back, so the last pass
// reads the edges (half as many, on a manifold mesh) rather than every use again.
// Returns the bucket's number of edges.
class BucketSorter {
 public:
  explicit BucketSorter(unsigned shift) : count_((std::size_t{1} << shift) + 1) {}

  std::uint32_t sort(EdgeUse* first, EdgeUse* last, std::uint32_t base, std::uint32_t first_use, EdgeTable& table) {
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
    std::uint32_t edges = 0;
    std::uint32_t* opposite_vertex = table.opposite_vertex.data() + first_use;
    std::uint32_t* opposite_triangle = table.opposite_triangle.data() + first_use;
    for (std::size_t j = 0; j < sorted_.size(); ++j) {
      const EdgeUse& e = sorted_[j];
      // Edge k's entry overwrites use k <= j, already copied into sorted_.
      if (j == 0 || !same_edge(e, sorted_[j - 1]))
        first[edges++] = {e.lower, e.upper, first_use + static_cast<std::uint32_t>(j), 0};
      opposite_vertex[j] = e.opposite;
      opposite_triangle[j] = e.triangle;
    }
    return edges;
  }

 private:
  std::vector<std::uint32_t> count_;
  std::vector<EdgeUse> sorted_;
};

}  // namespace

EdgeTable build_edge_table(const Soup& canonical) {
  CoarseBuckets buckets = count_coarse_buckets(canonical);
  HugePageBuffer<EdgeUse> uses = scatter_coarse(canonical, buckets);
  const std::size_t bucket_count = buckets.count;

  EdgeTable table;
  // Each resize zero-fills (and first touches) its storage on one thread: side by side.
  tbb::parallel_invoke([&] { resize_huge(table.opposite_vertex, uses.size()); },
                       [&] { resize_huge(table.opposite_triangle, uses.size()); });
  // Each bucket sorted, its opposite entries written; edge_start[b + 1] its number of edges,
  // then (prefix) edge_start[b] its first.
  std::vector<std::uint32_t> edge_start(bucket_count + 1, 0);
  tbb::enumerable_thread_specific<BucketSorter> sorters(buckets.shift);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bucket_count, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    BucketSorter& sorter = sorters.local();
    for (std::size_t b = r.begin(); b < r.end(); ++b)
      if (buckets.start[b] < buckets.start[b + 1])
        edge_start[b + 1] = sorter.sort(uses.data() + buckets.start[b], uses.data() + buckets.start[b + 1],
                                        static_cast<std::uint32_t>(b << buckets.shift), buckets.start[b], table);
  });
  for (std::size_t b = 1; b <= bucket_count; ++b) edge_start[b] += edge_start[b - 1];

  tbb::parallel_invoke([&] { resize_huge(table.edges, edge_start.back()); },
                       [&] { resize_huge(table.first_opposite, edge_start.back() + 1); });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bucket_count, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b < r.end(); ++b) {
      const EdgeUse* compacted = uses.data() + buckets.start[b];
      for (std::uint32_t edge = edge_start[b]; edge < edge_start[b + 1]; ++edge, ++compacted) {
        table.edges[edge] = {compacted->lower, compacted->upper};
        table.first_opposite[edge] = compacted->opposite;  // the edge's first use (BucketSorter::sort)
      }
    }
  });
  table.first_opposite.back() = static_cast<std::uint32_t>(uses.size());
  return table;
}

}  // namespace shadowcert
