#include "campaign/random_soup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "scene/affine_transform.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"
#include "scene/split_mix_random.h"

namespace shadowcert {
namespace {

// Independent random streams of one case: its kind, its soup, its light. Drawing the kind
// from its own stream lets a test force another kind on the very same soup stream.
enum class Stream : std::uint32_t { kind = 0, soup = 1, light = 2 };

// One stream per (seed, index, purpose) (scene/split_mix_random.h), with the few draws the
// generators need, every one fully specified: the same case with any standard library.
class CaseRandom {
 public:
  CaseRandom(std::uint64_t seed, std::uint64_t index, Stream stream)
      : random_({seed, index, static_cast<std::uint64_t>(stream)}) {}

  std::uint64_t bits() { return random_(); }
  double unit() { return random_.unit(); }            // [0, 1), exact
  double symmetric() { return random_.symmetric(); }  // [-1, 1), exact
  std::uint64_t below(std::uint64_t n) { return random_.below(n); }
  std::uint32_t below32(std::uint64_t n) { return static_cast<std::uint32_t>(below(n)); }
  int between(int lo, int hi) { return lo + static_cast<int>(below(static_cast<std::uint64_t>(hi - lo + 1))); }
  bool chance(double p) { return unit() < p; }
  // An index drawn with the given weights (not all zero).
  template <std::size_t N>
  std::size_t weighted(const std::array<unsigned, N>& weights) {
    unsigned total = 0;
    for (unsigned w : weights) total += w;
    std::uint64_t r = below(total);
    for (std::size_t i = 0; i < N; ++i) {
      if (r < weights[i]) return i;
      r -= weights[i];
    }
    return N - 1;
  }

