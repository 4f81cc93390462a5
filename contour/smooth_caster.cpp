#include "contour/smooth_caster.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <map>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "core/vector3.h"
#include "scene/welded_soup.h"

namespace shadowcert {
namespace {

using OpenMeshTriangles = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;

// One side of an edge: triangle t's edge k, running from -> to.
struct EdgeSide {
  std::uint32_t triangle = 0;
  std::uint8_t edge = 0;
  std::uint32_t from = 0, to = 0;
};

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}

// Union-find over the corners 3 t + k.
struct Corners {
  std::vector<std::uint32_t> parent;
  explicit Corners(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t root(std::uint32_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[root(a)] = root(b); }
};

std::uint32_t corner_of(const Triangle& t, std::uint32_t triangle, std::uint32_t vertex) {
  for (std::uint32_t k = 0; k < 3; ++k)
    if (t[k] == vertex) return 3 * triangle + k;
  throw std::logic_error("smooth_caster: a vertex is not on its triangle");
}

template <typename T>
void report(std::vector<T>& first, std::size_t& count, const T& item) {
  if (first.size() < CasterQualification::kMaxReported) first.push_back(item);
  ++count;
}

bool usable_normal(const Normal& n) {
  const double length2 = double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2];
  return std::isfinite(length2) && length2 > 0.0;
}

}  // namespace

std::string CasterQualification::summary() const {
  if (qualifies()) return "qualifies";
  std::string out = "not an oriented 2-manifold:";
  const auto list = [](const auto& items, auto&& name) {
    std::string s;
    for (std::size_t i = 0; i < items.size(); ++i) s += (i ? ", " : "") + name(items[i]);
    return s;
  };
  const auto edge = [](const std::array<std::uint32_t, 2>& e) { return fmt::format("({}, {})", e[0], e[1]); };
  const auto index = [](std::uint32_t i) { return std::to_string(i); };
  const auto add = [&](std::size_t count, const char* one, const char* many, const std::string& first) {
    if (count == 0) return;
    out += fmt::format("{} {} {} ({}{})", out.back() == ':' ? "" : ";", count, count == 1 ? one : many, first,
                       count > kMaxReported ? ", ..." : "");
  };
  add(degenerate_count, "degenerate triangle", "degenerate triangles", list(degenerate_triangles, index));
  add(non_manifold_edge_count, "non-manifold edge", "non-manifold edges", list(non_manifold_edges, edge));
  add(misoriented_edge_count, "misoriented edge", "misoriented edges", list(misoriented_edges, edge));
  add(non_manifold_vertex_count, "non-manifold vertex", "non-manifold vertices", list(non_manifold_vertices, index));
  return out;
}

