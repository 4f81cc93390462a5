#pragma once
// Small soups of the hard cases (docs/definitions.md#hard-cases), one builder each, the only
// copy: the exact tests certify them (tests/support/hard_case_scenes.h), data/scenes/hard/
// holds them as files, and the hard-scene GL campaign places them (campaign/hard_scene.h).
// Each is in its own model space, coordinates within a few units of the origin.
#include <cstdint>

#include "core/soup.h"

namespace shadowcert {

// k >= 1 triangles on the edge (0,0,0)-(0,1,0), apexes on the half circle z > 0 at y = 0.5,
// alternately flipped: with a light in the plane z = 0 away from the edge every apex lies on the
// same side of the plane (edge, light), so |m| = k. Throws std::invalid_argument for k = 0.
[[nodiscard]] Soup half_fan(std::uint32_t k);

// Grazing, sliver and zero-area triangles: a collinear triple of distinct points, a sliver
// 1e-12 high, a triangle 1e-9 off the plane y = 0, a nearly vertical one.
[[nodiscard]] Soup slivers();

// Two squares in y = 0 meeting at a T-junction (the right square's vertex (1, 0, 0.5) on the
// left one's edge x = 1) and a third square stopping 0.001 short of the second: a crack.
[[nodiscard]] Soup t_junctions_and_cracks();

// Two tetrahedra sharing only a vertex, and two triangles sharing only a vertex.
[[nodiscard]] Soup bow_ties();

// `soup` as a binary STL export holds it: every triangle with its own three vertices (nothing
// shared by index), each coordinate rounded to float; no normals.
[[nodiscard]] Soup unwelded(const Soup& soup);

}  // namespace shadowcert
