#include "contour/smoothie.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/vector3.h"

namespace shadowcert {
namespace {

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("build_smoothies: " + what); }

Vec3 scaled(const Vec3& v, double s) { return {v[0] * s, v[1] * s, v[2] * s}; }
Vec3 sum(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
double length(const Vec3& v) { return std::sqrt(dot(v, v)); }
bool finite(const Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// The direction from x towards the light: l - w x (not normalised).
Vec3 towards_light(const Light& light, const Vec3& x) {
  const Vec3 l{light.position[0], light.position[1], light.position[2]};
  return light.directional() ? l : difference(l, x);
}

// One smoothie before its outer vertices are placed.
struct Strip {
  std::array<std::uint32_t, 2> ends{};  // u, v
  Vec3 direction{};                     // unit: the quad's direction from the edge outwards
  Vec3 outward{};                       // unit: p, the light-image direction away from the occluders
  std::array<double, 2> width{};        // at u and at v
};

void validate(std::span<const Vec3> vertices, const SmoothieEdges& edges, const Light& light,
              const SmoothieOptions& options) {
  if (!light.defined()) fail("the light needs finite coordinates, w = 0 or 1, and a nonzero direction");
  if (!std::isfinite(options.width) || !(options.width > 0.0))
    fail("the width must be finite and > 0, got " + std::to_string(options.width));
  if (options.space == SmoothieSpace::light && !light.directional() &&
      (!std::isfinite(options.reference_distance) || !(options.reference_distance > 0.0)))
    fail("light space needs a finite reference distance > 0, got " + std::to_string(options.reference_distance));
  const std::size_t n = edges.edges.size();
  if (edges.occluder_side.size() != n) fail("one occluder side per edge is needed");
  if (edges.first_face.size() != n + 1 || edges.first_face.front() != 0 ||
      edges.first_face.back() != edges.face_opposite.size())
    fail("first_face must have edges + 1 entries, from 0 to the number of faces");
  const auto check_vertex = [&](std::uint32_t i) {
    if (i >= vertices.size())
      fail("vertex index " + std::to_string(i) + " out of range (" + std::to_string(vertices.size()) + " vertices)");
    if (!finite(vertices[i])) fail("vertex " + std::to_string(i) + " has a non-finite coordinate");
  };
  for (std::size_t e = 0; e < n; ++e) {
    if (edges.occluder_side[e] != 1 && edges.occluder_side[e] != -1)
      fail("edge " + std::to_string(e) + ": the occluder side must be +1 or -1");
    if (edges.first_face[e] > edges.first_face[e + 1]) fail("first_face must not decrease");
    check_vertex(edges.edges[e][0]);
    check_vertex(edges.edges[e][1]);
  }
  for (std::uint32_t o : edges.face_opposite) check_vertex(o);
}

}  // namespace

std::string_view smoothie_space_name(SmoothieSpace space) {
  return space == SmoothieSpace::light ? "light" : "world";
}

std::optional<SmoothieSpace> parse_smoothie_space(std::string_view name) {
  if (name == "world") return SmoothieSpace::world;
  if (name == "light") return SmoothieSpace::light;
  return std::nullopt;
}

Smoothies build_smoothies(std::span<const Vec3> vertices, const SmoothieEdges& edges, const Light& light,
                          const SmoothieOptions& options) {
  validate(vertices, edges, light, options);
  Smoothies out;
  out.stats.edges = edges.edges.size();

  // 1. Each edge's direction and widths (or no smoothie, for a degenerate edge).
  std::vector<Strip> strips;
  strips.reserve(edges.edges.size());
  for (std::size_t e = 0; e < edges.edges.size(); ++e) {
    const auto [u, v] = edges.edges[e];
    const Vec3& pu = vertices[u];
    const Vec3& pv = vertices[v];
    const Vec3 edge = difference(pv, pu);
    const double edge_length = length(edge);
    if (u == v || !(edge_length > 0.0)) {
      ++out.stats.zero_length_edges;
      continue;
    }
    const Vec3 ray = towards_light(light, pu);
    const Vec3 normal = cross(ray, edge);  // (l - w u) x (v - u): (o - u) . normal has D's sign
    const double normal_length = length(normal);
    if (!(normal_length > kMinEdgeLightSine * length(ray) * edge_length)) {
      ++out.stats.edge_on_edges;
      continue;
    }
    Strip s;
    s.ends = {u, v};
    s.outward = scaled(normal, -static_cast<double>(edges.occluder_side[e]) / normal_length);
    s.direction = s.outward;
    if (options.space == SmoothieSpace::world) {
      const Vec3 along = scaled(edge, 1.0 / edge_length);
      Vec3 bisector{0.0, 0.0, 0.0};
      for (std::uint32_t f = edges.first_face[e]; f < edges.first_face[e + 1]; ++f) {
        const Vec3 to_opposite = difference(vertices[edges.face_opposite[f]], pu);
        const Vec3 in_face = difference(to_opposite, scaled(along, dot(to_opposite, along)));
        const double in_face_length = length(in_face);
        if (!(in_face_length > kMinFaceWidthRatio * length(to_opposite))) continue;  // on the edge's line
        bisector = difference(bisector, scaled(in_face, 1.0 / in_face_length));
      }
      const double bisector_length = length(bisector);
      if (bisector_length > kMinBisectorLength &&
          dot(bisector, s.outward) > kMinBisectorOutwardCosine * bisector_length)
        s.direction = scaled(bisector, 1.0 / bisector_length);
      else
        ++out.stats.bisector_fallbacks;
      s.width = {options.width, options.width};
    } else {
      for (int end = 0; end < 2; ++end) {
        const double distance =
            light.directional() ? options.reference_distance : length(towards_light(light, vertices[s.ends[end]]));
        s.width[end] = light.directional() ? options.width : options.width * distance / options.reference_distance;
      }
    }
    strips.push_back(s);
  }

  // 2. Corners: vertices where exactly two smoothies meet.
  struct End {
    std::uint32_t strip;
    int end;
  };
  std::vector<std::uint32_t> end_count(vertices.size(), 0);
  std::vector<std::array<End, 2>> ends_at(vertices.size());
  for (std::uint32_t i = 0; i < strips.size(); ++i)
    for (int end = 0; end < 2; ++end) {
      const std::uint32_t vertex = strips[i].ends[end];
      if (end_count[vertex] < 2) ends_at[vertex][end_count[vertex]] = {i, end};
      ++end_count[vertex];
    }
  struct Link {
    End a, b;
  };
  std::vector<Link> links;
  for (std::uint32_t vertex = 0; vertex < vertices.size(); ++vertex) {
    if (end_count[vertex] != 2) continue;
    const End a = ends_at[vertex][0], b = ends_at[vertex][1];
    if (a.strip == b.strip) continue;  // one smoothie's two ends (only with u == v, skipped above)
    Strip& sa = strips[a.strip];
    Strip& sb = strips[b.strip];
    const Vec3& pv = vertices[vertex];
    const Vec3 to_a = difference(vertices[sa.ends[1 - a.end]], pv);  // towards A's other end
    const Vec3 to_b = difference(vertices[sb.ends[1 - b.end]], pv);
    const double concavity =
        0.5 * (dot(sa.outward, to_b) / length(to_b) + dot(sb.outward, to_a) / length(to_a));
    if (concavity > kStraightCornerSine) {
      if (options.shrink_concave_corners) {
        const double shrink = 0.5 * (1.0 + dot(sa.outward, sb.outward));
        sa.width[a.end] *= shrink;
        sb.width[b.end] *= shrink;
        ++out.stats.shrunk_corners;
      }
    } else if (options.link_corners) {
      links.push_back({a, b});
    }
  }

  // 3. The quads (u, v, v', u') as two triangles each, then the linking triangles.
  SmoothieMesh& mesh = out.mesh;
  mesh.vertices.reserve(4 * strips.size());
  mesh.alpha.reserve(4 * strips.size());
  mesh.triangles.reserve(2 * strips.size() + links.size());
  const auto add = [&mesh](const Vec3& p, float alpha) {
    mesh.vertices.push_back(p);
    mesh.alpha.push_back(alpha);
    return static_cast<std::uint32_t>(mesh.vertices.size() - 1);
  };
  // outer(i, end): the index of strip i's outer vertex at that end; inner likewise.
  const auto inner = [](std::uint32_t i, int end) { return 4 * i + static_cast<std::uint32_t>(end); };
  const auto outer = [](std::uint32_t i, int end) { return 4 * i + static_cast<std::uint32_t>(3 - end); };
  for (const Strip& s : strips) {
    const Vec3& pu = vertices[s.ends[0]];
    const Vec3& pv = vertices[s.ends[1]];
    const std::uint32_t iu = add(pu, 0.0f);
    const std::uint32_t iv = add(pv, 0.0f);
    const std::uint32_t ov = add(sum(pv, scaled(s.direction, s.width[1])), 1.0f);
    const std::uint32_t ou = add(sum(pu, scaled(s.direction, s.width[0])), 1.0f);
    mesh.triangles.push_back({iu, iv, ov});
    mesh.triangles.push_back({iu, ov, ou});
  }
  out.stats.smoothies = strips.size();
  for (const Link& link : links) {
    const std::uint32_t oa = outer(link.a.strip, link.a.end);
    const std::uint32_t ob = outer(link.b.strip, link.b.end);
    if (mesh.vertices[oa] == mesh.vertices[ob]) continue;  // the rims meet: nothing to fill
    mesh.triangles.push_back({inner(link.a.strip, link.a.end), oa, ob});
    ++out.stats.linked_corners;
  }
  return out;
}

}  // namespace shadowcert
