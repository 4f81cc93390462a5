#pragma once
// The reference shadow volume `render --method cpu` draws (and `shadowcert diff`, the render
// benchmark and the GL volume tests compare every GPU method with): the exact chain
// (docs/definitions.md#counts) of the input AS THE GPU RECEIVES IT, i.e. of the canonical soup with every
// vertex coordinate and the light rounded to float (core/float_rounding.h), as float
// homogeneous triangles (exact/chain_mesh.h).
//
// Why the float-rounded input: a GL renderer gets vertices and light in float (docs/definitions.md#pixel-protocol),
// so the volume it rasterizes is a volume of the rounded geometry. The exact chain of the
// DOUBLE input, once its vertices are rounded for upload, need not be a volume of anything the
// GPU sees: with the light one double ulp above a floor (docs/definitions.md#hard-cases,
// data/scenes/hard/light_one_ulp_off_floor_plane.json) the floor faces the light exactly and
// casts a half-space, but in float the light lies IN the floor's plane, the back cap collapses
// and every floor pixel counts wrong. The GPU-built methods take their signs from the rounded
// input; so does this reference. Float values are exact doubles, so this is still the EXACT
// chain (exact multiplicities, closed by docs/definitions.md#closure), of the geometry actually drawn.
//
// Indices and topology stay those of `canonical` (no re-welding after rounding: two vertices
// that round to one float keep their ids, as they do in the GPU's buffers), so `table` serves
// both inputs.
#include "core/homogeneous_mesh.h"
#include "core/light.h"
#include "core/soup.h"
#include "scene/edge_table.h"

namespace shadowcert {

// `canonical`: scene/canonical_soup.h's soup (any finite coordinates); `table`:
// build_edge_table(canonical); `light`: finite, w 0 or 1, not direction (0, 0, 0). Vertex ids
// of the result are chain_mesh's over `canonical`. Throws std::invalid_argument (from
// exact_multiplicities, naming it) on a bad light or a table that does not fit the soup.
[[nodiscard]] HomogeneousMesh cpu_volume_mesh(const Soup& canonical, const EdgeTable& table, const Light& light);

}  // namespace shadowcert
