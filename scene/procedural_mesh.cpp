#include "scene/procedural_mesh.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/portable_math.h"
#include "scene/sphere_grid_layout.h"

namespace shadowcert {
namespace {

constexpr std::uint64_t kMaxIndex = std::numeric_limits<std::uint32_t>::max();

void require(bool ok, const char* function, const std::string& what) {
  if (!ok) throw std::invalid_argument(std::string(function) + ": " + what);
}

void require_positive_finite(double x, const char* function, const char* name) {
  // `!(x > 0)` also rejects NaN, which a plain `x <= 0` would let through.
  require(std::isfinite(x) && x > 0.0, function,
          std::string(name) + " must be positive and finite, got " + std::to_string(x));
}

void require_finite(const Vec3& p, const char* function, const char* name) {
  require(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]), function,
          std::string(name) + " must be finite");
}

// The point at angle 2*pi*i/n on the unit circle, with quarter turns exact: a sphere's
// equator then lies exactly in its centre's plane and axis-aligned points are exact.
std::array<double, 2> circle_point(std::uint64_t i, std::uint64_t n) {
  const std::uint64_t m = i % n;
  if ((4 * m) % n == 0) {
    constexpr std::array<std::array<double, 2>, 4> quarters{{{1.0, 0.0}, {0.0, 1.0}, {-1.0, 0.0}, {0.0, -1.0}}};
    return quarters[4 * m / n];
  }
  const double angle = 2.0 * std::numbers::pi * static_cast<double>(m) / static_cast<double>(n);
  return {portable::cos(angle), portable::sin(angle)};
}

Vec3 place(const Vec3& center, double radius, const Vec3& unit) {
  return {center[0] + radius * unit[0], center[1] + radius * unit[1], center[2] + radius * unit[2]};
}

Normal to_normal(const Vec3& unit) {
  return {static_cast<float>(unit[0]), static_cast<float>(unit[1]), static_cast<float>(unit[2])};
}

Vec3 normalized(const Vec3& v) {
  const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / len, v[1] / len, v[2] / len};
}

// A unit UV sphere, computed once and placed many times (sphere_grid): each ring vertex is
// computed once and shared by index, so the mesh is closed by construction.
// Layout: index 0 = north pole (+y), then rings 1..stacks-1 from north to south, each with
// `slices` vertices, then the south pole.
struct UnitUvSphere {
  std::uint32_t slices;
  std::uint32_t stacks;
  std::vector<Vec3> directions;
  std::vector<Triangle> triangles;  // indices relative to the sphere's first vertex
};

UnitUvSphere make_unit_uv_sphere(std::uint32_t slices, std::uint32_t stacks) {
  UnitUvSphere s{slices, stacks, {}, {}};
  const std::uint32_t rings = stacks - 1;
  s.directions.reserve(std::size_t{slices} * rings + 2);
  s.directions.push_back({0.0, 1.0, 0.0});
  std::vector<std::array<double, 2>> around(slices);
  for (std::uint32_t j = 0; j < slices; ++j) around[j] = circle_point(j, slices);
  for (std::uint32_t i = 1; i <= rings; ++i) {
    // Polar angle pi*i/stacks from +y: the same quarter-exact circle, at twice the resolution.
    const auto [cos_polar, sin_polar] = circle_point(i, 2 * std::uint64_t{stacks});
    for (std::uint32_t j = 0; j < slices; ++j)
      s.directions.push_back({sin_polar * around[j][0], cos_polar, sin_polar * around[j][1]});
  }
  s.directions.push_back({0.0, -1.0, 0.0});

  const std::uint32_t south = slices * rings + 1;
  auto ring_vertex = [slices](std::uint32_t ring, std::uint32_t j) { return 1 + (ring - 1) * slices + j % slices; };
  s.triangles.reserve(2 * std::size_t{slices} * rings);
  // With x = sin(polar) cos(a), z = sin(polar) sin(a), the angle a turns from +x towards +z,
  // i.e. clockwise seen from +y: so (pole, next, current) is counter-clockwise from outside.
  for (std::uint32_t j = 0; j < slices; ++j) s.triangles.push_back({0, ring_vertex(1, j + 1), ring_vertex(1, j)});
  for (std::uint32_t i = 1; i < rings; ++i) {
    for (std::uint32_t j = 0; j < slices; ++j) {
      const std::uint32_t a = ring_vertex(i, j), b = ring_vertex(i, j + 1);
      const std::uint32_t c = ring_vertex(i + 1, j), d = ring_vertex(i + 1, j + 1);
      s.triangles.push_back({a, b, d});
      s.triangles.push_back({a, d, c});
    }
  }
  for (std::uint32_t j = 0; j < slices; ++j)
    s.triangles.push_back({south, ring_vertex(rings, j), ring_vertex(rings, j + 1)});
  return s;
}