 private:
  SplitMixRandom random_;
};

// ---- families ------------------------------------------------------------------------------

Triangle reversed(const Triangle& t) { return {t[0], t[2], t[1]}; }

// One closed mesh of about `budget` triangles, at the origin, radius about 1.
Soup closed_mesh(CaseRandom& rng, std::uint32_t budget) {
  switch (rng.below(4)) {
    case 0: {  // 2 * slices * (stacks - 1) triangles
      const auto stacks = static_cast<std::uint32_t>(std::max(2.0, std::round(std::sqrt(budget / 4.0))));
      const std::uint32_t slices = std::max(3u, budget / (2 * (stacks - 1)));
      return uv_sphere({0, 0, 0}, 1.0, slices, stacks);
    }
    case 1:  // 20 * 4^s triangles
      return icosphere({0, 0, 0}, 1.0, budget >= 320 ? 2 : (budget >= 80 ? 1 : 0));
    case 2: {  // 2 * major * minor triangles
      const auto minor = static_cast<std::uint32_t>(std::max(3.0, std::round(std::sqrt(budget / 4.0))));
      const std::uint32_t major = std::max(3u, budget / (2 * minor));
      return torus({0, 0, 0}, 0.7, 0.3, major, minor);
    }
    default: {
      // Drawn into named corners, in this order: the order in which a call's arguments are
      // evaluated is unspecified (g++ goes right to left, clang left to right), and a case must
      // be the same whichever compiler built it (docs/development.md#portable-math).
      const Vec3 hi{rng.unit() + 0.1, rng.unit() + 0.1, rng.unit() + 0.1};
      const Vec3 lo{-rng.unit() - 0.1, -rng.unit() - 0.1, -rng.unit() - 0.1};
      return box(lo, hi);
    }
  }
}

// Half the meshes stay axis-aligned up to quarter turns (exact coplanar faces), half turn freely.
AffineTransform random_placement(CaseRandom& rng) {
  const bool quarter_turns = rng.chance(0.5);
  Vec3 degrees{};
  for (double& d : degrees) d = quarter_turns ? 90.0 * rng.between(0, 3) : 360.0 * rng.unit();
  const double size = 0.3 + 0.7 * rng.unit();
  return compose_trs({0.8 * rng.symmetric(), 0.8 * rng.symmetric(), 0.8 * rng.symmetric()}, {size, size, size},
                     degrees);
}

void erase_random_triangle(CaseRandom& rng, Soup& s) {
  const std::size_t i = rng.below(s.triangles.size());
  s.triangles[i] = s.triangles.back();
  s.triangles.pop_back();
}

// A non-manifold fan: `blades` new triangles on one edge of a random triangle, to new apexes
// around the edge's midpoint, each in a random orientation.
void add_fan(CaseRandom& rng, Soup& s, std::uint32_t blades) {
  const Triangle t = s.triangles[rng.below(s.triangles.size())];  // copies: both vectors grow below
  const std::uint32_t k = rng.below32(3);
  const std::uint32_t u = t[k], v = t[(k + 1) % 3];
  const Vec3 pu = s.vertices[u], pv = s.vertices[v];
  const double length = std::max({std::fabs(pu[0] - pv[0]), std::fabs(pu[1] - pv[1]), std::fabs(pu[2] - pv[2]), 0.05});
  for (std::uint32_t b = 0; b < blades; ++b) {
    const auto apex = static_cast<std::uint32_t>(s.vertices.size());
    s.vertices.push_back({0.5 * (pu[0] + pv[0]) + length * rng.symmetric(),
                          0.5 * (pu[1] + pv[1]) + length * rng.symmetric(),
                          0.5 * (pu[2] + pv[2]) + length * rng.symmetric()});
    s.triangles.push_back(rng.chance(0.5) ? Triangle{u, v, apex} : Triangle{v, u, apex});
  }
}

void add_duplicate(CaseRandom& rng, Soup& s) {
  const Triangle t = s.triangles[rng.below(s.triangles.size())];
  s.triangles.push_back(rng.chance(0.5) ? t : reversed(t));
}

Soup mesh_soup(CaseRandom& rng, std::uint32_t triangles) {
  Soup s;
  const auto components = static_cast<std::uint32_t>(1 + rng.below(3));
  const std::uint32_t budget = std::max(12u, triangles / components);
  for (std::uint32_t c = 0; c < components; ++c) {
    Soup m = closed_mesh(rng, budget);
    m = transformed(m, random_placement(rng));
    m.normals.clear();
    append_soup(s, m);
  }
  const std::array<double, 3> flip_rates{0.0, 0.05, 0.5};
  const double flip = flip_rates[rng.below(3)];
  for (Triangle& t : s.triangles)
    if (rng.chance(flip)) t = reversed(t);
  const std::uint64_t few = triangles / 10 + 1;
  for (std::uint64_t i = rng.below(few); i > 0; --i) add_duplicate(rng, s);
  for (std::uint64_t i = rng.below(few); i > 0 && s.triangles.size() > 1; --i) erase_random_triangle(rng, s);
  for (std::uint64_t i = rng.below(3); i > 0; --i) add_fan(rng, s, 1 + rng.below32(8));
  // Exactly `triangles`: more holes, or more fans and duplicates.
  while (s.triangles.size() > triangles) erase_random_triangle(rng, s);
  while (s.triangles.size() < triangles) {
    if (rng.chance(0.5))
      add_fan(rng, s, 1);
    else
      add_duplicate(rng, s);
  }
  return s;
}

// Triangles on a pool of points of the grid {-g, ..., g}^3: repeated indices, repeated
// positions, collinear and coplanar triples are all frequent.
Soup grid_soup(CaseRandom& rng, std::uint32_t triangles) {
  const int g = rng.between(1, 3);
  const std::uint64_t pool = 4 + rng.below(2 * std::uint64_t{triangles});
  Soup s;
  for (std::uint64_t i = 0; i < pool; ++i)
    s.vertices.push_back({double(rng.between(-g, g)), double(rng.between(-g, g)), double(rng.between(-g, g))});
  for (std::uint32_t t = 0; t < triangles; ++t)
    s.triangles.push_back({rng.below32(pool), rng.below32(pool), rng.below32(pool)});
  return s;
}

// A mesh soup rounded to the grid {-g, ..., g}^3.
Soup snapped_soup(CaseRandom& rng, std::uint32_t triangles) {
  Soup s = mesh_soup(rng, triangles);
  const int g = rng.between(2, 8);
  double reach = 0.0;
  for (const Vec3& p : s.vertices)
    for (double x : p) reach = std::max(reach, std::fabs(x));
  for (Vec3& p : s.vertices)
    for (double& x : p) x = std::round(x / reach * g);
  return s;
}

// ---- frame ----------------------------------------------------------------------------------

Vec3 framed(const Vec3& p, const SoupFrame& frame) {
  return {std::ldexp(p[0], frame.scale_exponent) + frame.offset, std::ldexp(p[1], frame.scale_exponent) + frame.offset,
          std::ldexp(p[2], frame.scale_exponent) + frame.offset};
}

// ---- lights ---------------------------------------------------------------------------------

bool grid_family(SoupFamily f) { return f == SoupFamily::grid || f == SoupFamily::snapped; }

bool distinct_indices(const Triangle& t) { return t[0] != t[1] && t[1] != t[2] && t[2] != t[0]; }

// (b - a) x (c - a) in doubles is nonzero: the triangle is (almost surely) not collinear.
bool spans_a_plane(const Soup& s, const Triangle& t) {
  const Vec3 &a = s.vertices[t[0]], &b = s.vertices[t[1]], &c = s.vertices[t[2]];
  const double x0 = b[0] - a[0], x1 = b[1] - a[1], x2 = b[2] - a[2];
  const double y0 = c[0] - a[0], y1 = c[1] - a[1], y2 = c[2] - a[2];
  return x1 * y2 - x2 * y1 != 0.0 || x2 * y0 - x0 * y2 != 0.0 || x0 * y1 - x1 * y0 != 0.0;
}

bool needs_plane(LightPlacement p) {
  return p == LightPlacement::on_plane || p == LightPlacement::off_plane || p == LightPlacement::directional_parallel ||
         p == LightPlacement::directional_parallel_off;
}

// A triangle to place the light against: distinct indices, and spanning a plane when the
// placement needs one. kNoTarget when a few tries find none.
std::uint32_t pick_target(CaseRandom& rng, const Soup& s, LightPlacement placement) {
  constexpr int kTries = 16;
  for (int k = 0; k < kTries; ++k) {
    const std::uint32_t t = rng.below32(s.triangles.size());
    const Triangle& tri = s.triangles[t];
    if (distinct_indices(tri) && (!needs_plane(placement) || spans_a_plane(s, tri))) return t;
  }
  return kNoTarget;
}

// Snaps the target's vertices to the dyadic grid of step U = 2^k of the header: every
// coordinate an integer multiple of U of magnitude <= 2^48 U, about 2^16 steps across the
// triangle. The combinations of place_on_target are then exact.
void snap_target(Soup& s, const Triangle& t) {
  double reach = 0.0, extent = 0.0;
  for (int d = 0; d < 3; ++d) {
    double lo = s.vertices[t[0]][d], hi = lo;
    for (std::uint32_t i : t) {
      lo = std::min(lo, s.vertices[i][d]);
      hi = std::max(hi, s.vertices[i][d]);
      reach = std::max(reach, std::fabs(s.vertices[i][d]));
    }
    extent = std::max(extent, hi - lo);
  }
  if (reach == 0.0) return;  // all at the origin: already on every grid
  int k = std::ilogb(reach) + 1 - 48;
  if (extent > 0.0) k = std::max(k, std::ilogb(extent) - 16);
  for (std::uint32_t i : t)
    for (double& x : s.vertices[i]) x = std::ldexp(std::nearbyint(std::ldexp(x, -k)), k);
}

// a + i (b - a) + j (c - a), exact on snapped vertices (header).
Vec3 combination(const Vec3& a, const Vec3& b, const Vec3& c, double i, double j) {
  Vec3 p{};
  for (int d = 0; d < 3; ++d) p[d] = a[d] + i * (b[d] - a[d]) + j * (c[d] - a[d]);
  return p;
}

void one_ulp_off(CaseRandom& rng, Light& light) {
  const std::size_t axis = rng.below(3);
  const double toward =
      rng.chance(0.5) ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
  light.position[axis] = std::nextafter(light.position[axis], toward);
}

Light point_light(const Vec3& p) { return Light{{p[0], p[1], p[2], 1.0}}; }

Light random_direction(CaseRandom& rng) {
  for (;;) {
    const Vec3 d{rng.symmetric(), rng.symmetric(), rng.symmetric()};
    if (d[0] != 0.0 || d[1] != 0.0 || d[2] != 0.0) return Light{{d[0], d[1], d[2], 0.0}};
  }
}

// A point light uniform in the bounding box of the soup's vertices enlarged 2x about its centre.
Light random_point(CaseRandom& rng, const Soup& s) {
  Vec3 lo = s.vertices.front(), hi = lo;
  for (const Vec3& p : s.vertices)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  Vec3 p{};
  for (int d = 0; d < 3; ++d) p[d] = 0.5 * (lo[d] + hi[d]) + (hi[d] - lo[d]) * rng.symmetric();
  return point_light(p);
}

// The adversarial placements on the (snapped) target triangle.
std::optional<Light> place_on_target(CaseRandom& rng, CampaignCase& c) {
  const Triangle& t = c.soup.triangles[c.target];
  const Vec3& a = c.soup.vertices[t[c.corner]];
  const Vec3& b = c.soup.vertices[t[(c.corner + 1) % 3]];
  const Vec3& d = c.soup.vertices[t[(c.corner + 2) % 3]];
  // Off both edge lines through a and off the line bc: j != 0, i != 0, i + j != 1.
  constexpr std::array<std::array<double, 2>, 8> kInPlane{
      {{1, 1}, {-1, -1}, {0.25, 0.25}, {3, -1}, {-1, 3}, {2, 1}, {1, 2}, {-1, 0.25}}};
  constexpr std::array<double, 6> kOnLine{0.5, 0.25, -1, 2, 3, -0.25};  // 0.5, 0.25: inside the edge
  constexpr std::array<std::array<double, 2>, 6> kParallel{{{1, 0}, {0, 1}, {1, 1}, {1, -1}, {2, 1}, {-1, 2}}};
  switch (c.kind.light) {
    case LightPlacement::on_plane:
    case LightPlacement::off_plane: {
      const auto& w = kInPlane[rng.below(kInPlane.size())];
      return point_light(combination(a, b, d, w[0], w[1]));
    }
    case LightPlacement::on_edge_line:
    case LightPlacement::off_edge_line:
      return point_light(combination(a, b, d, kOnLine[rng.below(kOnLine.size())], 0.0));
    case LightPlacement::at_vertex:
    case LightPlacement::off_vertex:
      return point_light(a);
    case LightPlacement::directional_parallel:
    case LightPlacement::directional_parallel_off: {
      const auto& w = kParallel[rng.below(kParallel.size())];
      const Vec3 zero{0, 0, 0};
      Vec3 dir{};
      for (int k = 0; k < 3; ++k) dir[k] = w[0] * (b[k] - a[k]) + w[1] * (d[k] - a[k]);
      if (dir == zero) return std::nullopt;
      return Light{{dir[0], dir[1], dir[2], 0.0}};
    }
    case LightPlacement::point:
    case LightPlacement::directional:
      break;
  }
  return std::nullopt;
}

bool one_ulp_variant(LightPlacement p) {
  return p == LightPlacement::off_plane || p == LightPlacement::off_edge_line || p == LightPlacement::off_vertex ||
         p == LightPlacement::directional_parallel_off;
}

bool directional_placement(LightPlacement p) {
  return p == LightPlacement::directional || p == LightPlacement::directional_parallel ||
         p == LightPlacement::directional_parallel_off;
}

void place_light(CaseRandom& rng, CampaignCase& c) {
  const LightPlacement wanted = c.kind.light;
  if (wanted != LightPlacement::point && wanted != LightPlacement::directional) {
    c.target = pick_target(rng, c.soup, wanted);
    if (c.target != kNoTarget) {
      c.corner = static_cast<std::uint8_t>(rng.below(3));
      snap_target(c.soup, c.soup.triangles[c.target]);
      if (const std::optional<Light> light = place_on_target(rng, c)) {
        c.light = c.unmoved = *light;
        if (one_ulp_variant(wanted)) one_ulp_off(rng, c.light);
        return;
      }
      c.target = kNoTarget;
      c.corner = 0;
    }
    c.kind.light = directional_placement(wanted) ? LightPlacement::directional : LightPlacement::point;
  }
  c.light = c.unmoved = c.kind.light == LightPlacement::directional ? random_direction(rng) : random_point(rng, c.soup);
}

}  // namespace

CampaignCaseKind draw_case_kind(std::uint64_t seed, std::uint64_t index) {
  CaseRandom rng(seed, index, Stream::kind);
  CampaignCaseKind kind;
  kind.family = static_cast<SoupFamily>(rng.weighted(std::array<unsigned, kSoupFamilies>{30, 30, 20, 20}));
  kind.light = static_cast<LightPlacement>(
      rng.weighted(std::array<unsigned, kLightPlacements>{25, 10, 10, 10, 8, 10, 8, 7, 6, 6}));
  const double frame = rng.unit();
  if (frame < 0.5) return kind;  // unit scale
  if (frame < 0.75) {
    kind.frame.scale_exponent = rng.between(-20, 20);
  } else {
    kind.frame.scale_exponent = rng.between(-20, 0);
    kind.frame.offset = 1e6;
  }
  return kind;
}

CampaignCase make_campaign_case(std::uint64_t seed, std::uint64_t index, std::uint32_t triangles, const CampaignCaseKind& kind) {
  if (triangles == 0) throw std::invalid_argument("make_campaign_case: a case needs at least one triangle");
  if (kind.frame.scale_exponent < -20 || kind.frame.scale_exponent > 20 ||
      (kind.frame.offset != 0.0 && kind.frame.offset != 1e6))
    throw std::invalid_argument("make_campaign_case: the frame's scale exponent must be in [-20, 20], its offset 0 or 1e6");
  CaseRandom soup_rng(seed, index, Stream::soup);
  CampaignCase c;
  c.kind = kind;
  switch (kind.family) {
    case SoupFamily::uniform:
      c.soup = random_soup(soup_rng.bits(), triangles, 1.0);
      break;
    case SoupFamily::mesh:
      c.soup = mesh_soup(soup_rng, triangles);
      break;
    case SoupFamily::grid:
      c.soup = grid_soup(soup_rng, triangles);
      break;
    case SoupFamily::snapped:
      c.soup = snapped_soup(soup_rng, triangles);
      break;
  }
  CaseRandom light_rng(seed, index, Stream::light);
  // A grid family's point light is a grid point too, framed with the soup: it then lies
  // exactly on many of the soup's planes and lines.
  if (grid_family(kind.family) && kind.light == LightPlacement::point) {
    double reach = 0.0;
    for (const Vec3& p : c.soup.vertices)
      for (double x : p) reach = std::max(reach, std::fabs(x));
    const int g = static_cast<int>(reach) + 1;
    c.light = point_light(
        framed({double(light_rng.between(-g, g)), double(light_rng.between(-g, g)), double(light_rng.between(-g, g))},
               kind.frame));
    for (Vec3& p : c.soup.vertices) p = framed(p, kind.frame);
    c.unmoved = c.light;
    return c;
  }
  for (Vec3& p : c.soup.vertices) p = framed(p, kind.frame);
  place_light(light_rng, c);
  return c;
}

CampaignCase campaign_case(std::uint64_t seed, std::uint64_t index, std::uint32_t triangles) {
  return make_campaign_case(seed, index, triangles, draw_case_kind(seed, index));
}

std::string_view family_name(SoupFamily family) {
  switch (family) {
    case SoupFamily::uniform:
      return "uniform";
    case SoupFamily::mesh:
      return "mesh";
    case SoupFamily::grid:
      return "grid";
    case SoupFamily::snapped:
      return "snapped";
  }
  throw std::invalid_argument("family_name: unknown family");
}

std::string_view placement_name(LightPlacement placement) {
  switch (placement) {
    case LightPlacement::point:
      return "point";
    case LightPlacement::directional:
      return "directional";
    case LightPlacement::on_plane:
      return "on_plane";
    case LightPlacement::on_edge_line:
      return "on_edge_line";
    case LightPlacement::at_vertex:
      return "at_vertex";
    case LightPlacement::off_plane:
      return "off_plane";
    case LightPlacement::off_edge_line:
      return "off_edge_line";
    case LightPlacement::off_vertex:
      return "off_vertex";
    case LightPlacement::directional_parallel:
      return "directional_parallel";
    case LightPlacement::directional_parallel_off:
      return "directional_parallel_off";
  }
  throw std::invalid_argument("placement_name: unknown placement");
}

}  // namespace shadowcert
