#pragma once
// Internal to reference/: the cone of a tile of pixel rays, as a few dilated segments for
// exact/box_tree.h's dilated queries, so that a tile of the exact image asks the box tree once
// for every triangle any of its rays can meet (reference/exact_image.cpp: the tile's rays then
// test that list instead of each walking the tree). Coherent rays share their traversal, as
// packet and frustum tracers share theirs (docs/diff.md#tiles-coherent-rays-share-their-queries);
// the per-ray tests stay the exact ones, so every answer is the one a per-ray query gives.
//
// The bound: pixel_ray(frame, x, y) has direction d = forward + a right + b up, a and b each
// rounded once from x and y by monotone operations, so over the tile's image points [x0, x1] x
// [y0, y1] they lie in [a(x0), a(x1)] and [b(y1), b(y0)]. d is within s (per axis) of the
// tile's middle direction c (the spread of a and b times |right|, |up|, plus a bound on both
// roundings), so the ray point e + t d lies within t s of e + t c. A point met in the box
// [lo, hi] has t between dist(e, box) / max |d| and max_corner |v - e| / min |d|; that range is
// cut into kEyeTilePieces equal pieces, each dilated by its far end's spread plus the rounding
// of its end points (the cone, not the cylinder of its widest end).
#include <array>
#include <optional>

#include "core/pixel_ray.h"
#include "core/soup.h"

namespace shadowcert::detail {

// Every point within `slack` (per axis, >= 0) of the segment from -> to.
struct DilatedSegment {
  Vec3 from{};
  Vec3 to{};
  Vec3 slack{};
};

inline constexpr std::size_t kEyeTilePieces = 8;
using EyeTileCone = std::array<DilatedSegment, kEyeTilePieces>;

// The pieces holding every point of the box [lo, hi] (the scene's bounds) that a ray
// pixel_ray(frame, x, y) with x in [x0, x1] and y in [y0, y1] (x0 <= x1, y0 <= y1) meets at a
// parameter t >= 0; also every point of such a box in the closed cone from the eye over those
// rays' directions (the eye pyramid of a pixel of the tile). std::nullopt where the bound is not
// worth it or not safe in doubles (an image plane point beyond 2^10 of the axis, a frame
// whose forward barely leads the directions, values beyond 2^400): the caller asks per ray.
[[nodiscard]] std::optional<EyeTileCone> eye_tile_cone(const CameraFrame& frame, double x0, double x1, double y0,
                                                       double y1, const Vec3& lo, const Vec3& hi);

// A bound on |d_k| per axis for the direction d of every ray pixel_ray(frame, x, y) with x in
// [x0, x1] and y in [y0, y1] (as eye_tile_cone's; for filters on the tile's rays' signs).
[[nodiscard]] Vec3 eye_tile_direction_bound(const CameraFrame& frame, double x0, double x1, double y0, double y1);

}  // namespace shadowcert::detail
