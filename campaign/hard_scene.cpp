#include "campaign/hard_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "campaign/random_soup.h"
#include "core/near_plane.h"
#include "scene/affine_transform.h"
#include "scene/hard_soups.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"
#include "scene/split_mix_random.h"

namespace shadowcert {
namespace {

// Keys the scene's stream apart from the random-soup cases' streams of the same seed and index
// (campaign/random_soup.cpp keys its streams 0, 1, 2).
constexpr std::uint64_t kHardSceneStream = 0x68617264;  // "hard"
// The parts borrowed from the random-soup families are that campaign's cases index * kPartSlots
// + slot of the same seed, one per slot.
constexpr std::uint64_t kPartSlots = 8;
// Shifts and the first light are rounded to this grid: a multiple of 1/64 added to a grid
// part's coordinates (integers times a power of two no finer than 1/64) is exact.
constexpr double kPlacementStep = 1.0 / 64.0;
// Each part is scaled by a power of two to a half extent of at most this (world units).
constexpr double kPartHalfExtent = 0.9;
// Part centres on a ring of this radius range around the origin.
constexpr double kRingMin = 1.6, kRingMax = 2.5;
constexpr double kMaxLift = 0.8;  // the lowest point of a part, above the floor
constexpr double kFloorMargin = 2.0;
constexpr double kFovDegrees = 45.0;

class SceneRandom {
 public:
  SceneRandom(std::uint64_t seed, std::uint64_t index) : random_({seed, index, kHardSceneStream}) {}
  double unit() { return random_.unit(); }
  double between(double lo, double hi) { return lo + (hi - lo) * random_.unit(); }
  std::uint64_t below(std::uint64_t n) { return random_.below(n); }
  std::uint32_t below32(std::uint64_t n) { return static_cast<std::uint32_t>(random_.below(n)); }
  bool chance(double p) { return random_.unit() < p; }

 private:
  SplitMixRandom random_;
};

double snapped(double x) { return std::round(x / kPlacementStep) * kPlacementStep; }

struct Box3 {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()};
  void add(const Vec3& p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  void add(const Soup& s) {
    for (const Vec3& p : s.vertices) add(p);
  }
  [[nodiscard]] Vec3 centre() const { return {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])}; }
  [[nodiscard]] double radius() const {
    const double x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
    return 0.5 * std::sqrt(x * x + y * y + z * z);
  }
};

Soup shifted(Soup s, const Vec3& by) {
  for (Vec3& p : s.vertices)
    for (int k = 0; k < 3; ++k) p[k] += by[k];
  return s;
}

Soup campaign_soup(std::uint64_t seed, std::uint64_t index, std::size_t slot, SoupFamily family,
                   std::uint32_t triangles) {
  CampaignCaseKind kind;
  kind.family = family;  // unit frame; the light is not used
  return make_campaign_case(seed, index * kPartSlots + slot, triangles, kind).soup;
}

// slivers(), t_junctions_and_cracks() and bow_ties() side by side in z.
Soup sliver_set() {
  Soup s = slivers();
  append_soup(s, shifted(t_junctions_and_cracks(), {-0.5, 0.25, 1.5}));
  append_soup(s, shifted(bow_ties(), {-1.0, 0.5, -2.0}));
  return s;
}

// A part in its model space (no normals: only the geometry is hard).
Soup part_soup(SceneRandom& rng, HardPart part, std::uint64_t seed, std::uint64_t index, std::size_t slot) {
  Soup s;
  switch (part) {
    case HardPart::fan:
      s = half_fan(16u << rng.below32(5));
      break;
    case HardPart::grid:
      s = campaign_soup(seed, index, slot, SoupFamily::grid, 30 + rng.below32(91));
      break;
    case HardPart::damaged_mesh:
      s = campaign_soup(seed, index, slot, SoupFamily::mesh, 60 + rng.below32(241));
      break;
    case HardPart::snapped:
      s = campaign_soup(seed, index, slot, SoupFamily::snapped, 40 + rng.below32(161));
      break;
    case HardPart::slivers:
      s = sliver_set();
      break;
    case HardPart::stl_torus:
      s = unwelded(torus({0, 0, 0}, 1.0, rng.between(0.2, 0.45), 12 + rng.below32(37), 6 + rng.below32(11)));
      break;
    case HardPart::uniform:
      s = campaign_soup(seed, index, slot, SoupFamily::uniform, 20 + rng.below32(81));
      break;
  }
  s.normals.clear();
  return s;
}

// The part scaled by a power of two to a half extent of at most kPartHalfExtent, centred on the
// origin by a shift of a multiple of kPlacementStep, turned, and moved to `at` with its lowest
// point `lift` above the floor.
Soup placed(Soup s, SceneRandom& rng, double ring_angle, double lift) {
  Box3 box;
  box.add(s);
  const Vec3 c = box.centre();
  s = shifted(std::move(s), {-snapped(c[0]), -snapped(c[1]), -snapped(c[2])});
  double half = 0.0;
  for (int k = 0; k < 3; ++k) half = std::max(half, 0.5 * (box.hi[k] - box.lo[k]));
  const double scale = half > 0.0 ? std::ldexp(1.0, -static_cast<int>(std::ceil(std::log2(half / kPartHalfExtent)))) : 1.0;
  const bool quarter_turns = rng.chance(0.5);
  Vec3 degrees{};
  for (double& d : degrees) d = quarter_turns ? 90.0 * static_cast<double>(rng.below(4)) : rng.between(0.0, 360.0);
  const double radius = rng.between(kRingMin, kRingMax);
  const Vec3 at{snapped(radius * std::cos(ring_angle)), 0.0, snapped(radius * std::sin(ring_angle))};
  s = transformed(s, compose_trs(at, {scale, scale, scale}, degrees));
  Box3 turned;
  turned.add(s);
  return shifted(std::move(s), {0.0, lift - turned.lo[1], 0.0});
}

