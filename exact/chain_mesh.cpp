#include "exact/chain_mesh.h"

#include <stdexcept>
#include <string>

namespace shadowcert {
namespace {

std::array<float, 4> homogeneous(double x, double y, double z, float w) {
  return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z), w};
}

}  // namespace

HomogeneousMesh chain_mesh(const ShadowVolumeChain& chain, const Soup& canonical, const Light& light) {
  if (chain.finite_vertices != canonical.vertices.size())
    throw std::invalid_argument("chain_mesh: the chain has " + std::to_string(chain.finite_vertices) +
                                " finite vertices, the soup " + std::to_string(canonical.vertices.size()));
  if (chain.directional != light.directional())
    throw std::invalid_argument("chain_mesh: the chain was assembled for another kind of light");
  HomogeneousMesh mesh;
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
  mesh.triangles.insert(mesh.triangles.end(), chain.triangles.begin(), chain.triangles.end());
  for (const auto& q : chain.quads) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

}  // namespace shadowcert