SmoothCasterResult smooth_caster(const Soup& soup, const SmoothCasterOptions& options) {
  require_indices_in_range(soup, "smooth_caster");
  require_finite_vertices(soup, "smooth_caster");
  if (!(options.crease_angle_degrees >= 0.0 && options.crease_angle_degrees <= 180.0))
    throw std::invalid_argument("smooth_caster: the crease angle must be in [0, 180] degrees");
  const WeldedSoup welded = weld_soup(soup);
  const Soup& w = welded.soup;
  const std::size_t n = w.triangles.size();

  SmoothCasterResult result;
  CasterQualification& q = result.qualification;
  for (std::uint32_t t = 0; t < n; ++t) {
    const Triangle& tri = w.triangles[t];
    const Vec3 normal = cross(difference(w.vertices[tri[1]], w.vertices[tri[0]]),
                              difference(w.vertices[tri[2]], w.vertices[tri[0]]));
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] || normal == Vec3{0.0, 0.0, 0.0})
      report(q.degenerate_triangles, q.degenerate_count, t);
  }

  // Edges: who runs along each, and which way.
  std::unordered_map<std::uint64_t, std::vector<EdgeSide>> edges;
  edges.reserve(3 * n);
  for (std::uint32_t t = 0; t < n; ++t)
    for (std::uint8_t k = 0; k < 3; ++k) {
      const std::uint32_t a = w.triangles[t][k], b = w.triangles[t][(k + 1) % 3];
      if (a != b) edges[edge_key(a, b)].push_back({t, k, a, b});
    }
  std::vector<std::pair<std::uint64_t, const std::vector<EdgeSide>*>> sorted_edges;
  sorted_edges.reserve(edges.size());
  for (const auto& [key, sides] : edges) sorted_edges.emplace_back(key, &sides);
  std::sort(sorted_edges.begin(), sorted_edges.end());  // reports in a fixed order
  Corners corners(3 * n);
  for (const auto& [key, sides] : sorted_edges) {
    const std::array<std::uint32_t, 2> e{static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key)};
    if (sides->size() > 2) {
      report(q.non_manifold_edges, q.non_manifold_edge_count, e);
    } else if (sides->size() == 2) {
      const EdgeSide& s0 = (*sides)[0];
      const EdgeSide& s1 = (*sides)[1];
      if (s0.from == s1.from) report(q.misoriented_edges, q.misoriented_edge_count, e);
      // The two triangles meet at both ends: their corners there are one fan (a misoriented
      // edge is reported as that, not again as two non-manifold vertices).
      for (std::uint32_t v : e)
        corners.join(corner_of(w.triangles[s0.triangle], s0.triangle, v),
                     corner_of(w.triangles[s1.triangle], s1.triangle, v));
    }
  }
  // A vertex whose corners fall into several fans (two cones touching at a point).
  std::vector<std::uint32_t> fan(w.vertices.size(), kBorder);
  std::vector<bool> several(w.vertices.size(), false);
  for (std::uint32_t c = 0; c < 3 * n; ++c) {
    const std::uint32_t v = w.triangles[c / 3][c % 3];
    const std::uint32_t r = corners.root(c);
    if (fan[v] == kBorder) fan[v] = r;
    else if (fan[v] != r) several[v] = true;
  }
  for (std::uint32_t v = 0; v < several.size(); ++v)  // in index order, as the edges are
    if (several[v]) report(q.non_manifold_vertices, q.non_manifold_vertex_count, v);
  if (!q.qualifies()) return result;

  // The mesh: every check above is what OpenMesh's add_face refuses, so it accepts every face.
  OpenMeshTriangles mesh;
  std::vector<OpenMeshTriangles::VertexHandle> handles;
  handles.reserve(w.vertices.size());
  for (const Vec3& v : w.vertices) handles.push_back(mesh.add_vertex({v[0], v[1], v[2]}));
  for (const Triangle& t : w.triangles)
    if (!mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]).is_valid())
      throw std::logic_error("smooth_caster: OpenMesh refused a face of a qualifying soup");

  SmoothCaster caster;
  caster.vertices = w.vertices;
  caster.triangles = w.triangles;
  caster.normals.resize(n);
  caster.across.assign(n, {kBorder, kBorder, kBorder});
  caster.crease.assign(n, {false, false, false});
  const bool file_normals = options.use_file_normals && !soup.normals.empty() &&
                            std::all_of(soup.normals.begin(), soup.normals.end(), usable_normal);
  if (file_normals) {
    caster.normal_source = CornerNormalSource::file;
    for (std::uint32_t t = 0; t < n; ++t)
      for (std::size_t k = 0; k < 3; ++k) {
        const Normal& f = soup.normals[soup.triangles[t][k]];
        caster.normals[t][k] = normalized(Vec3{f[0], f[1], f[2]});
      }
  } else {
    caster.normal_source = CornerNormalSource::computed;
    mesh.request_face_normals();
    mesh.request_halfedge_normals();
    mesh.update_face_normals();
    const double feature_angle = options.crease_angle_degrees * std::numbers::pi / 180.0;
    mesh.update_halfedge_normals(feature_angle);
    for (const auto face : mesh.faces()) {
      const auto t = static_cast<std::uint32_t>(face.idx());
      for (const auto h : face.halfedges()) {
        const auto v = static_cast<std::uint32_t>(h.to().idx());
        const auto normal = mesh.normal(h);
        caster.normals[t][corner_of(w.triangles[t], t, v) % 3] = {normal[0], normal[1], normal[2]};
      }
    }
    // Creases are OpenMesh's feature edges (dihedral angle above the crease angle). Across every
    // other edge the corners at each end are one wedge: they take one normal, bit for bit (the
    // wedge's first corner's), so both triangles of an edge evaluate its silhouette point alike.
    Corners wedges(3 * n);
    for (const auto& [key, sides] : sorted_edges) {
      if (sides->size() != 2) continue;
      const EdgeSide& s0 = (*sides)[0];
      const EdgeSide& s1 = (*sides)[1];
      const auto h = mesh.find_halfedge(handles[s0.from], handles[s0.to]);
      const bool feature = mesh.is_estimated_feature_edge(h, feature_angle);
      caster.crease[s0.triangle][s0.edge] = caster.crease[s1.triangle][s1.edge] = feature;
      if (feature) continue;
      for (std::uint32_t v : {s0.from, s0.to})
        wedges.join(corner_of(w.triangles[s0.triangle], s0.triangle, v),
                    corner_of(w.triangles[s1.triangle], s1.triangle, v));
    }
    std::vector<std::uint32_t> first(3 * n, kBorder);  // per wedge root: its least corner
    for (std::uint32_t c = 0; c < 3 * n; ++c) {
      const std::uint32_t r = wedges.root(c);
      if (first[r] == kBorder) first[r] = c;
      caster.normals[c / 3][c % 3] = caster.normals[first[r] / 3][first[r] % 3];
    }
  }
  for (const auto& [key, sides] : sorted_edges) {
    if (sides->size() != 2) continue;
    const EdgeSide& s0 = (*sides)[0];
    const EdgeSide& s1 = (*sides)[1];
    caster.across[s0.triangle][s0.edge] = s1.triangle;
    caster.across[s1.triangle][s1.edge] = s0.triangle;
    if (caster.normal_source != CornerNormalSource::file) continue;
    // File normals: a crease where the two triangles' corner normals differ at an end.
    bool differs = false;
    for (std::uint32_t v : {s0.from, s0.to})
      differs |= caster.normals[s0.triangle][corner_of(w.triangles[s0.triangle], s0.triangle, v) % 3] !=
                 caster.normals[s1.triangle][corner_of(w.triangles[s1.triangle], s1.triangle, v) % 3];
    caster.crease[s0.triangle][s0.edge] = caster.crease[s1.triangle][s1.edge] = differs;
  }
  for (std::uint32_t t = 0; t < n; ++t)
    for (std::uint32_t k = 0; k < 3; ++k)
      if (caster.crease[t][k] && caster.across[t][k] != kBorder && caster.across[t][k] > t)
        caster.crease_edges.push_back({t, k});
  // Wedges: one per distinct (vertex, normal bits).
  std::map<std::pair<std::uint32_t, Vec3>, std::uint32_t> wedge_of;
  caster.wedge.resize(n);
  for (std::uint32_t t = 0; t < n; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = caster.triangles[t][k];
      const auto [it, added] =
          wedge_of.emplace(std::pair{v, caster.normals[t][k]}, static_cast<std::uint32_t>(caster.wedge_vertex.size()));
      if (added) {
        caster.wedge_vertex.push_back(v);
        caster.wedge_normal.push_back(caster.normals[t][k]);
      }
      caster.wedge[t][k] = it->second;
    }
  result.caster = std::move(caster);
  return result;
}

}  // namespace shadowcert
