#include "exact/triangle_soup_topology.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "exact/degenerate_triangles.h"

namespace shadowcert {
namespace {

// For every vertex, the triangles (with three distinct indices) that use it, in CSR form.
// Built by counting sort, so linear time; every edge and fan question below is then local to
// one vertex, which makes the pass embarrassingly parallel and free of global hash tables.
struct VertexTriangles {
  std::vector<std::size_t> offsets;  // size vertices + 1
  std::vector<std::uint32_t> triangles;
};

void check_indices(const Soup& soup) {
  // Triangles are named by 32-bit indices in the union-find, like vertices in Soup.
  if (soup.triangles.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("analyze_topology: more than 2^32 - 1 triangles");
  const std::size_t n = soup.vertices.size();
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    for (std::uint32_t v : soup.triangles[t])
      if (v >= n)
        throw std::invalid_argument("analyze_topology: triangle " + std::to_string(t) + " has index " +
                                    std::to_string(v) + " but the soup has " + std::to_string(n) + " vertices");
}

VertexTriangles vertex_triangles(const Soup& soup) {
  VertexTriangles vt;
  vt.offsets.assign(soup.vertices.size() + 1, 0);
  for (const Triangle& t : soup.triangles)
    if (has_distinct_indices(t))
      for (std::uint32_t v : t) ++vt.offsets[v + 1];
  for (std::size_t v = 0; v < soup.vertices.size(); ++v) vt.offsets[v + 1] += vt.offsets[v];
  vt.triangles.resize(vt.offsets.back());
  std::vector<std::size_t> cursor(vt.offsets.begin(), vt.offsets.end() - 1);
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (has_distinct_indices(soup.triangles[t]))
      for (std::uint32_t v : soup.triangles[t]) vt.triangles[cursor[v]++] = static_cast<std::uint32_t>(t);
  return vt;
}

// Lock-free union-find over triangles (root = smallest index of its class): each vertex task
// unites the triangles around the edges it owns, concurrently with the others. A root is
// only ever relinked by a successful compare-exchange that still sees it as a root, and
// parents only decrease, so no cycle can form.
class ConcurrentDisjointSets {
 public:
  explicit ConcurrentDisjointSets(std::size_t n) : parent_(n) {
    for (std::size_t i = 0; i < n; ++i) parent_[i].store(static_cast<std::uint32_t>(i), std::memory_order_relaxed);
  }
  std::uint32_t find(std::uint32_t x) {
    for (;;) {
      std::uint32_t p = parent_[x].load(std::memory_order_relaxed);
      if (p == x) return x;
      const std::uint32_t grandparent = parent_[p].load(std::memory_order_relaxed);
      if (grandparent != p) parent_[x].compare_exchange_weak(p, grandparent, std::memory_order_relaxed);  // halving
      x = grandparent;
    }
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    for (;;) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);
      std::uint32_t expected = a;
      if (parent_[a].compare_exchange_strong(expected, b)) return;
    }
  }

 private:
  std::vector<std::atomic<std::uint32_t>> parent_;
};

// Sequential union-find over the few triangles around one vertex (local indices).
class LocalDisjointSets {
 public:
  void reset(std::size_t n) {
    parent_.resize(n);
    for (std::size_t i = 0; i < n; ++i) parent_[i] = static_cast<std::uint32_t>(i);
    classes_ = n;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    parent_[std::max(a, b)] = std::min(a, b);
    --classes_;
  }
  [[nodiscard]] std::size_t classes() const { return classes_; }

 private:
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  std::vector<std::uint32_t> parent_;
  std::size_t classes_ = 0;
};

// One use of the edge {v, other} by the triangle at local slot `local` around v;
// direction is +1 if the triangle traverses v -> other, -1 if other -> v.
struct EdgeUse {
  std::uint32_t other;
  std::uint32_t local;
  int direction;
};

struct Scratch {
  std::vector<EdgeUse> uses;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> opposite_edges;  // for duplicates
  LocalDisjointSets fan;
};

// The counts one vertex contributes; summed over vertices they give SoupTopology.
struct Counts {
  SoupTopology topology;
  Counts& operator+=(const Counts& o) {
    SoupTopology& t = topology;
    const SoupTopology& u = o.topology;
    t.edges += u.edges;
    t.border_edges += u.border_edges;
    t.nonmanifold_edges += u.nonmanifold_edges;
    t.unbalanced_edges += u.unbalanced_edges;
    t.unbalanced_interior_edges += u.unbalanced_interior_edges;
    t.nonmanifold_vertices += u.nonmanifold_vertices;
    t.duplicate_triangles += u.duplicate_triangles;
    return *this;
  }
};

class VertexPass {
 public:
  VertexPass(const Soup& soup, const VertexTriangles& vt, ConcurrentDisjointSets& components)
      : soup_(soup), vt_(vt), components_(components) {}