void append_placed(Soup& out, const UnitUvSphere& unit, const Vec3& center, double radius) {
  const auto base = static_cast<std::uint32_t>(out.vertices.size());
  for (const Vec3& d : unit.directions) {
    out.vertices.push_back(place(center, radius, d));
    out.normals.push_back(to_normal(d));
  }
  for (const Triangle& t : unit.triangles) out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

void check_uv_sphere_size(const char* function, std::uint64_t slices, std::uint64_t stacks, std::uint64_t copies) {
  require(slices * (stacks - 1) * copies + 2 * copies <= kMaxIndex, function,
          "too many vertices for 32-bit indices");
}

// Midpoint-subdivision cache: an edge's midpoint is created once and reused by both
// triangles that share the edge, which keeps the icosphere closed.
class MidpointCache {
 public:
  explicit MidpointCache(std::vector<Vec3>& directions) : directions_(directions) {}

  std::uint32_t midpoint(std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = a < b ? (std::uint64_t{a} << 32 | b) : (std::uint64_t{b} << 32 | a);
    const auto [it, inserted] = cache_.try_emplace(key, static_cast<std::uint32_t>(directions_.size()));
    if (inserted) {
      const Vec3& p = directions_[a];
      const Vec3& q = directions_[b];
      directions_.push_back(normalized({p[0] + q[0], p[1] + q[1], p[2] + q[2]}));
    }
    return it->second;
  }

 private:
  std::vector<Vec3>& directions_;
  std::unordered_map<std::uint64_t, std::uint32_t> cache_;
};

}  // namespace

Soup floor_quad(double half_size) {
  require_positive_finite(half_size, "floor_quad", "half_size");
  const double h = half_size;
  Soup s;
  s.vertices = {{-h, 0.0, -h}, {h, 0.0, -h}, {h, 0.0, h}, {-h, 0.0, h}};
  // Both triangles have (b-a)x(c-a) = (0, 4h^2, 0): facing +y, the side a shadow lands on.
  s.triangles = {{0, 3, 2}, {0, 2, 1}};
  s.normals.assign(4, Normal{0.0F, 1.0F, 0.0F});
  return s;
}

Soup box(const Vec3& min, const Vec3& max) {
  require_finite(min, "box", "min");
  require_finite(max, "box", "max");
  require(min[0] < max[0] && min[1] < max[1] && min[2] < max[2], "box", "min must be < max on every axis");
  Soup s;
  // Vertex i has x = bit 0, y = bit 1, z = bit 2 (0 -> min, 1 -> max).
  for (std::uint32_t i = 0; i < 8; ++i)
    s.vertices.push_back({(i & 1) ? max[0] : min[0], (i & 2) ? max[1] : min[1], (i & 4) ? max[2] : min[2]});
  s.triangles = {{0, 4, 6}, {0, 6, 2},   // -x
                 {1, 3, 7}, {1, 7, 5},   // +x
                 {0, 1, 5}, {0, 5, 4},   // -y
                 {2, 6, 7}, {2, 7, 3},   // +y
                 {0, 2, 3}, {0, 3, 1},   // -z
                 {4, 5, 7}, {4, 7, 6}};  // +z
  return s;
}

Soup uv_sphere(const Vec3& center, double radius, std::uint32_t slices, std::uint32_t stacks) {
  require_finite(center, "uv_sphere", "center");
  require_positive_finite(radius, "uv_sphere", "radius");
  require(slices >= 3, "uv_sphere", "slices must be >= 3, got " + std::to_string(slices));
  require(stacks >= 2, "uv_sphere", "stacks must be >= 2, got " + std::to_string(stacks));
  check_uv_sphere_size("uv_sphere", slices, stacks, 1);
  Soup s;
  append_placed(s, make_unit_uv_sphere(slices, stacks), center, radius);
  return s;
}

