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
// Preconditions: `chain` was assembled from `canonical` (n == chain.finite_vertices) under
// `light`; throws std::invalid_argument("chain_mesh: ...") when the vertex counts or the
// light's kind disagree.
[[nodiscard]] HomogeneousMesh chain_mesh(const ShadowVolumeChain& chain, const Soup& canonical, const Light& light);

}  // namespace shadowcert
