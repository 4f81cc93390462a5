#include "exact/shadow_volume_chain.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/huge_page_advice.h"

namespace shadowcert {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("assemble_chain: " + what);
}

// Grain of the parallel loops: chunks of triangles or edges whose overhead is noise.
constexpr std::size_t kChunk = std::size_t{1} << 15;

std::size_t chunk_count(std::size_t items) { return (items + kChunk - 1) / kChunk; }

void require_consistent(const Soup& canonical, const EdgeTable& table, const EdgeMultiplicities& m,
                        const Light& light) {
  require_defined(light, "assemble_chain");
  require(m.multiplicity.size() == table.size(), "one multiplicity per edge of the table is needed");
  require(m.triangle_sign.size() == canonical.triangles.size(), "one cap sign per soup triangle is needed");
  // Far ids n + i (point light) must fit 32 bits, and closure packs two ids and a bit in 64.
  require(canonical.vertices.size() < (std::size_t{1} << 31), "more than 2^31 vertices");
  const std::size_t n = canonical.vertices.size();
  const bool edges_ok = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, table.size(), kChunk), true,
      [&](const tbb::blocked_range<std::size_t>& r, bool ok) {
        for (std::size_t e = r.begin(); ok && e < r.end(); ++e)
          ok = table.edges[e][0] < table.edges[e][1] && table.edges[e][1] < n;
        return ok;
      },
      [](bool a, bool b) { return a && b; });
  require(edges_ok, "edge out of range or not (u < v)");
  const bool triangles_ok = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, canonical.triangles.size(), kChunk), true,
      [&](const tbb::blocked_range<std::size_t>& r, bool ok) {
        for (std::size_t t = r.begin(); ok && t < r.end(); ++t)
          ok = canonical.triangles[t][0] < n && canonical.triangles[t][1] < n && canonical.triangles[t][2] < n;
        return ok;
      },
      [](bool a, bool b) { return a && b; });
  require(triangles_ok, "triangle index out of range");
}

// The far vertex x_inf of vertex x (shadow_volume_chain.h): n + x for a point light, the one
// vertex n for a directional light.
struct FarIds {
  std::uint32_t n;
  bool directional;
  [[nodiscard]] std::uint32_t operator()(std::uint32_t x) const { return directional ? n : n + x; }
};

// Exclusive prefix sum of per-chunk counts, in place; returns the total.
std::size_t prefix_sum(std::vector<std::size_t>& counts) {
  std::size_t total = 0;
  for (std::size_t& c : counts) total += std::exchange(c, total);
  return total;
}

// docs/definitions.md#counts: front cap t' (t if s = +1, reversed if s = -1: its normal towards the light)
// and, for a point light, the back cap t' at infinity, reversed. A directional light's back
// cap collapses to its one far vertex: no face. In parallel: each chunk of triangles counts its
// caps, then writes them at its prefix offset, so the faces come in triangle order as a
// sequential loop writes them. `extra_triangles`: the directional side triangles that follow
// the caps (room is reserved for them, so that adding them moves nothing).
void add_caps(const Soup& canonical, const std::vector<Sign>& cap_sign, const FarIds& far, std::size_t extra_triangles,
              ShadowVolumeChain& chain) {
  const std::size_t triangles = canonical.triangles.size();
  std::vector<std::size_t> first(chunk_count(triangles), 0);
  tbb::parallel_for(std::size_t{0}, first.size(), [&](std::size_t c) {
    const std::size_t last = std::min(triangles, (c + 1) * kChunk);
    for (std::size_t i = c * kChunk; i < last; ++i) first[c] += cap_sign[i] != Sign::zero;
  });
  const std::size_t caps = prefix_sum(first);
  const std::size_t faces_per_cap = far.directional ? 1 : 2;
  reserve_huge(chain.triangles, caps * faces_per_cap + extra_triangles);
  chain.triangles.resize(caps * faces_per_cap);
  resize_huge(chain.cap_triangles, caps);
  chain.cap_sign.resize(caps);
  tbb::parallel_for(std::size_t{0}, first.size(), [&](std::size_t c) {
    std::size_t j = first[c];
    const std::size_t last = std::min(triangles, (c + 1) * kChunk);
    for (std::size_t i = c * kChunk; i < last; ++i) {
      const Triangle& t = canonical.triangles[i];
      std::array<std::uint32_t, 3> front{};
      switch (cap_sign[i]) {
        case Sign::zero:
          continue;  // casts nothing (docs/definitions.md#orientation)
        case Sign::positive:
          front = {t[0], t[1], t[2]};
          break;
        case Sign::negative:
          front = {t[0], t[2], t[1]};
          break;
      }
      chain.triangles[faces_per_cap * j] = front;
      if (!far.directional) chain.triangles[faces_per_cap * j + 1] = {far(front[0]), far(front[2]), far(front[1])};
      chain.cap_triangles[j] = static_cast<std::uint32_t>(i);
      chain.cap_sign[j] = cap_sign[i];
      ++j;
    }
  });
}

// Per chunk of edges: its side edges (m != 0) and their copies |m|; then their prefix offsets.
struct SideCounts {
  std::vector<std::size_t> first_side, first_copy;
  std::size_t sides = 0, copies = 0;
};

SideCounts count_sides(const std::vector<std::int32_t>& multiplicity) {
  const std::size_t edges = multiplicity.size();
  SideCounts counts;
  counts.first_side.assign(chunk_count(edges), 0);
  counts.first_copy.assign(chunk_count(edges), 0);
  tbb::parallel_for(std::size_t{0}, counts.first_side.size(), [&](std::size_t c) {
    const std::size_t last = std::min(edges, (c + 1) * kChunk);
    for (std::size_t e = c * kChunk; e < last; ++e)
      if (const std::int32_t m = multiplicity[e]; m != 0) {
        ++counts.first_side[c];
        counts.first_copy[c] += static_cast<std::size_t>(std::llabs(static_cast<long long>(m)));
      }
  });
  counts.sides = prefix_sum(counts.first_side);
  counts.copies = prefix_sum(counts.first_copy);
  return counts;
}

