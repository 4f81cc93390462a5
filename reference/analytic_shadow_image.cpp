// analytic_shadow_image of reference/analytic_shadow_image.h, in two passes over the rays:
//   1. every centre ray and every corner ray (shared by the four pixels around it) is followed
//      to its first hit (the box tree's nearest-first query and reference/detail/ray_hit.h's
//      exact tests, as reference/exact_image.cpp does), and at its hit point each light's
//      verdict is taken: other casters (ellipsoids exactly, reference/detail/hit_point_occlusion.h;
//      casting triangles by the exact crossing rule of exact/face_crossing.h), then the hit
//      surface itself (a receiver's light side, an analytic caster's terminator);
//   2. per pixel and light, the five verdicts make the pixel's truth.
#include "reference/analytic_shadow_image.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/box.h"
#include "core/pixel_ray.h"
#include "core/vector3.h"
#include "exact/box_tree.h"
#include "exact/face_crossing.h"
#include "exact/light_orientation.h"
#include "reference/detail/hit_point_occlusion.h"
#include "reference/detail/ray_hit.h"
#include "reference/ellipsoid_occlusion.h"
#include "scene/merged_soup.h"

namespace shadowcert {
namespace {

using Clock = std::chrono::steady_clock;

// A ray's first hit (as reference/exact_image.cpp's): `degenerate` when the first contact is at
// a zero sign (an edge, a vertex, the eye on the triangle, a tie, a contact in a plane).
struct RayHit {
  std::uint32_t triangle = kNoMesh;
  bool degenerate = false;
  Sign eye_side = Sign::zero;
  Sign direction_side = Sign::zero;
};

// One ray's verdict for one light: `value`, and whether no other caster shadows or bounds it
// (`clear`): on an analytic caster, verdicts that differ only by its terminator then make the
// pixel caster_band.
enum class RayValue : std::uint8_t { none, degenerate, boundary, faces_away, lit, shadowed, band };
struct RayVerdict {
  RayValue value = RayValue::none;
  bool clear = false;
};

struct Geometry {
  Soup soup;                                  // every mesh's triangles (scene/merged_soup.h)
  std::vector<std::uint32_t> mesh_of;         // [triangle]: its mesh
  std::vector<std::uint32_t> first_triangle;  // [mesh]: its first triangle in `soup`
  std::vector<const Ellipsoid*> analytic;     // [mesh]: the ellipsoid it casts as, or null
  std::vector<std::vector<std::array<Vec3, 3>>> normals;  // [mesh]: an analytic caster's corner normals
  std::vector<std::uint32_t> casting;         // triangles cast as triangles (the others' casting meshes)
  std::vector<HomogeneousPoint> lights;
  std::vector<std::vector<Sign>> light_sides;  // [light][triangle]: s(t)
  std::unique_ptr<detail::BoxTree> tree;       // every triangle, for first hits
  std::unique_ptr<detail::BoxTree> casting_tree;  // `casting`, for segments to the light
  double band = kDefaultTerminatorBand;