  void visit(std::uint32_t v, Scratch& scratch, Counts& counts) const {
    const std::size_t begin = vt_.offsets[v];
    const std::size_t degree = vt_.offsets[v + 1] - begin;
    if (degree == 0) return;
    collect_edge_uses(v, begin, degree, scratch.uses);
    scratch.fan.reset(degree);
    const auto& uses = scratch.uses;
    for (std::size_t g = 0; g < uses.size();) {
      std::size_t e = g + 1;
      while (e < uses.size() && uses[e].other == uses[g].other) ++e;
      visit_edge(v, begin, uses, g, e, scratch.fan, counts);
      g = e;
    }
    if (scratch.fan.classes() > 1) ++counts.topology.nonmanifold_vertices;
    counts.topology.duplicate_triangles += duplicates_led_by(v, begin, degree, scratch.opposite_edges);
  }

 private:
  void collect_edge_uses(std::uint32_t v, std::size_t begin, std::size_t degree, std::vector<EdgeUse>& uses) const {
    uses.clear();
    for (std::size_t i = 0; i < degree; ++i) {
      const Triangle& t = soup_.triangles[vt_.triangles[begin + i]];
      const int k = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
      const auto local = static_cast<std::uint32_t>(i);
      uses.push_back({t[(k + 1) % 3], local, +1});  // the triangle runs v -> next
      uses.push_back({t[(k + 2) % 3], local, -1});  // and previous -> v
    }
    std::sort(uses.begin(), uses.end(), [](const EdgeUse& a, const EdgeUse& b) { return a.other < b.other; });
  }

  // uses[g, e) all lie on the edge {v, w}. Every vertex sees its edges, so the edge itself
  // is counted once, by its smaller endpoint; the fan around v is joined across it always.
  void visit_edge(std::uint32_t v, std::size_t begin, const std::vector<EdgeUse>& uses, std::size_t g,
                  std::size_t e, LocalDisjointSets& fan, Counts& counts) const {
    for (std::size_t j = g + 1; j < e; ++j) fan.unite(uses[g].local, uses[j].local);
    if (uses[g].other < v) return;
    const std::size_t incident = e - g;
    int signed_uses = 0;
    for (std::size_t j = g; j < e; ++j) signed_uses += uses[j].direction;
    for (std::size_t j = g + 1; j < e; ++j)
      components_.unite(vt_.triangles[begin + uses[g].local], vt_.triangles[begin + uses[j].local]);
    SoupTopology& t = counts.topology;
    ++t.edges;
    if (incident == 1) ++t.border_edges;
    if (incident >= 3) ++t.nonmanifold_edges;
    if (signed_uses != 0) ++t.unbalanced_edges;
    if (signed_uses != 0 && incident >= 2) ++t.unbalanced_interior_edges;
  }

  // Copies of one vertex set are counted at its smallest vertex, each set exactly once.
  std::uint64_t duplicates_led_by(std::uint32_t v, std::size_t begin, std::size_t degree,
                                  std::vector<std::pair<std::uint32_t, std::uint32_t>>& keys) const {
    keys.clear();
    for (std::size_t i = 0; i < degree; ++i) {
      Triangle t = soup_.triangles[vt_.triangles[begin + i]];
      std::sort(t.begin(), t.end());
      if (t[0] == v) keys.emplace_back(t[1], t[2]);
    }
    if (keys.size() < 2) return 0;
    std::sort(keys.begin(), keys.end());
    return static_cast<std::uint64_t>(keys.size() - (std::unique(keys.begin(), keys.end()) - keys.begin()));
  }

  const Soup& soup_;
  const VertexTriangles& vt_;
  ConcurrentDisjointSets& components_;
};

std::uint64_t count_components(const Soup& soup, ConcurrentDisjointSets& sets) {
  std::uint64_t roots = 0;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (has_distinct_indices(soup.triangles[t]) && sets.find(static_cast<std::uint32_t>(t)) == t) ++roots;
  return roots;
}

}  // namespace

SoupTopology analyze_topology(const Soup& soup) {
  check_indices(soup);
  const VertexTriangles vt = vertex_triangles(soup);
  ConcurrentDisjointSets components(soup.triangles.size());
  const VertexPass pass(soup, vt, components);
  tbb::enumerable_thread_specific<Scratch> scratch;
  const Counts total = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, soup.vertices.size(), 1 << 12), Counts{},
      [&](const tbb::blocked_range<std::size_t>& range, Counts counts) {
        Scratch& local = scratch.local();
        for (std::size_t v = range.begin(); v != range.end(); ++v)
          pass.visit(static_cast<std::uint32_t>(v), local, counts);
        return counts;
      },
      [](Counts a, const Counts& b) { return a += b; });
  SoupTopology topology = total.topology;
  topology.components = count_components(soup, components);
  return topology;
}

}  // namespace shadowcert