Light point_light(const Vec3& p) { return Light{{p[0], p[1], p[2], 1.0}}; }

// A unit direction, uniform on the sphere, its y at least `min_y`.
Vec3 random_direction(SceneRandom& rng, double min_y) {
  const double y = rng.between(min_y, 1.0);
  const double angle = rng.between(0.0, 2.0 * std::numbers::pi);
  const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
  return {r * std::cos(angle), y, r * std::sin(angle)};
}

}  // namespace

std::string_view hard_part_name(HardPart part) {
  switch (part) {
    case HardPart::fan: return "fan";
    case HardPart::grid: return "grid";
    case HardPart::damaged_mesh: return "damaged_mesh";
    case HardPart::snapped: return "snapped";
    case HardPart::slivers: return "slivers";
    case HardPart::stl_torus: return "stl_torus";
    case HardPart::uniform: return "uniform";
  }
  throw std::invalid_argument("hard_part_name: unknown part");
}

HardSceneCase hard_scene_case(std::uint64_t seed, std::uint64_t index, std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0) throw std::invalid_argument("hard_scene_case: empty image");
  SceneRandom rng(seed, index);
  HardSceneCase out;
  out.scene.meshes.push_back({});  // the floor, made once the parts are placed

  // 3 to 5 distinct parts, in random order around the ring.
  std::array<HardPart, kHardParts> order{HardPart::fan,      HardPart::grid,      HardPart::damaged_mesh,
                                         HardPart::snapped,  HardPart::slivers,   HardPart::stl_torus,
                                         HardPart::uniform};
  for (std::size_t i = order.size() - 1; i > 0; --i) std::swap(order[i], order[rng.below(i + 1)]);
  const std::size_t count = 3 + rng.below(3);
  const double start = rng.between(0.0, 2.0 * std::numbers::pi);
  Box3 all;
  std::vector<Box3> boxes;
  for (std::size_t i = 0; i < count; ++i) {
    const HardPart part = order[i];
    const double angle = start + 2.0 * std::numbers::pi * (static_cast<double>(i) + rng.between(-0.2, 0.2)) /
                                     static_cast<double>(count);
    const double lift = rng.chance(0.25) ? 0.0 : snapped(rng.between(0.0, kMaxLift));
    SceneMesh mesh;
    mesh.name = std::string(hard_part_name(part));
    mesh.soup = placed(part_soup(rng, part, seed, index, i), rng, angle, lift);
    Box3 box;
    box.add(mesh.soup);
    boxes.push_back(box);
    all.add(mesh.soup);
    out.parts.push_back(part);
    out.scene.meshes.push_back(std::move(mesh));
  }

  const double reach = std::max({std::fabs(all.lo[0]), std::fabs(all.hi[0]), std::fabs(all.lo[2]), std::fabs(all.hi[2])});
  out.scene.meshes[0].name = "floor";
  out.scene.meshes[0].soup = floor_quad(std::ceil(reach + kFloorMargin));

  // The first light close to one part, above the floor; then point lights above the scene or
  // directions.
  const Box3& near_part = boxes[rng.below(boxes.size())];
  const Vec3 c = near_part.centre();
  const double r = std::max(near_part.radius(), kPlacementStep);
  const Vec3 d = random_direction(rng, -0.3);
  const double distance = r * rng.between(0.5, 1.8);
  Vec3 l{c[0] + distance * d[0], std::max(c[1] + distance * d[1], 0.05), c[2] + distance * d[2]};
  if (rng.chance(0.5))
    for (double& x : l) x = snapped(x);
  out.scene.lights.push_back(point_light(l));
  const std::size_t lights = 1 + rng.below(3);
  for (std::size_t k = 1; k < lights; ++k) {
    if (rng.chance(0.6)) {
      out.scene.lights.push_back(point_light({rng.between(-3.0, 3.0), all.hi[1] + rng.between(1.0, 4.0),
                                              rng.between(-3.0, 3.0)}));
    } else {
      const Vec3 towards = random_direction(rng, 0.2);
      out.scene.lights.push_back(Light{{towards[0], towards[1], towards[2], 0.0}});
    }
  }

  // The camera: the parts' bounding sphere in the vertical field of view.
  const Vec3 target = all.centre();
  const double sphere = std::max(all.radius(), 1.0);
  const double elevation = rng.between(20.0, 65.0) * std::numbers::pi / 180.0;
  const double azimuth = rng.between(0.0, 2.0 * std::numbers::pi);
  const double distance_to_eye = rng.between(1.05, 1.4) * sphere / std::sin(kFovDegrees * std::numbers::pi / 360.0);
  Camera& camera = out.scene.camera;
  camera.eye = {target[0] + distance_to_eye * std::cos(elevation) * std::cos(azimuth),
                target[1] + distance_to_eye * std::sin(elevation),
                target[2] + distance_to_eye * std::cos(elevation) * std::sin(azimuth)};
  camera.target = target;
  camera.up = {0.0, 1.0, 0.0};
  camera.fov_y_degrees = kFovDegrees;
  camera.width = width;
  camera.height = height;
  camera = camera_fitted_to(out.scene);
  return out;
}

}  // namespace shadowcert
