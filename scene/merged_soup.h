#pragma once
// Several soups as one (docs/definitions.md#inputs, docs/definitions.md#counts): a scene's shadow volumes see every triangle of every
// casting mesh as a caster, so inspect, certify, render and diff work on the scene's casting
// meshes concatenated (merged_casters), and draw and see every mesh (merged_soup): a mesh with
// "casts": false (core/scene.h) only receives. Concatenation only: no welding
// (scene/welded_soup.h, canonical_soup do that later), so every vertex and triangle keeps its
// values and its relative order.
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "core/soup.h"

namespace shadowcert {

// Appends `from` to `to`: from's vertices after to's, then from's triangles with every index
// raised by to's former vertex count, so that each names the same three points as before.
// Normals (Soup keeps none or one per vertex; a soup without vertices counts as having them)
// are kept only when both soups have them; otherwise the result has none, and shading falls
// back to face normals. Preconditions: both soups valid (indices in range, normals empty or
// one per vertex). Throws std::length_error("append_soup: ...") when the result would hold
// more than 2^32 - 1 vertices (indices are 32-bit); `to` is then unchanged.
void append_soup(Soup& to, const Soup& from);

// Every mesh of `scene`, in the scene's order, appended (append_soup) to an empty soup: mesh
// k's vertices follow those of meshes 0..k-1; normals are kept only when every mesh has them.
// An empty scene gives an empty soup. Throws InputError naming the first mesh (SceneMesh::name)
// that takes the total past 2^32 - 1 vertices.
[[nodiscard]] Soup merged_soup(const Scene& scene);

// The casting meshes of `scene` (SceneMesh::casts) merged as merged_soup merges them all (their
// normals kept when every casting mesh has them): what the shadow volumes are built from. A
// scene whose meshes all cast gives merged_soup(scene). Throws as merged_soup.
[[nodiscard]] Soup merged_casters(const Scene& scene);

// One flag per triangle of merged_soup(scene), in its order: 1 where the triangle's mesh casts,
// 0 where it only receives (reference/exact_image.h's ExactImageOptions::casts).
[[nodiscard]] std::vector<std::uint8_t> casting_triangles(const Scene& scene);

}  // namespace shadowcert
