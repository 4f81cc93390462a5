#pragma once
// The hard-soup scenes of `shadowcert fuzz --gl --gl-scenes hard` (docs/campaign.md, "Hard-soup
// scenes"): several hard soups placed at random over one floor, lit by point lights close to
// them, seen at a full image size. The random-soup campaign's views hold one soup over a floor at
// 64x48, where a defect of one pixel in a million cannot show; these scenes put many hard
// configurations (fans on one edge, exact coplanarities, duplicated, flipped and fin triangles,
// holes, slivers, T-junctions, bow ties, unwelded STL meshes) into each picture, under lights
// that make their volumes wide and close to the receivers.
//
// Scene `index` of seed `seed` is a function of (seed, index, size) alone (SplitMix64 streams,
// scene/split_mix_random.h; no std::*_distribution), the same with any standard library:
//   - 3 to 5 parts, each one of HardPart, normalised to about a unit box (a power-of-two scale
//     and a shift by a multiple of 1/64, exact for the integer-grid parts), turned by quarter
//     turns (exact: coplanar faces stay coplanar) or freely, and placed on a ring around the
//     origin, its lowest point on the floor or up to 0.8 above it;
//   - the floor: a square of two triangles in the plane y = 0, casting and receiving;
//   - 1 to 3 lights: the first a point light close to one part (0.5 to 1.8 of its radius from
//     its centre, above the floor; every other scene on the grid of 1/64, where it may lie
//     exactly in planes of the grid parts) or, in a quarter of the scenes with an integer part
//     placed by quarter turns, exactly in the plane of one of its triangles (a + i (b - a) +
//     j (c - a), quarter weights, exact); the others point lights above the scene or directions;
//   - the camera looks at the parts' box from a random azimuth and an elevation of 20 to 65
//     degrees, 45 degrees vertical field of view, the box's bounding sphere in view; or, in a
//     quarter of the scenes, from within 1e-6 to 1e-4 (relative) of the plane through the first
//     light and an edge of a part, at the point where that edge's side face meets the floor: the
//     face seen edge-on (issue 27, pertri's reversed side quads); its near plane fitted to the
//     scene (core/near_plane.h).
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/scene.h"

namespace shadowcert {

enum class HardPart : std::uint8_t {
  fan,           // scene/hard_soups.h half_fan(k), k = 16 to 256 triangles on one edge
  grid,          // the campaign's grid family: triangles on integer points, exact coplanarities
  damaged_mesh,  // the campaign's mesh family: spheres, tori, boxes with flips, duplicates, holes, fins
  snapped,       // the campaign's snapped family: a damaged mesh rounded to a small integer grid
  slivers,       // slivers(), t_junctions_and_cracks() and bow_ties() side by side
  stl_torus,     // a torus unwelded as a binary STL stores it (scene/hard_soups.h unwelded)
  uniform,       // independent random triangles
};
inline constexpr std::size_t kHardParts = 7;

struct HardSceneCase {
  // meshes: "floor" first, then one per part named by hard_part_name; every mesh casts.
  Scene scene;
  std::vector<HardPart> parts;  // in mesh order, after the floor
  bool first_light_on_plane = false;  // the first light exactly in a part triangle's plane
  bool edge_on_view = false;          // the eye next to a side face's plane, looking along it
};

// Scene `index` of the hard-scene campaign seeded `seed`, for a width x height image (>= 1
// each; throws std::invalid_argument("hard_scene_case: ...") otherwise).
[[nodiscard]] HardSceneCase hard_scene_case(std::uint64_t seed, std::uint64_t index, std::uint32_t width,
                                            std::uint32_t height);

[[nodiscard]] std::string_view hard_part_name(HardPart part);

}  // namespace shadowcert
