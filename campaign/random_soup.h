#pragma once
// The random soups of the random-soup campaign (docs/campaign.md, docs/definitions.md#hard-cases): every case is a soup
// and a light, drawn deterministically from (campaign seed, case index) alone, so a case is
// replayed on any thread, in any order, by its two numbers. Plain code (no CGAL): the
// adversarial lights are exact *by construction* (below); tests/campaign/random_soup_test.cpp checks
// them with the exact predicate.
//
// A case is built in three steps:
//   1. a soup of the case's family at unit scale (coordinates within a few units of the
//      origin; integers up to 8 for the grid families);
//   2. the frame: p -> 2^e p + (o, o, o). Powers of two keep every grid coordinate and every
//      exact coincidence exact; o = 1e6 is an integer, so offset grid points stay exact too;
//   3. the light, placed on the framed soup.
//
// Exact adversarial lights. The target triangle's three vertices are first snapped to a
// dyadic grid of step U = 2^k, k chosen so that every coordinate is an integer multiple of U
// of magnitude at most 2^48 U while the triangle keeps about 2^16 steps across. Then the
// light a + i (b - a) + j (c - a), with i, j small integers (|i|, |j| <= 3) or quarters, is
// computed without rounding: every intermediate value is a multiple of U / 4 below 2^51 U in
// magnitude, which a double holds exactly. So the light is EXACTLY on the plane, on the edge
// line or at the vertex; "one ulp off" then applies std::nextafter to one coordinate.
// Snapping moves a vertex shared with other triangles along with it: the soup stays connected.
#include <cstdint>
#include <limits>
#include <string_view>

#include "core/light.h"
#include "core/soup.h"

namespace shadowcert {

enum class SoupFamily : std::uint8_t {
  uniform,  // independent uniform random triangles in [-1, 1]^3 (scene/procedural_mesh.h random_soup)
  mesh,     // closed meshes (spheres, tori, boxes) with random flips, duplicates, holes, non-manifold fans
  grid,     // triangles on a pool of points of a small integer grid: exact coplanarity, collinearity, repeats
  snapped,  // a `mesh` soup snapped to a small integer grid: degenerate, duplicate and coplanar triangles
};

enum class LightPlacement : std::uint8_t {
  point,                     // a point light in the soup's box enlarged 2x (grid families: a grid point)
  directional,               // a random direction
  on_plane,                  // exactly on the target triangle's plane, off its edge lines
  on_edge_line,              // exactly on the line of one of the target's edges (inside the edge or beyond)
  at_vertex,                 // exactly at one of the target's vertices
  off_plane,                 // on_plane, then one coordinate one ulp up or down
  off_edge_line,             // on_edge_line, then one ulp off
  off_vertex,                // at_vertex, then one ulp off
  directional_parallel,      // direction i (b - a) + j (c - a): parallel to the target's plane
  directional_parallel_off,  // the same, one component one ulp off
};

inline constexpr std::size_t kSoupFamilies = 4;
inline constexpr std::size_t kLightPlacements = 10;

// p -> 2^scale_exponent * p + (offset, offset, offset): scale_exponent in [-20, 20]
// (1e-6 to 1e6), offset 0 or 1e6.
struct SoupFrame {
  int scale_exponent = 0;
  double offset = 0.0;
};

struct CampaignCaseKind {
  SoupFamily family = SoupFamily::uniform;
  LightPlacement light = LightPlacement::point;
  SoupFrame frame;
};

inline constexpr std::uint32_t kNoTarget = std::numeric_limits<std::uint32_t>::max();

struct CampaignCase {
  Soup soup;  // no normals
  Light light;
  // The placement actually used: an adversarial placement with no usable target triangle (all
  // degenerate, or a zero direction) falls back to `point` or `directional`.
  CampaignCaseKind kind;
  // Adversarial placements: the soup triangle the light was placed against (kNoTarget
  // otherwise) and its corner k: at/off a vertex, corner k; on/off an edge line, the edge
  // from corner k to corner (k + 1) % 3.
  std::uint32_t target = kNoTarget;
  std::uint8_t corner = 0;
  // The exact placement before the one-ulp move of the off_* placements (== light otherwise).
  Light unmoved;
};

// The kind of case `index` of a campaign seeded `seed`: its family, light placement and frame.
[[nodiscard]] CampaignCaseKind draw_case_kind(std::uint64_t seed, std::uint64_t index);

// Case `index` of kind `kind`, with exactly `triangles` triangles (>= 1; throws
// std::invalid_argument("make_campaign_case: ...") otherwise). Deterministic in all arguments.
[[nodiscard]] CampaignCase make_campaign_case(std::uint64_t seed, std::uint64_t index, std::uint32_t triangles,
                                      const CampaignCaseKind& kind);

// make_campaign_case(seed, index, triangles, draw_case_kind(seed, index)).
[[nodiscard]] CampaignCase campaign_case(std::uint64_t seed, std::uint64_t index, std::uint32_t triangles);

[[nodiscard]] std::string_view family_name(SoupFamily family);
[[nodiscard]] std::string_view placement_name(LightPlacement placement);

}  // namespace shadowcert
