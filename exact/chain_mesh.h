#pragma once
// exact/'s symbolic shadow-volume chain (exact/shadow_volume_chain.h) as float homogeneous
// triangles (core/homogeneous_mesh.h): what `render --method cpu` uploads, the reference the
// GL volume tests compare every GPU method with, and what `render --capture` writes for cpu.
#include "core/homogeneous_mesh.h"
#include "core/light.h"
#include "core/soup.h"
#include "exact/shadow_volume_chain.h"

namespace shadowcert {

// Vertex ids keep the chain's: [0, n) are `canonical`'s vertices, rounded once to float with
// w = 1; a point light's n + i is x_i's far vertex (x_i - l, 0), x - l formed in double and
// rounded once (so it is the float nearest the exact direction, not a difference of two
// rounded floats); a directional light's n is (-l, 0). Chain triangles are copied; each quad
// (a, b, c, d) becomes (a, b, c) and (a, c, d), which keeps its outward orientation and its
// boundary (the diagonal a-c cancels).
//
// Wide far edges (point light): when the far vertices u - l and v - l of an edge make more than
// a right angle (the light close to the edge's line, between its ends), one triangle between
// them rasterises wrong: GL interpolates the clip coordinates of its far edge through nearly
// the zero vector, and clipping there keeps no digit (a third of a 256x192 frame wrong, with
// the volume closed: tests/regressions/gl/). Such an edge gets far vertices at the bisectors of
// its angle, ids from 2n on, appended in the order they are met, until no piece spans more than
// a right angle; the side quads of that edge become fans over the far polyline, and every back
// cap with a split edge a fan from the far vertex of its plane's normal (at less than a right
// angle from every direction of the cap). The rule depends on the edge alone, so the mesh stays
// closed edge for edge; an unsplit chain's mesh is exactly the two-triangles-per-quad one.
// Preconditions: `chain` was assembled from `canonical` (n == chain.finite_vertices) under
// `light`; throws std::invalid_argument("chain_mesh: ...") when the vertex counts or the
// light's kind disagree.
[[nodiscard]] HomogeneousMesh chain_mesh(const ShadowVolumeChain& chain, const Soup& canonical, const Light& light);
// The same into `mesh`, emptied and refilled within its capacity (volume/volume_workspace.h
// reuses one mesh for every light). Nothing else is allocated unless the chain has a wide far
// edge (the split vertices' table above).
void chain_mesh(const ShadowVolumeChain& chain, const Soup& canonical, const Light& light, HomogeneousMesh& mesh);

}  // namespace shadowcert
