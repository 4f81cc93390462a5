#pragma once
// Internal to exact/: a pixel's footprint on the surface it sees, and the two polytopes over it
// that decide whether the pixel's answer is uniform (reference/exact_image.h, docs/definitions.md#pixel-protocol).
//
// The footprint region R is the convex quadrilateral of the four corner rays' hits on the hit
// triangle h (all four see h, so R lies in h). A pixel's answer is uniform when nothing but h
// is seen over R and the count n is constant on R. That fails only if an edge crosses one of:
//   - the eye pyramid hull{e, R}: an edge of another triangle in front of R (a triangle seen
//     inside the footprint but at no corner has an edge there);
//   - the light pyramid hull{L, R} (for a directional light the prism R + s l, s >= 0): a
//     silhouette edge (multiplicity m != 0, docs/definitions.md#counts) between R and the light, i.e. a side
//     face of the shadow-volume chain crossing R, where n changes.
// The corner rays alone miss a shadow sliver or a small triangle that passes between the
// corners and the centre; GL, whose depth test resolves a volume face only to ~1e-3 of the
// view depth, can draw such a feature over the centre.
//
// Exact: "meets" is decided by the separating-axis theorem (the segment and the closed convex
// polytope are disjoint iff a plane parallel to one of the polytope's faces, or to the segment
// and one of its edges, strictly separates them). Each axis is tried in interval arithmetic
// on enclosures of R's corners; an axis the intervals cannot settle is decided exactly, with
// the corners as exact homogeneous points (reference/detail/hit_point_coordinates.h) and Mpzf.
#include <array>
#include <initializer_list>
#include <memory>

#include "core/soup.h"
#include "exact/light_orientation.h"
#include "reference/detail/ray_hit.h"

namespace shadowcert::detail {

class FootprintPolytope {
 public:
  // `apex`: a finite point (w = 1: the eye, or a point light) or a direction (w = 0: a
  // directional light; the polytope is then the prism R + s apex, s >= 0). `corners`: where
  // the four corner rays meet h's plane, in cyclic order (the pixel's corners (i, r),
  // (i + 1, r), (i + 1, r + 1), (i, r + 1) seen on one plane keep that order).
  FootprintPolytope(const HomogeneousPoint& apex, const std::array<RayParameter, 4>& corners);
  // The same with each corner's HitPoint box known (lo, hi: what HitPoint(corners[i]) computes,
  // from a per-ray cache): the same polytope, without recomputing the four boxes.
  using CornerBoxes = std::array<std::array<Vec3, 2>, 4>;
  FootprintPolytope(const HomogeneousPoint& apex, const std::array<RayParameter, 4>& corners, const CornerBoxes& boxes);
  ~FootprintPolytope();
  FootprintPolytope(const FootprintPolytope&) = delete;
  FootprintPolytope& operator=(const FootprintPolytope&) = delete;

  // Whether the closed segment [u, v] meets the closed polytope. Exact.
  [[nodiscard]] bool meets(const Vec3& u, const Vec3& v) const;
  // Whether an edge of triangle abc meets it (after one test of the whole triangle against
  // the polytope's face planes, which settles most far triangles at once). Exact.
  [[nodiscard]] bool meets_an_edge_of(const Vec3& a, const Vec3& b, const Vec3& c) const;

  // A segment from `query_from` to the apex (for a directional apex: a ray from it along the
  // direction), dilated by `query_slack` per axis, contains the polytope (for exact/box_tree.h's
  // dilated queries).
  [[nodiscard]] const Vec3& query_from() const { return from_; }
  [[nodiscard]] const Vec3& query_slack() const { return slack_; }
  // The same two, from the corners' boxes alone (before any polytope is built).
  static void query_box(const CornerBoxes& boxes, Vec3& from, Vec3& slack);

 private:
  struct Bounds {
    double lo = 0.0;
    double hi = 0.0;
  };
  using BoundsVec = std::array<Bounds, 3>;
  // How far intervals settle one axis: the points strictly on one side of the polytope
  // (separated), certainly not, or unsure (then decided exactly).
 public:
  enum class Verdict { separated, not_separated, unsure };

 private:
  struct Exact;
  enum class AxisKind { face, region_edge, apex_edge };
  [[nodiscard]] Verdict face_verdict(std::size_t j, std::initializer_list<const Vec3*> points) const;
  [[nodiscard]] Verdict edge_verdict(AxisKind kind, int index, const Vec3& u, const Vec3& v) const;
  [[nodiscard]] bool exactly_separated(AxisKind kind, int index, std::initializer_list<const Vec3*> points) const;
  [[nodiscard]] const Exact& exact() const;
  void enclose(const CornerBoxes& boxes);

  HomogeneousPoint apex_;
  std::array<RayParameter, 4> corners_;
  bool directional_ = false;
  // Interval enclosures, relative to from_: the finite vertices (apex first when finite, then
  // R's corners), R's edges, the apex edges C_i - A, the face normals (four sides, then R's
  // plane) and the polytope's projection on each: [lo of min, hi of min] and [lo of max, hi
  // of max] over its vertices, opened where a prism is unbounded.
  std::array<BoundsVec, 5> vertices_{};
  int vertex_count_ = 0;
  BoundsVec direction_{};
  std::array<BoundsVec, 4> region_edges_{};
  std::array<BoundsVec, 4> apex_edges_{};
  std::array<BoundsVec, 5> normals_{};
  std::array<Bounds, 5> minimum_{};
  std::array<Bounds, 5> maximum_{};
  Vec3 from_{};
  Vec3 slack_{};
  mutable std::unique_ptr<Exact> exact_;
};

}  // namespace shadowcert::detail