Soup icosphere(const Vec3& center, double radius, std::uint32_t subdivisions) {
  require_finite(center, "icosphere", "center");
  require_positive_finite(radius, "icosphere", "radius");
  // 20 * 4^10 = 21M triangles is already far beyond any shading need; 4^16 would overflow indices.
  require(subdivisions <= 10, "icosphere", "subdivisions must be <= 10, got " + std::to_string(subdivisions));

  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> directions;
  for (const Vec3& v : std::array<Vec3, 12>{{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}}})
    directions.push_back(normalized(v));
  std::vector<Triangle> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (std::uint32_t level = 0; level < subdivisions; ++level) {
    MidpointCache cache(directions);
    std::vector<Triangle> finer;
    finer.reserve(faces.size() * 4);
    for (const Triangle& f : faces) {
      const std::uint32_t ab = cache.midpoint(f[0], f[1]);
      const std::uint32_t bc = cache.midpoint(f[1], f[2]);
      const std::uint32_t ca = cache.midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    faces = std::move(finer);
  }

  Soup s;
  s.vertices.reserve(directions.size());
  s.normals.reserve(directions.size());
  for (const Vec3& d : directions) {
    s.vertices.push_back(place(center, radius, d));
    s.normals.push_back(to_normal(d));
  }
  s.triangles = std::move(faces);
  return s;
}

Soup torus(const Vec3& center, double major_radius, double minor_radius, std::uint32_t major_segments,
           std::uint32_t minor_segments) {
  require_finite(center, "torus", "center");
  require_positive_finite(major_radius, "torus", "major_radius");
  require_positive_finite(minor_radius, "torus", "minor_radius");
  // A spindle torus (minor >= major) passes through its own axis: no longer an embedded surface.
  require(minor_radius < major_radius, "torus", "minor_radius must be < major_radius");
  require(major_segments >= 3, "torus", "major_segments must be >= 3, got " + std::to_string(major_segments));
  require(minor_segments >= 3, "torus", "minor_segments must be >= 3, got " + std::to_string(minor_segments));
  require(std::uint64_t{major_segments} * minor_segments <= kMaxIndex, "torus",
          "too many vertices for 32-bit indices");

  std::vector<std::array<double, 2>> tube(minor_segments);
  for (std::uint32_t j = 0; j < minor_segments; ++j) tube[j] = circle_point(j, minor_segments);
  Soup s;
  const std::size_t n = std::size_t{major_segments} * minor_segments;
  s.vertices.reserve(n);
  s.normals.reserve(n);
  for (std::uint32_t i = 0; i < major_segments; ++i) {
    const auto [cu, su] = circle_point(i, major_segments);
    for (std::uint32_t j = 0; j < minor_segments; ++j) {
      const auto [cv, sv] = tube[j];
      const double ring = major_radius + minor_radius * cv;
      s.vertices.push_back({center[0] + ring * cu, center[1] + minor_radius * sv, center[2] + ring * su});
      s.normals.push_back(to_normal({cv * cu, sv, cv * su}));
    }
  }
  auto id = [major_segments, minor_segments](std::uint32_t i, std::uint32_t j) {
    return (i % major_segments) * minor_segments + j % minor_segments;
  };
  s.triangles.reserve(2 * n);
  // dP/dv x dP/du points away from the tube's core circle, so (P, P+dv, P+du) faces outwards.
  for (std::uint32_t i = 0; i < major_segments; ++i) {
    for (std::uint32_t j = 0; j < minor_segments; ++j) {
      const std::uint32_t p00 = id(i, j), p10 = id(i + 1, j), p01 = id(i, j + 1), p11 = id(i + 1, j + 1);
      s.triangles.push_back({p00, p01, p10});
      s.triangles.push_back({p10, p01, p11});
    }
  }
  return s;
}