  [[nodiscard]] const Vec3& vertex(std::uint32_t triangle, int k) const {
    return soup.vertices[soup.triangles[triangle][static_cast<std::size_t>(k)]];
  }
};

std::vector<Box> subset_boxes(const Soup& soup, const std::vector<std::uint32_t>& subset) {
  std::vector<Box> boxes;
  boxes.reserve(subset.size());
  for (const std::uint32_t t : subset) boxes.push_back(triangle_box(soup.vertices, soup.triangles[t]));
  return boxes;
}

// The corner normals of mesh `m`, an analytic caster: the caller's, else its soup's.
std::vector<std::array<Vec3, 3>> corner_normals(const Scene& scene, std::size_t m, const AnalyticImageOptions& options) {
  const SceneMesh& mesh = scene.meshes[m];
  if (m < options.corner_normals.size() && !options.corner_normals[m].empty()) {
    if (options.corner_normals[m].size() != mesh.soup.triangles.size())
      throw std::invalid_argument("analytic_shadow_image: mesh " + mesh.name + " has " +
                                  std::to_string(options.corner_normals[m].size()) + " corner normal triples for " +
                                  std::to_string(mesh.soup.triangles.size()) + " triangles");
    return options.corner_normals[m];
  }
  if (mesh.soup.normals.size() != mesh.soup.vertices.size() || mesh.soup.vertices.empty())
    throw std::invalid_argument("analytic_shadow_image: mesh " + mesh.name +
                                " casts as an ellipsoid but has no normals to define its terminator");
  std::vector<std::array<Vec3, 3>> out(mesh.soup.triangles.size());
  for (std::size_t t = 0; t < out.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Normal& n = mesh.soup.normals[mesh.soup.triangles[t][k]];
      out[t][k] = {n[0], n[1], n[2]};
    }
  return out;
}

Geometry build_geometry(const Scene& scene, const AnalyticImageOptions& options) {
  if (!(options.terminator_band >= 0.0 && options.terminator_band < 1.0))
    throw std::invalid_argument("analytic_shadow_image: the terminator band must be in [0, 1)");
  Geometry g;
  g.band = options.terminator_band;
  for (const SceneMesh& mesh : scene.meshes) {
    require_indices_in_range(mesh.soup, "analytic_shadow_image");
    require_finite_vertices(mesh.soup, "analytic_shadow_image");
  }
  for (const Light& light : scene.lights) {
    require_defined(light, "analytic_shadow_image");
    g.lights.push_back(light.position);
  }
  g.soup = merged_soup(scene);
  if (g.soup.triangles.size() >= kNoMesh) throw std::invalid_argument("analytic_shadow_image: too many triangles");
  g.analytic.assign(scene.meshes.size(), nullptr);
  g.normals.resize(scene.meshes.size());
  std::uint32_t first = 0;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const SceneMesh& mesh = scene.meshes[m];
    g.first_triangle.push_back(first);
    const auto count = static_cast<std::uint32_t>(mesh.soup.triangles.size());
    g.mesh_of.insert(g.mesh_of.end(), count, static_cast<std::uint32_t>(m));
    if (mesh.casts && mesh.ellipsoid) {
      require_proper(*mesh.ellipsoid, "analytic_shadow_image");
      g.analytic[m] = &*mesh.ellipsoid;
      g.normals[m] = corner_normals(scene, m, options);
    } else if (mesh.casts) {
      for (std::uint32_t t = first; t < first + count; ++t) g.casting.push_back(t);
    }
    first += count;
  }
  g.light_sides.resize(scene.lights.size());
  for (std::size_t k = 0; k < scene.lights.size(); ++k) {
    std::vector<Sign>& sides = g.light_sides[k];
    sides.resize(g.soup.triangles.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sides.size(), 4096), [&](const auto& r) {
      for (std::size_t t = r.begin(); t != r.end(); ++t)
        sides[t] = light_orientation(g.vertex(static_cast<std::uint32_t>(t), 0), g.vertex(static_cast<std::uint32_t>(t), 1),
                                     g.vertex(static_cast<std::uint32_t>(t), 2), scene.lights[k]);
    });
  }
  g.tree = std::make_unique<detail::BoxTree>(triangle_boxes(g.soup), detail::LeafTest::exact);
  g.casting_tree = std::make_unique<detail::BoxTree>(subset_boxes(g.soup, g.casting), detail::LeafTest::exact);
  return g;
}

// The first hit of `ray`, exact (reference/exact_image.cpp's first_hit).
RayHit first_hit(const Geometry& g, const PixelRay& ray, std::vector<std::uint32_t>& in_plane) {
  in_plane.clear();
  std::optional<detail::RayParameter> best;
  RayHit hit;
  double bound = std::numeric_limits<double>::infinity();
  g.tree->nearest_first_ray_query(ray.origin, ray.direction, &bound, [&](std::uint32_t id) {
    const Vec3 &a = g.vertex(id, 0), &b = g.vertex(id, 1), &c = g.vertex(id, 2);
    const detail::RayMeeting m = detail::ray_meets_triangle(ray, a, b, c);
    switch (m.contact) {
      case detail::RayContact::apart:
        return true;
      case detail::RayContact::in_plane:
        in_plane.push_back(id);
        return true;
      case detail::RayContact::crosses:
      case detail::RayContact::touches:
        break;
    }
    const detail::RayParameter t(ray, a, b, c, m.direction_side);
    const bool touch = m.contact == detail::RayContact::touches;
    switch (best ? t.compare(*best) : Sign::negative) {
      case Sign::negative:
        best = t;
        hit = {id, touch, m.eye_side, m.direction_side};
        bound = t.upper();
        break;
      case Sign::zero:  // a tie: P lies on two triangles
        hit.degenerate = true;
        hit.triangle = std::min(hit.triangle, id);
        break;
      case Sign::positive:
        break;
    }
    return true;
  });
  for (std::uint32_t id : in_plane) {
    if (best && !detail::in_plane_contact_before(ray, g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2), *best))
      continue;
    hit.degenerate = true;
    hit.triangle = std::min(hit.triangle, id);
  }
  return hit;
}

