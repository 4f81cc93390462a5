#include "exact/shadow_volume_chain.h"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>


namespace shadowcert {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("assemble_chain: " + what);
}

void require_consistent(const Soup& canonical, const EdgeTable& table, const EdgeMultiplicities& m,
                        const Light& light) {
  require_defined(light, "assemble_chain");
  require(m.multiplicity.size() == table.size(), "one multiplicity per edge of the table is needed");
  require(m.triangle_sign.size() == canonical.triangles.size(), "one cap sign per soup triangle is needed");
  // Far ids n + i (point light) must fit 32 bits, and closure packs two ids and a bit in 64.
  require(canonical.vertices.size() < (std::size_t{1} << 31), "more than 2^31 vertices");
  for (const auto& e : table.edges)
    require(e[0] < e[1] && e[1] < canonical.vertices.size(), "edge out of range or not (u < v)");
  for (const Triangle& t : canonical.triangles)
    for (std::uint32_t i : t) require(i < canonical.vertices.size(), "triangle index out of range");
}

// The far vertex x_inf of vertex x (shadow_volume_chain.h): n + x for a point light, the one
// vertex n for a directional light.
struct FarIds {
  std::uint32_t n;
  bool directional;
  [[nodiscard]] std::uint32_t operator()(std::uint32_t x) const { return directional ? n : n + x; }
};

// docs/definitions.md#counts: front cap t' (t if s = +1, reversed if s = -1: its normal towards the light)
// and, for a point light, the back cap t' at infinity, reversed. A directional light's back
// cap collapses to its one far vertex: no face.
void add_caps(const Soup& canonical, const std::vector<Sign>& cap_sign, const FarIds& far, ShadowVolumeChain& chain) {
  for (std::uint32_t i = 0; i < canonical.triangles.size(); ++i) {
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
    chain.triangles.push_back(front);
    if (!far.directional) chain.triangles.push_back({far(front[0]), far(front[2]), far(front[1])});
    chain.cap_triangles.push_back(i);
    chain.cap_sign.push_back(cap_sign[i]);
  }
}

// docs/definitions.md#counts: m copies of the quad (u, v, v_inf, u_inf), i.e. |m| copies oriented by
// sign(m); with one far vertex the quad is the triangle (u, v, inf).
void add_sides(const EdgeTable& table, const std::vector<std::int32_t>& multiplicity, const FarIds& far,
               ShadowVolumeChain& chain) {
  for (std::size_t e = 0; e < table.size(); ++e) {
    const std::int32_t m = multiplicity[e];
    if (m == 0) continue;
    const auto [u, v] = table.edges[e];
    chain.side_edges.push_back({u, v});
    chain.side_multiplicity.push_back(m);
    const std::uint32_t p = m > 0 ? u : v, q = m > 0 ? v : u;  // -(u, v, ...) = (v, u, ...)
    const std::int64_t copies = std::llabs(static_cast<long long>(m));
    for (std::int64_t k = 0; k < copies; ++k) {
      if (far.directional)
        chain.triangles.push_back({p, q, far(p)});
      else
        chain.quads.push_back({p, q, far(q), far(p)});
    }
  }
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
  require_consistent(canonical, table, multiplicities, light);
  ShadowVolumeChain chain;
  chain.finite_vertices = static_cast<std::uint32_t>(canonical.vertices.size());
  chain.directional = light.directional();
  const FarIds far{chain.finite_vertices, chain.directional};
  chain.triangles.reserve(canonical.triangles.size() * (chain.directional ? 1 : 2));
  add_caps(canonical, multiplicities.triangle_sign, far, chain);
  add_sides(table, multiplicities.multiplicity, far, chain);
  return chain;
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