Soup torus_knot(const Vec3& center, std::uint32_t p, std::uint32_t q, double major_radius, double knot_radius,
                double tube_radius, std::uint32_t segments, std::uint32_t tube_segments) {
  require_finite(center, "torus_knot", "center");
  require(p >= 1 && q >= 1, "torus_knot", "p and q must be >= 1");
  require(std::gcd(p, q) == 1, "torus_knot", "p and q must be coprime, got " + std::to_string(p) + " and " + std::to_string(q));
  require_positive_finite(major_radius, "torus_knot", "major_radius");
  require_positive_finite(knot_radius, "torus_knot", "knot_radius");
  require_positive_finite(tube_radius, "torus_knot", "tube_radius");
  require(knot_radius < major_radius, "torus_knot", "knot_radius must be < major_radius");
  require(segments >= 3, "torus_knot", "segments must be >= 3, got " + std::to_string(segments));
  require(tube_segments >= 3, "torus_knot", "tube_segments must be >= 3, got " + std::to_string(tube_segments));
  require(std::uint64_t{segments} * tube_segments <= kMaxIndex, "torus_knot", "too many vertices for 32-bit indices");

  const double R = major_radius, r = knot_radius, dp = p, dq = q;
  Soup s;
  const std::size_t n = std::size_t{segments} * tube_segments;
  s.vertices.reserve(n);
  s.normals.reserve(n);
  for (std::uint32_t i = 0; i < segments; ++i) {
    const double t = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(segments);
    const double cp = portable::cos(dp * t), sp = portable::sin(dp * t), cq = portable::cos(dq * t), sq = portable::sin(dq * t);
    const double rho = R + r * cq, drho = -r * dq * sq, ddrho = -r * dq * dq * cq;
    const Vec3 c{rho * cp, r * sq, rho * sp};
    const Vec3 d1{drho * cp - rho * dp * sp, r * dq * cq, drho * sp + rho * dp * cp};
    const Vec3 d2{ddrho * cp - 2.0 * drho * dp * sp - rho * dp * dp * cp, -r * dq * dq * sq,
                  ddrho * sp + 2.0 * drho * dp * cp - rho * dp * dp * sp};
    // The Frenet frame: tangent, binormal c' x c'', normal b x t (a torus knot never goes straight).
    const Vec3 tangent = normalized(d1);
    const Vec3 binormal = normalized({d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                                      d1[0] * d2[1] - d1[1] * d2[0]});
    const Vec3 normal{binormal[1] * tangent[2] - binormal[2] * tangent[1],
                      binormal[2] * tangent[0] - binormal[0] * tangent[2],
                      binormal[0] * tangent[1] - binormal[1] * tangent[0]};
    for (std::uint32_t j = 0; j < tube_segments; ++j) {
      const auto [cf, sf] = circle_point(j, tube_segments);
      const Vec3 out{cf * normal[0] + sf * binormal[0], cf * normal[1] + sf * binormal[1], cf * normal[2] + sf * binormal[2]};
      s.vertices.push_back({center[0] + c[0] + tube_radius * out[0], center[1] + c[1] + tube_radius * out[1],
                            center[2] + c[2] + tube_radius * out[2]});
      s.normals.push_back(to_normal(out));
    }
  }
  auto id = [segments, tube_segments](std::uint32_t i, std::uint32_t j) {
    return (i % segments) * tube_segments + j % tube_segments;
  };
  s.triangles.reserve(2 * n);
  // d/dphi x d/dt is the outward direction cos(phi) n + sin(phi) b: (P, P+dphi, P+dt) faces out.
  for (std::uint32_t i = 0; i < segments; ++i)
    for (std::uint32_t j = 0; j < tube_segments; ++j) {
      const std::uint32_t p00 = id(i, j), p10 = id(i + 1, j), p01 = id(i, j + 1), p11 = id(i + 1, j + 1);
      s.triangles.push_back({p00, p01, p10});
      s.triangles.push_back({p10, p01, p11});
    }
  return s;
}

