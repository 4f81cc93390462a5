#pragma once
// Procedural casters and receivers, deterministic for given parameters (and seed).
// Each returns a soup in its own model space; scenes place it with a transform.
// Throws std::invalid_argument("<function>: ...") on parameters out of range.
#include <cstdint>

#include "core/soup.h"

namespace shadowcert {

// Two triangles spanning [-half_size, half_size]^2 in the plane y = 0, facing +y.
[[nodiscard]] Soup floor_quad(double half_size);
// Axis-aligned closed box, 12 triangles, outward facing.
[[nodiscard]] Soup box(const Vec3& min, const Vec3& max);
// Closed UV sphere: slices >= 3 around y, stacks >= 2; 2*slices*(stacks-1) triangles, vertex normals.
[[nodiscard]] Soup uv_sphere(const Vec3& center, double radius, std::uint32_t slices, std::uint32_t stacks);
// Closed icosphere: 20 * 4^subdivisions triangles, vertex normals.
[[nodiscard]] Soup icosphere(const Vec3& center, double radius, std::uint32_t subdivisions);
// Closed torus around y: 2 * major_segments * minor_segments triangles, vertex normals.
[[nodiscard]] Soup torus(const Vec3& center, double major_radius, double minor_radius,
                         std::uint32_t major_segments, std::uint32_t minor_segments);
// A closed tube around the (p, q) torus knot: the curve winds p times around the y axis and q
// times around the core circle of radius major_radius, at knot_radius from it:
//   c(t) = ((R + r cos qt) cos pt, r sin qt, (R + r cos qt) sin pt),  t in [0, 2 pi),
// swept by a circle of tube_radius in the curve's Frenet frame; `segments` rings along the curve
// of `tube_segments` vertices each: 2 segments tube_segments triangles, vertex normals, outward.
// p, q >= 1 and coprime; knot_radius < major_radius. A tube too thick for its knot intersects
// itself (the defaults do not: 2, 3, 1, 0.4, 0.12).
[[nodiscard]] Soup torus_knot(const Vec3& center, std::uint32_t p, std::uint32_t q, double major_radius,
                              double knot_radius, double tube_radius, std::uint32_t segments,
                              std::uint32_t tube_segments);
// Milet 2014's benchmark: 10 x 10 UV spheres on a grid in the plane y = 1, with as close to
// total_triangles triangles as the sphere resolution allows (32K to 4M requested).
[[nodiscard]] Soup sphere_grid(std::uint64_t total_triangles);
// Uniform random triangles with vertices in [-extent, extent]^3 (mt19937_64 seeded).
[[nodiscard]] Soup random_soup(std::uint64_t seed, std::uint64_t triangles, double extent);
// k >= 1 triangles sharing the edge (0,0,0)-(0,1,0), fanned around it; alternate ones flipped.
[[nodiscard]] Soup nonmanifold_fan(std::uint32_t k);
// A unit box with its top face missing, and fins (single triangles) standing on its rim edges,
// so some edges are border edges and some carry three triangles.
[[nodiscard]] Soup open_box_with_fins();

}  // namespace shadowcert
