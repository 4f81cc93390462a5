#pragma once
// Internal to exact/: where the occluder-count certificate (exact/count_certificate.h,
// docs/definitions.md#count-certificate) draws its sample points, and the order it checks them in. Sample positions
// are plain doubles computed in floating point: they are inputs of the exact tests, so their
// rounding never affects a verdict (only where the points land).
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "core/box.h"
#include "core/soup.h"

namespace shadowcert::detail {

// The box random samples are drawn in: the bounding box of the vertices the triangles use,
// enlarged on every side by 10% of its largest extent (a flat scene, a floor, still gets
// volume above and below), by 1 when it is a single point; never empty.
[[nodiscard]] Box sampling_box(const Soup& soup);

// Uniform in the closed box.
[[nodiscard]] Vec3 draw_in_box(const Box& box, std::mt19937_64& rng);

// A triangle of the soup chosen uniformly by index, a uniform barycentric point on it, then
// every coordinate moved by one ulp of the point's largest coordinate, up or down at random:
// as close to the surface as doubles allow at that scale, and almost never exactly on the
// triangle's plane, where n is undefined (a point still on a boundary is re-drawn).
// Precondition: the soup has a triangle.
[[nodiscard]] Vec3 draw_near_triangle(const Soup& soup, std::mt19937_64& rng);

// A generator for stream (kind, index) of a run seeded `seed`: the same draws whatever the
// thread that makes them.
[[nodiscard]] std::mt19937_64 sample_stream(std::uint64_t seed, std::uint64_t kind, std::uint64_t index);

// Indices of `points` sorted along a Morton (Z-order) curve over `box` (points outside it are
// clamped to it): consecutive points are near each other, so the segments between them are
// short. Ties keep index order, so the order is deterministic.
[[nodiscard]] std::vector<std::uint32_t> morton_order(const std::vector<Vec3>& points, const Box& box);


}  // namespace shadowcert::detail