enum class Crossing : std::uint8_t { none, crosses, touches };

// Whether the open segment P -> light crosses a triangle cast as a triangle (s != 0), the hit
// one excepted: exact/face_crossing.h's rule on P's exact point (reference/exact_image.cpp's
// count_at, stopping at the first crossing or touch).
Crossing polyhedral_crossing(const Geometry& g, std::size_t light, const detail::HitPoint& p, std::uint32_t h) {
  if (g.casting.empty()) return Crossing::none;
  const HomogeneousPoint& l = g.lights[light];
  const std::vector<Sign>& sides = g.light_sides[light];
  Crossing result = Crossing::none;
  const auto classify = [&](std::uint32_t id) {
    const std::uint32_t t = g.casting[id];
    if (t == h) return true;
    const Sign s = sides[t];
    if (s == Sign::zero) return true;  // casts nothing
    const Vec3 &a = g.vertex(t, 0), &b = g.vertex(t, 1), &c = g.vertex(t, 2);
    const Sign start = p.side(a, b, c);
    if (start == Sign::zero || start == s) return true;  // the open segment misses its plane's triangle
    // exact/face_crossing.h's rule on the three edge lines (orient(P, L, p, q) times -start).
    const std::array<std::pair<const Vec3*, const Vec3*>, 3> edges{{{&a, &b}, {&b, &c}, {&c, &a}}};
    switch (detail::fold_boundary_signs([&](int k) {
      const auto& [u, v] = edges[static_cast<std::size_t>(k)];
      return p.orient_with(l, *u, *v) * -start;
    })) {
      case detail::Meeting::apart:
        return true;
      case detail::Meeting::touches:
        result = Crossing::touches;
        return true;  // a crossing elsewhere still shadows P
      case detail::Meeting::crosses:
        break;
    }
    result = Crossing::crosses;
    return false;
  };
  Vec3 from = p.lo(), slack{};
  for (int k = 0; k < 3; ++k) {
    const double mid = p.lo()[k] / 2 + p.hi()[k] / 2;
    from[k] = std::clamp(mid, p.lo()[k], p.hi()[k]);
    slack[k] = std::nextafter(std::max(p.hi()[k] - from[k], from[k] - p.lo()[k]), std::numeric_limits<double>::infinity());
  }
  if (l[3] == 0.0) {
    g.casting_tree->dilated_ray_query(from, {l[0], l[1], l[2]}, slack, classify);
  } else {
    const Vec3 target{l[0], l[1], l[2]};
    if (p.equals(target)) return Crossing::none;  // the open segment is empty
    if (from == target) {
      from = p.lo();
      for (int k = 0; k < 3; ++k)
        slack[k] = std::nextafter(p.hi()[k] - p.lo()[k], std::numeric_limits<double>::infinity());
      if (from == target) from = p.hi();
    }
    g.casting_tree->dilated_segment_query(from, target, slack, classify);
  }
  return result;
}