// docs/definitions.md#counts: m copies of the quad (u, v, v_inf, u_inf), i.e. |m| copies oriented by
// sign(m); with one far vertex the quad is the triangle (u, v, inf). In parallel as add_caps:
// each chunk of edges writes at its prefix offsets (count_sides).
void add_sides(const EdgeTable& table, const std::vector<std::int32_t>& multiplicity, const SideCounts& counts,
               const FarIds& far, ShadowVolumeChain& chain) {
  const std::size_t edges = table.size();
  const std::vector<std::size_t>& first_side = counts.first_side;
  const std::vector<std::size_t>& first_copy = counts.first_copy;
  const std::size_t sides = counts.sides, copies = counts.copies;
  chain.side_edges.resize(sides);
  chain.side_multiplicity.resize(sides);
  const std::size_t face_base = far.directional ? chain.triangles.size() : 0;
  if (far.directional)
    chain.triangles.resize(face_base + copies);
  else
    resize_huge(chain.quads, copies);
  tbb::parallel_for(std::size_t{0}, first_side.size(), [&](std::size_t c) {
    std::size_t side = first_side[c], copy = face_base + first_copy[c];
    const std::size_t last = std::min(edges, (c + 1) * kChunk);
    for (std::size_t e = c * kChunk; e < last; ++e) {
      const std::int32_t m = multiplicity[e];
      if (m == 0) continue;
      const auto [u, v] = table.edges[e];
      chain.side_edges[side] = {u, v};
      chain.side_multiplicity[side] = m;
      ++side;
      const std::uint32_t p = m > 0 ? u : v, q = m > 0 ? v : u;  // -(u, v, ...) = (v, u, ...)
      const std::int64_t n = std::llabs(static_cast<long long>(m));
      for (std::int64_t k = 0; k < n; ++k, ++copy) {
        if (far.directional)
          chain.triangles[copy] = {p, q, far(p)};
        else
          chain.quads[copy] = {p, q, far(q), far(p)};
      }
    }
  });
}

// Where chain_picture draws x_inf: pushed far_distance along the ray away from the light.
Vec3 pushed_far(const Vec3& x, const Light& light, double far_distance) {
  const auto& l = light.position;
  Vec3 d = light.directional() ? Vec3{-l[0], -l[1], -l[2]} : Vec3{x[0] - l[0], x[1] - l[1], x[2] - l[2]};
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(length > 0.0) || !std::isfinite(length)) return x;  // a vertex at the light: nowhere to push
  return {x[0] + far_distance * d[0] / length, x[1] + far_distance * d[1] / length,
          x[2] + far_distance * d[2] / length};
}

}  // namespace

ShadowVolumeChain assemble_chain(const Soup& canonical, const EdgeTable& table,
                                 const EdgeMultiplicities& multiplicities, const Light& light) {
  ShadowVolumeChain chain;
  assemble_chain(canonical, table, multiplicities, light, chain);
  return chain;
}

void assemble_chain(const Soup& canonical, const EdgeTable& table, const EdgeMultiplicities& multiplicities,
                    const Light& light, ShadowVolumeChain& chain) {
  require_consistent(canonical, table, multiplicities, light);
  // Emptied, not replaced: every array below is resized within the capacity it already has.
  chain.triangles.clear();
  chain.quads.clear();
  chain.side_edges.clear();
  chain.side_multiplicity.clear();
  chain.cap_triangles.clear();
  chain.cap_sign.clear();
  chain.finite_vertices = static_cast<std::uint32_t>(canonical.vertices.size());
  chain.directional = light.directional();
  const FarIds far{chain.finite_vertices, chain.directional};
  const SideCounts sides = count_sides(multiplicities.multiplicity);
  add_caps(canonical, multiplicities.triangle_sign, far, chain.directional ? sides.copies : 0, chain);
  add_sides(table, multiplicities.multiplicity, sides, far, chain);
}

Soup chain_picture(const ShadowVolumeChain& chain, const Soup& canonical, const Light& light,
                   double far_distance) {
  const std::uint32_t n = chain.finite_vertices;
  if (canonical.vertices.size() != n)
    throw std::invalid_argument("chain_picture: the chain was not assembled on this soup");
  // Picture vertices: [0, n) the soup's, [n, 2n) each one's pushed far point. A directional
  // chain's one far vertex is drawn per finite neighbour, so its triangles (p, q, inf) become
  // the quads (p, q, q_far, p_far).
  Soup picture;
  picture.vertices = canonical.vertices;
  for (const Vec3& x : canonical.vertices) picture.vertices.push_back(pushed_far(x, light, far_distance));
  auto add_quad = [&picture](std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    picture.triangles.push_back({a, b, c});
    picture.triangles.push_back({a, c, d});
  };
  for (const auto& t : chain.triangles) {
    if (!chain.directional || (t[0] < n && t[1] < n && t[2] < n)) {
      picture.triangles.push_back({t[0], t[1], t[2]});
      continue;
    }
    for (int k = 0; k < 3; ++k) {  // rotate the far vertex last: (p, q, inf)
      const std::uint32_t p = t[(k + 1) % 3], q = t[(k + 2) % 3];
      if (t[k] == n && p < n && q < n) add_quad(p, q, n + q, n + p);
    }
  }
  for (const auto& q : chain.quads) add_quad(q[0], q[1], q[2], q[3]);
  return picture;
}

}  // namespace shadowcert
