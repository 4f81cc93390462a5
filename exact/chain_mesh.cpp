#include "exact/chain_mesh.h"

#include "core/vector3.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace shadowcert {
namespace {

std::array<float, 4> homogeneous(double x, double y, double z, float w) {
  return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z), w};
}

// The far vertices of a point light's chain, with the wide far edges split (see chain_mesh.h).
class FarVertices {
 public:
  FarVertices(const Soup& canonical, const Light& light, HomogeneousMesh& mesh)
      : canonical_(canonical), l_{light.position[0], light.position[1], light.position[2]}, mesh_(mesh) {}

  [[nodiscard]] std::uint32_t n() const { return static_cast<std::uint32_t>(canonical_.vertices.size()); }
  [[nodiscard]] bool far(std::uint32_t id) const { return id >= n() && id < 2 * n(); }

  // A wide far edge far(u) - far(v) spans more than a right angle; the far vertices strictly
  // between its ends are the directions that bisect its angle,
  // recursively, until no piece spans more than a right angle (two levels at most: the angle is
  // below 180 degrees). A bisector d0/|d0| + d1/|d1| is a positive combination of the two
  // directions, so it is the direction to a point of the edge: the pieces stay in the side's
  // plane and on its sweep. The rule reads only the edge's two finite vertices, so every face
  // with that far edge (its side quads, the back caps on both sides) splits it alike and the
  // mesh stays closed.
  // Whether far(u) - far(v) is such an edge: one dot product, the fast path of every face.
  [[nodiscard]] bool wide(std::uint32_t u, std::uint32_t v) const {
    return dot(difference(canonical_.vertices[u], l_), difference(canonical_.vertices[v], l_)) < 0.0;
  }

  // Appends those vertices of a wide edge to `out`, in order from u to v (built on first use).
  void append_between(std::uint32_t u, std::uint32_t v, std::vector<std::uint32_t>& out) {
    const bool reversed = u > v;
    if (reversed) std::swap(u, v);
    const std::uint64_t key = (std::uint64_t{u} << 32) | v;
    auto it = middles_.find(key);
    if (it == middles_.end()) {
      std::vector<std::uint32_t> ids;
      bisect(difference(canonical_.vertices[u], l_), difference(canonical_.vertices[v], l_), kMaxSplitDepth, ids);
      it = middles_.emplace(key, std::move(ids)).first;
    }
    if (reversed)
      out.insert(out.end(), it->second.rbegin(), it->second.rend());
    else
      out.insert(out.end(), it->second.begin(), it->second.end());
  }

  // A new far vertex in the direction of the normal of triangle (u, v, w)'s plane that points
  // away from the light: every direction x - l to a point x of that plane makes an angle below
  // 90 degrees with it ((x - l) . n is the light's distance to the plane), so the back cap
  // fanned from it has no wide spoke, wherever the foot of the perpendicular falls.
  std::uint32_t away_normal(std::uint32_t u, std::uint32_t v, std::uint32_t w) {
    const Vec3& x = canonical_.vertices[u];
    Vec3 n = cross(difference(canonical_.vertices[v], x), difference(canonical_.vertices[w], x));
    if (dot(n, difference(x, l_)) < 0.0) n = {-n[0], -n[1], -n[2]};
    mesh_.vertices.push_back(homogeneous(n[0], n[1], n[2], 0.0f));
    return static_cast<std::uint32_t>(mesh_.vertices.size() - 1);
  }

 private:
  // Appends the far vertices strictly between directions d0 and d1 (not zero), in order.
  void bisect(const Vec3& d0, const Vec3& d1, int depth, std::vector<std::uint32_t>& ids) {
    if (!(dot(d0, d1) < 0.0) || depth == 0) return;
    const Vec3 a = normalized(d0), b = normalized(d1);
    const Vec3 m{a[0] + b[0], a[1] + b[1], a[2] + b[2]};
    // Antipodal to the last bit: the light lies on the edge, where its triangles cast nothing.
    if (m[0] == 0.0 && m[1] == 0.0 && m[2] == 0.0) return;
    bisect(d0, m, depth - 1, ids);
    const Vec3 unit = normalized(m);
    ids.push_back(static_cast<std::uint32_t>(mesh_.vertices.size()));
    mesh_.vertices.push_back(homogeneous(unit[0], unit[1], unit[2], 0.0f));
    bisect(m, d1, depth - 1, ids);
  }

