#pragma once
// The smooth contour of Mattausch et al. 2012 (§3.2, §3.3; docs/smooth-silhouettes.md): each
// accurate silhouette loop (contour/silhouette_loop.h) displaced onto the smooth surface the
// corner normals describe and adaptively subdivided until it is within epsilon of it.
//   - Displacement (Eq. 1): a loop point on the mesh edge (v_i, v_j) at u moves to the cubic
//     Hermite curve of that edge at u: end points v_i, v_j; tangents from the corner normals
//     n_i, n_j as t = e - (n . e) n, normalised and scaled by |e| (e = v_j - v_i). A point at a
//     mesh vertex stays there.
//   - Subdivision (Eq. 2, Listing 1): a contour segment p0 -> p1 with normals n0, n1 (tangents
//     from them as above, e = p1 - p0) gets the point p = H(1/2) while |p - (p0 + p1) / 2| >=
//     epsilon, up to kMaxSubdivisionDepth halvings; the new point's normal is normalize(n0 +
//     n1) and its partner the midpoint of its parents' partners.
// Every contour point keeps its partner p', the point of the accurate silhouette (on the mesh)
// it came from: the smooth shadow volume's gap strip joins p and p' (the paper's §4).
#include <cstdint>
#include <vector>

#include "contour/silhouette_loop.h"
#include "contour/smooth_caster.h"

namespace shadowcert {

// Halvings of one loop segment at most (2^8 pieces): bounds the work where epsilon is below
// what the Hermite curves' own rounding can reach.
inline constexpr std::uint32_t kMaxSubdivisionDepth = 8;

struct ContourPoint {
  Vec3 position{};  // p, on the smooth surface (within epsilon)
  Vec3 normal{};    // unit
  Vec3 partner{};   // p', on the mesh (the accurate silhouette)
  bool at_vertex = false;  // p' is a mesh vertex (then p = p'): caps never move it (cap_offset)
};

struct SmoothContour {
  std::vector<ContourPoint> points;  // a closed contour does not repeat its first point
  // loop_points[i]: where loop point i (displaced) is in `points`; the points its subdivision
  // added lie between loop_points[i] and loop_points[i + 1] (or the end, for a closed loop's last).
  std::vector<std::size_t> loop_points;
  bool closed = false;
};

// The cubic Hermite curve of Eq. 1 at u in [0, 1].
[[nodiscard]] Vec3 hermite_point(const Vec3& p0, const Vec3& p1, const Vec3& t0, const Vec3& t1, double u);

// The tangent at p0 of the segment p0 -> p1 from the unit normal n: e - (n . e) n, normalised and
// scaled by |e| (0 when e is 0 or parallel to n).
[[nodiscard]] Vec3 hermite_tangent(const Vec3& p0, const Vec3& p1, const Vec3& n);

// Precondition (std::invalid_argument("smooth_contour: ...")): epsilon > 0 and finite; `loops`
// are accurate_silhouette loops of `caster`.
[[nodiscard]] std::vector<SmoothContour> smooth_contour(const SmoothCaster& caster,
                                                        const std::vector<SilhouetteLoop>& loops, double epsilon);

}  // namespace shadowcert
