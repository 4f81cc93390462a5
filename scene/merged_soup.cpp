#include "scene/merged_soup.h"

#include <cstdint>
#include <limits>
#include <stdexcept>

#include "core/input_error.h"

namespace shadowcert {
namespace {

constexpr std::size_t kMaxVertices = std::numeric_limits<std::uint32_t>::max();

bool has_normals(const Soup& soup) { return soup.normals.size() == soup.vertices.size(); }

bool fits(const Soup& to, const Soup& from) { return from.vertices.size() <= kMaxVertices - to.vertices.size(); }

}  // namespace

void append_soup(Soup& to, const Soup& from) {
  if (to.vertices.size() > kMaxVertices || !fits(to, from))
    throw std::length_error("append_soup: more than 2^32 - 1 vertices in all");
  const bool keep_normals = has_normals(to) && has_normals(from);
  const auto offset = static_cast<std::uint32_t>(to.vertices.size());
  to.vertices.insert(to.vertices.end(), from.vertices.begin(), from.vertices.end());
  if (keep_normals) {
    to.normals.insert(to.normals.end(), from.normals.begin(), from.normals.end());
  } else {
    to.normals.clear();
  }
  to.triangles.reserve(to.triangles.size() + from.triangles.size());
  for (const Triangle& t : from.triangles) to.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

namespace {

Soup merged(const Scene& scene, bool casters_only) {
  Soup out;
  for (const SceneMesh& mesh : scene.meshes) {
    if (casters_only && !mesh.casts) continue;
    if (!fits(out, mesh.soup)) throw InputError(mesh.name, "the scene has more than 2^32-1 vertices in all");
    append_soup(out, mesh.soup);
  }
  return out;
}

}  // namespace

Soup merged_soup(const Scene& scene) { return merged(scene, false); }

Soup merged_casters(const Scene& scene) { return merged(scene, true); }

std::vector<std::uint8_t> casting_triangles(const Scene& scene) {
  std::vector<std::uint8_t> casts;
  for (const SceneMesh& mesh : scene.meshes) casts.insert(casts.end(), mesh.soup.triangles.size(), mesh.casts ? 1 : 0);
  return casts;
}

}  // namespace shadowcert
