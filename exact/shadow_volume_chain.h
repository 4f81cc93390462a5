#pragma once
// The shadow-volume chain (docs/definitions.md#counts, docs/definitions.md#closure): side quads |m| times per edge oriented by
// sign(m), front caps t' and back caps (t' at infinity, reversed), with symbolic far vertices.
//
// Vertex ids of a chain: [0, n) are the soup's vertices; for a point light n + i is x_inf of
// vertex i, the point at infinity in direction x - l; for a directional light id n is the one
// far vertex (-l, 0), side quads degenerate to triangles (u, v, inf) and back caps vanish.
#include <array>
#include <cstdint>
#include <vector>

#include "core/light.h"
#include "core/soup.h"
#include "exact/edge_multiplicity.h"
#include "scene/edge_table.h"

namespace shadowcert {

struct ShadowVolumeChain {
  std::uint32_t finite_vertices = 0;  // n: the soup's vertex count
  bool directional = false;
  // Every face oriented outwards (normal by the right-hand rule). Point light: caps are
  // triangles and sides quads (v, u, u_inf, v_inf); directional: all faces are triangles.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::array<std::uint32_t, 4>> quads;
  // Kept for counting and for output: side faces by edge, with their signed multiplicity,
  // so a certificate need not expand |m| copies.
  std::vector<std::array<std::uint32_t, 2>> side_edges;  // (u, v), one entry per edge with m != 0
  std::vector<std::int32_t> side_multiplicity;            // m(u, v) for each side edge
  std::vector<std::uint32_t> cap_triangles;               // soup triangles with s != 0
  std::vector<Sign> cap_sign;                             // their s(t)
};

// Assembles the chain of `multiplicities` (any method's). Faces expand |m| copies.
[[nodiscard]] ShadowVolumeChain assemble_chain(const Soup& canonical, const EdgeTable& table,
                                               const EdgeMultiplicities& multiplicities, const Light& light);
// The same into `chain`, whose arrays are emptied and refilled within their capacity: a caller
// that assembles many lights' chains of one soup (volume/volume_workspace.h) allocates them once.
// Only small per-chunk counters (one per 32768 triangles or edges) are allocated per call.
void assemble_chain(const Soup& canonical, const EdgeTable& table, const EdgeMultiplicities& multiplicities,
                    const Light& light, ShadowVolumeChain& chain);

// The chain as a soup for viewing (io/soup_file.h writes it as .off .obj .ply): vertices
// [0, n) are the canonical soup's, [n, 2n) their far points pushed to
// x + far_distance * (x - l) / |x - l| (point light) or x - far_distance * l / |l| (directional)
// in doubles; each side quad is two triangles. Only the picture is approximate, never a
// certificate. Throws std::invalid_argument when the chain was not assembled on `canonical`.
[[nodiscard]] Soup chain_picture(const ShadowVolumeChain& chain, const Soup& canonical, const Light& light,
                                 double far_distance);

}  // namespace shadowcert