  // Angles below 180 degrees need two levels; a third only guards the rounding of a bisector.
  static constexpr int kMaxSplitDepth = 3;

  const Soup& canonical_;
  Vec3 l_;
  HomogeneousMesh& mesh_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> middles_;
};

void add_point_light_faces(const ShadowVolumeChain& chain, FarVertices& far, HomogeneousMesh& mesh) {
  const std::uint32_t n = far.n();
  std::vector<std::uint32_t> boundary;
  for (const auto& t : chain.triangles) {
    const bool back_cap = far.far(t[0]) && far.far(t[1]) && far.far(t[2]);
    if (!back_cap || !(far.wide(t[0] - n, t[1] - n) || far.wide(t[1] - n, t[2] - n) || far.wide(t[2] - n, t[0] - n))) {
      mesh.triangles.push_back(t);
      continue;
    }
    // A back cap with a wide far edge: its boundary with those edges split, fanned from the far
    // vertex of its plane's normal (a fan from a point outside the polygon covers the outside
    // twice with opposite orientations, which cancels in the stencil count and in the closure).
    boundary.clear();
    for (int k = 0; k < 3; ++k) {
      boundary.push_back(t[k]);
      if (far.wide(t[k] - n, t[(k + 1) % 3] - n)) far.append_between(t[k] - n, t[(k + 1) % 3] - n, boundary);
    }
    const std::uint32_t g = far.away_normal(t[0] - n, t[1] - n, t[2] - n);
    for (std::size_t k = 0; k < boundary.size(); ++k)
      mesh.triangles.push_back({g, boundary[k], boundary[(k + 1) % boundary.size()]});
  }
  std::vector<std::uint32_t> polyline;
  for (const auto& q : chain.quads) {
    // (p, q, far(q), far(p)) is (p, q, far q), (p, far q, far p); a wide far edge's inner
    // vertices m1..mk (from q to p) make the second (p, far q, m1), ..., (p, mk, far p): a fan
    // from p over the far polyline.
    mesh.triangles.push_back({q[0], q[1], q[2]});
    if (!far.wide(q[1], q[0])) {
      mesh.triangles.push_back({q[0], q[2], q[3]});
      continue;
    }
    polyline.assign(1, q[2]);
    far.append_between(q[1], q[0], polyline);
    polyline.push_back(q[3]);
    for (std::size_t k = 0; k + 1 < polyline.size(); ++k) mesh.triangles.push_back({q[0], polyline[k], polyline[k + 1]});
  }
}

}  // namespace

HomogeneousMesh chain_mesh(const ShadowVolumeChain& chain, const Soup& canonical, const Light& light) {
  HomogeneousMesh mesh;
  chain_mesh(chain, canonical, light, mesh);
  return mesh;
}

void chain_mesh(const ShadowVolumeChain& chain, const Soup& canonical, const Light& light, HomogeneousMesh& mesh) {
  if (chain.finite_vertices != canonical.vertices.size())
    throw std::invalid_argument("chain_mesh: the chain has " + std::to_string(chain.finite_vertices) +
                                " finite vertices, the soup " + std::to_string(canonical.vertices.size()));
  if (chain.directional != light.directional())
    throw std::invalid_argument("chain_mesh: the chain was assembled for another kind of light");
  // Emptied, not replaced: a reused mesh keeps its capacity (the reserves below are then no-ops).
  mesh.vertices.clear();
  mesh.triangles.clear();
  const auto& l = light.position;
  mesh.vertices.reserve(chain.directional ? canonical.vertices.size() + 1 : 2 * canonical.vertices.size());
  for (const Vec3& x : canonical.vertices) mesh.vertices.push_back(homogeneous(x[0], x[1], x[2], 1.0f));
  if (chain.directional) {
    mesh.vertices.push_back(homogeneous(-l[0], -l[1], -l[2], 0.0f));
  } else {
    for (const Vec3& x : canonical.vertices)
      mesh.vertices.push_back(homogeneous(x[0] - l[0], x[1] - l[1], x[2] - l[2], 0.0f));
  }
  mesh.triangles.reserve(chain.triangles.size() + 2 * chain.quads.size());
  if (chain.directional) {
    mesh.triangles.insert(mesh.triangles.end(), chain.triangles.begin(), chain.triangles.end());
    return;
  }
  FarVertices far(canonical, light, mesh);
  add_point_light_faces(chain, far, mesh);
}

}  // namespace shadowcert