// The terminator at P (a double approximation of the exact hit point) on triangle h of
// analytic caster m: band, lit or shadowed.
RayValue terminator(const Geometry& g, std::size_t light, const detail::HitPoint& p, std::uint32_t h, std::uint32_t m) {
  Vec3 x{};
  for (int k = 0; k < 3; ++k) x[k] = p.lo()[k] / 2 + p.hi()[k] / 2;
  const Vec3 &a = g.vertex(h, 0), &b = g.vertex(h, 1), &c = g.vertex(h, 2);
  const Vec3 face = cross(difference(b, a), difference(c, a));
  const double area2 = dot(face, face);
  const std::array<Vec3, 3>& n = g.normals[m][h - g.first_triangle[m]];
  if (!(area2 > 0.0)) return RayValue::band;
  const double wa = dot(cross(difference(b, x), difference(c, x)), face) / area2;
  const double wb = dot(cross(difference(c, x), difference(a, x)), face) / area2;
  const double wc = 1.0 - wa - wb;
  const Vec3 normal{wa * n[0][0] + wb * n[1][0] + wc * n[2][0], wa * n[0][1] + wb * n[1][1] + wc * n[2][1],
                    wa * n[0][2] + wb * n[1][2] + wc * n[2][2]};
  const HomogeneousPoint& l = g.lights[light];
  const Vec3 to_light{l[0] - l[3] * x[0], l[1] - l[3] * x[1], l[2] - l[3] * x[2]};
  const double scale = std::sqrt(dot(normal, normal) * dot(to_light, to_light));
  if (!(scale > 0.0)) return RayValue::band;
  const double cosine = dot(normal, to_light) / scale;
  if (std::abs(cosine) < g.band) return RayValue::band;
  return cosine > 0.0 ? RayValue::lit : RayValue::shadowed;
}

// Every light's verdict at `hit` of `ray` into verdicts[0..lights).
void verdicts_at(const Geometry& g, const PixelRay& ray, const RayHit& hit, RayVerdict* verdicts) {
  const std::size_t lights = g.lights.size();
  if (hit.triangle == kNoMesh || hit.degenerate) {
    for (std::size_t k = 0; k < lights; ++k) verdicts[k] = {hit.triangle == kNoMesh ? RayValue::none : RayValue::degenerate, false};
    return;
  }
  const std::uint32_t h = hit.triangle;
  const std::uint32_t m = g.mesh_of[h];
  const detail::RayParameter t(ray, g.vertex(h, 0), g.vertex(h, 1), g.vertex(h, 2), hit.direction_side);
  const detail::HitPoint p(t);
  for (std::size_t k = 0; k < lights; ++k) {
    RayVerdict& v = verdicts[k];
    // A receiver whose own plane does not face the light on the eye's side: its terminator
    // (reference/exact_image.h's kTerminator), ambiguous whatever else.
    if (g.analytic[m] == nullptr && g.light_sides[k][h] != hit.eye_side) {
      v = {RayValue::faces_away, false};
      continue;
    }
    bool boundary = false, shadowed = false;
    for (std::size_t j = 0; j < g.analytic.size() && !shadowed; ++j) {
      if (j == m || g.analytic[j] == nullptr) continue;
      switch (detail::hit_point_occlusion(*g.analytic[j], t, p, g.lights[k])) {
        case Sign::positive: shadowed = true; break;
        case Sign::zero: boundary = true; break;
        case Sign::negative: break;
      }
    }
    if (!shadowed) {
      switch (polyhedral_crossing(g, k, p, h)) {
        case Crossing::crosses: shadowed = true; break;
        case Crossing::touches: boundary = true; break;
        case Crossing::none: break;
      }
    }
    if (shadowed) {
      v = {RayValue::shadowed, false};
    } else if (boundary) {
      v = {RayValue::boundary, false};
    } else if (g.analytic[m] != nullptr) {
      v = {terminator(g, k, p, h, m), true};
    } else {
      v = {RayValue::lit, true};
    }
  }
}

// The pixel's truth from its five rays' meshes and verdicts (centre first).
AnalyticPixel classify(const Geometry& g, const std::array<std::uint32_t, 5>& meshes,
                       const std::array<const RayVerdict*, 5>& verdicts) {
  const std::uint32_t m = meshes[0];
  if (m == kNoMesh) return AnalyticPixel::none;
  const bool caster = g.analytic[m] != nullptr;
  const AnalyticPixel ambiguous = caster ? AnalyticPixel::caster_ambiguous : AnalyticPixel::ambiguous;
  bool band = false, same = true, clear = true;
  for (std::size_t r = 0; r < 5; ++r) {
    const RayVerdict& v = *verdicts[r];
    if (meshes[r] != m) return ambiguous;
    switch (v.value) {
      case RayValue::none:
      case RayValue::degenerate:
      case RayValue::boundary:
      case RayValue::faces_away:
        return ambiguous;
      case RayValue::band:
        band = true;
        break;
      case RayValue::lit:
      case RayValue::shadowed:
        break;
    }
    same = same && v.value == verdicts[0]->value;
    clear = clear && v.clear;
  }
  if (!caster) {
    if (!same) return AnalyticPixel::ambiguous;
    return verdicts[0]->value == RayValue::lit ? AnalyticPixel::lit : AnalyticPixel::shadowed;
  }
  if (same && !band) return verdicts[0]->value == RayValue::lit ? AnalyticPixel::caster_lit : AnalyticPixel::caster_shadowed;
  // No other caster touches the footprint: only the terminator differs across it, or a ray is
  // within its band.
  return clear ? AnalyticPixel::caster_band : AnalyticPixel::caster_ambiguous;
}

}  // namespace