Soup sphere_grid(std::uint64_t total_triangles) {
  require(total_triangles >= kSphereGridMinTriangles && total_triangles <= kSphereGridMaxTriangles, "sphere_grid",
          "the triangle count must be in [" + std::to_string(kSphereGridMinTriangles) + ", " +
              std::to_string(kSphereGridMaxTriangles) + "], got " + std::to_string(total_triangles));
  const SphereGridLayout layout = sphere_grid_layout(total_triangles);
  check_uv_sphere_size("sphere_grid", layout.slices, layout.stacks, kSphereGridSide * kSphereGridSide);
  const UnitUvSphere unit = make_unit_uv_sphere(layout.slices, layout.stacks);

  Soup s;
  const std::size_t spheres = kSphereGridSide * kSphereGridSide;
  s.vertices.reserve(spheres * unit.directions.size());
  s.normals.reserve(spheres * unit.directions.size());
  s.triangles.reserve(spheres * unit.triangles.size());
  const double half = (kSphereGridSide - 1) / 2.0;  // the grid is centred on the origin
  for (std::uint32_t row = 0; row < kSphereGridSide; ++row) {
    for (std::uint32_t col = 0; col < kSphereGridSide; ++col) {
      const Vec3 center{(col - half) * kSphereGridSpacing, kSphereGridRadius, (row - half) * kSphereGridSpacing};
      append_placed(s, unit, center, kSphereGridRadius);
    }
  }
  return s;
}

Soup random_soup(std::uint64_t seed, std::uint64_t triangles, double extent) {
  require_positive_finite(extent, "random_soup", "extent");
  require(triangles <= kMaxIndex / 3, "random_soup", "too many triangles for 32-bit indices");
  // mt19937_64's output sequence is fixed by the standard; the uniform distributions are not,
  // so coordinates come straight from its bits: identical soups on every standard library.
  std::mt19937_64 engine(seed);
  auto coordinate = [&engine, extent] {
    const double unit = static_cast<double>(engine() >> 11) * 0x1.0p-53;  // [0, 1), exact
    return extent * (2.0 * unit - 1.0);                                   // 2u - 1 is exact too
  };
  Soup s;
  s.vertices.reserve(3 * triangles);
  s.triangles.reserve(triangles);
  for (std::uint64_t t = 0; t < triangles; ++t) {
    const auto base = static_cast<std::uint32_t>(3 * t);
    for (int corner = 0; corner < 3; ++corner) {
      const double x = coordinate();
      const double y = coordinate();
      const double z = coordinate();
      s.vertices.push_back({x, y, z});
    }
    s.triangles.push_back({base, base + 1, base + 2});
  }
  return s;
}

Soup nonmanifold_fan(std::uint32_t k) {
  require(k >= 1, "nonmanifold_fan", "k must be >= 1");
  require(k <= kMaxIndex - 2, "nonmanifold_fan", "k too large for 32-bit indices");
  Soup s;
  s.vertices = {{0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  s.vertices.reserve(std::size_t{k} + 2);
  s.triangles.reserve(k);
  for (std::uint32_t i = 0; i < k; ++i) {
    // Apexes evenly around the shared edge at mid-height, so no two blades coincide.
    const auto [c, sn] = circle_point(i, k);
    s.vertices.push_back({c, 0.5, sn});
    const std::uint32_t apex = i + 2;
    // Alternate orientations: the edge's multiplicity then depends on every sign, not a count.
    s.triangles.push_back(i % 2 == 0 ? Triangle{0, 1, apex} : Triangle{1, 0, apex});
  }
  return s;
}

Soup open_box_with_fins() {
  Soup s = box({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  // Remove the +y face (triangles 6 and 7 of box()): the rim edges at y = 1 become borders.
  s.triangles.erase(s.triangles.begin() + 6, s.triangles.begin() + 8);
  // Fins, each one triangle to an apex at y = 1.5 (all coordinates exact binary fractions):
  //   rim z = 0 (vertices 2, 3): one fin leaning out  -> that edge carries 2 triangles;
  //   rim x = 1 (vertices 3, 7): one fin leaning out  -> 2 triangles;
  //   rim x = 0 (vertices 6, 2): a fin leaning out and one leaning in -> 3 triangles;
  //   rim z = 1 (vertices 7, 6): no fin               -> stays a border edge.
  // Each fin's two free edges are border edges too. Fins use the rim edge in the direction
  // opposite to their wall's triangle, as a continued surface would.
  s.vertices.push_back({0.5, 1.5, -0.5});  // 8
  s.vertices.push_back({1.5, 1.5, 0.5});   // 9
  s.vertices.push_back({-0.5, 1.5, 0.5});  // 10
  s.vertices.push_back({0.5, 1.5, 0.5});   // 11
  s.triangles.push_back({3, 2, 8});
  s.triangles.push_back({7, 3, 9});
  s.triangles.push_back({2, 6, 10});
  s.triangles.push_back({2, 6, 11});
  return s;
}

}  // namespace shadowcert
