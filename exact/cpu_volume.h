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
#include "exact/edge_multiplicity.h"
#include "exact/shadow_volume_chain.h"
#include "scene/edge_table.h"

namespace shadowcert {

// `canonical`: scene/canonical_soup.h's soup (any finite coordinates); `table`:
// build_edge_table(canonical); `light`: finite, w 0 or 1, not direction (0, 0, 0). Vertex ids
// of the result are chain_mesh's over `canonical`. Throws std::invalid_argument("cpu_volume_mesh:
// ...") on a bad light, and (from exact_multiplicities, naming it) on a light that rounds to an
// infinite float or a table that does not fit the soup.
[[nodiscard]] HomogeneousMesh cpu_volume_mesh(const Soup& canonical, const EdgeTable& table, const Light& light);

// What one build of the cpu volume fills, kept by a caller that builds many (one per light, per
// frame: volume/volume_workspace.h) so that each step refills arrays of the capacity it left:
// the exact multiplicities, the chain (which the count certificate reads) and the mesh.
struct CpuVolumeBuffers {
  EdgeMultiplicities multiplicities;
  ShadowVolumeChain chain;
  HomogeneousMesh mesh;
};

// cpu_volume_mesh's steps after the soup's rounding, into `buffers` (the same code: the value
// form above is this on float_rounded(canonical)): `rounded` is float_rounded of a canonical
// soup, rounded once by the caller for all its lights; `table` its edge table; `light` as above,
// rounded here. buffers.mesh is then cpu_volume_mesh(canonical, table, light), bit for bit, and
// buffers.chain the chain it was made of. Throws std::invalid_argument("rounded_cpu_volume: ...")
// when a coordinate of `rounded` is not a float value, and as cpu_volume_mesh otherwise.
void rounded_cpu_volume(const Soup& rounded, const EdgeTable& table, const Light& light, CpuVolumeBuffers& buffers);

}  // namespace shadowcert