AnalyticShadowImage analytic_shadow_image(const Scene& scene, const AnalyticImageOptions& options) {
  const auto start = Clock::now();
  const CameraFrame frame = camera_frame(scene.camera, "analytic_shadow_image");
  const Geometry g = build_geometry(scene, options);
  const std::uint32_t width = frame.width, height = frame.height;
  const std::size_t lights = g.lights.size();

  // 1. Rays: centres (width x height), then corners ((width + 1) x (height + 1)).
  const std::size_t centres = std::size_t{width} * height;
  const std::size_t corners = std::size_t{width + 1} * (height + 1);
  std::vector<std::uint32_t> ray_mesh(centres + corners, kNoMesh);
  std::vector<RayVerdict> verdicts((centres + corners) * lights);
  const std::uint32_t rows = height + (height + 1);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, rows, 1), [&](const tbb::blocked_range<std::uint32_t>& r) {
    std::vector<std::uint32_t> in_plane;
    for (std::uint32_t row = r.begin(); row != r.end(); ++row) {
      const bool centre_row = row < height;
      const std::uint32_t y = centre_row ? row : row - height;
      const std::uint32_t count = centre_row ? width : width + 1;
      const std::size_t first = centre_row ? std::size_t{y} * width : centres + std::size_t{y} * (width + 1);
      for (std::uint32_t i = 0; i < count; ++i) {
        const double offset = centre_row ? 0.5 : 0.0;
        const PixelRay ray = pixel_ray(frame, i + offset, y + offset);
        const RayHit hit = first_hit(g, ray, in_plane);
        const std::size_t index = first + i;
        ray_mesh[index] = hit.triangle == kNoMesh ? kNoMesh : g.mesh_of[hit.triangle];
        verdicts_at(g, ray, hit, verdicts.data() + index * lights);
      }
    }
  });

  // 2. Pixels.
  AnalyticShadowImage image;
  image.width = width;
  image.height = height;
  image.meshes.assign(ray_mesh.begin(), ray_mesh.begin() + static_cast<std::ptrdiff_t>(centres));
  for (std::uint32_t m = 0; m < g.analytic.size(); ++m)
    if (g.analytic[m] != nullptr) image.analytic_casters.push_back(m);
  image.lights.assign(lights, std::vector<AnalyticPixel>(centres, AnalyticPixel::none));
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, height, 8), [&](const tbb::blocked_range<std::uint32_t>& r) {
    for (std::uint32_t y = r.begin(); y != r.end(); ++y)
      for (std::uint32_t x = 0; x < width; ++x) {
        const std::size_t centre = std::size_t{y} * width + x;
        const std::array<std::size_t, 5> rays{centre, centres + std::size_t{y} * (width + 1) + x,
                                              centres + std::size_t{y} * (width + 1) + x + 1,
                                              centres + std::size_t{y + 1} * (width + 1) + x,
                                              centres + std::size_t{y + 1} * (width + 1) + x + 1};
        std::array<std::uint32_t, 5> meshes{};
        for (std::size_t k = 0; k < 5; ++k) meshes[k] = ray_mesh[rays[k]];
        for (std::size_t light = 0; light < lights; ++light) {
          std::array<const RayVerdict*, 5> v{};
          for (std::size_t k = 0; k < 5; ++k) v[k] = &verdicts[rays[k] * lights + light];
          image.lights[light][centre] = classify(g, meshes, v);
        }
      }
  });
  image.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return image;
}

}  // namespace shadowcert
