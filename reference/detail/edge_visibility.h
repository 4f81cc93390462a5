#pragma once
// Internal to reference/: exact hidden-line removal along one edge, and where its visible part
// passes through a pixel's eye pyramid (reference/edge_ground_truth.h,
// docs/edge-maps.md#the-exact-ground-truth).
//
// The edge is the segment E(s) = u + s (v - u), s in [0, 1]. A point X of it is HIDDEN by a
// triangle T (not seen edge-on: the eye e strictly off T's plane) when X lies in the closed
// set V(T) = {e + lambda (y - e) : y in T, lambda >= 1}: the segment from the eye to X meets
// T. V(T) is the intersection of four closed half-spaces (T's plane, the far side; the three
// planes through the eye and an edge of T, the side of T's third vertex), so the part of E that
// T hides is one closed interval of s, bounded by parameters where one of those planes' linear
// functions changes sign along E: s = g(u) / (g(u) - g(v)), a rational number never rounded.
// A triangle whose plane holds the whole edge (the edge's own faces, coplanar neighbours) hides
// none of it: from the eye, the open segment to X meets that plane in X alone. A triangle seen
// edge-on hides nothing either: it covers no area of the image. Intervals of zero length are
// dropped, so the VISIBLE part, [0, 1] without the union of the hidden intervals, is a union of
// pieces of positive length, open where an occluder bounds them.
//
// A pixel's eye pyramid is the cone from the eye spanned by its four corner rays' directions
// (core/pixel_ray.h; exactly the pyramid reference/detail/pixel_footprint.h builds its region
// under): four closed half-spaces through the eye, shared with the four neighbouring pixels,
// so the pyramids tile the view exactly. The visible part PASSES through the pixel when it
// meets the open pyramid (then in a piece of positive length), and only TOUCHES it when it
// meets the closed pyramid but not the open one (at a corner ray, or along a face shared with
// a neighbour).
//
// Every decision is a sign of a polynomial in the input doubles: an interval filter first
// (CGAL's Interval_nt), exact binary floats (Mpzf) where it cannot decide. No CGAL here.
#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/sign.h"
#include "core/soup.h"

namespace shadowcert::detail {

// g(X) = det[p1 - p0, q1 - q0, X - o]: a linear function whose zero set is a plane through o.
struct PlaneFunction {
  Vec3 p1{};
  Vec3 p0{};
  Vec3 q1{};
  Vec3 q0{};
  Vec3 o{};
};

// A point E(s) of the edge: s = 0 (start), s = 1 (end), or where a plane function changes sign
// along the edge, s = g(u) / (g(u) - g(v)) (crossing). lo <= s <= hi encloses it.
struct EdgeParameter {
  enum class Kind : std::uint8_t { start, end, crossing };
  Kind kind = Kind::start;
  double lo = 0.0;
  double hi = 0.0;
  PlaneFunction plane{};  // crossing only
};

// A closed range [lo, hi] of parameters, lo <= hi.
struct ParameterRange {
  EdgeParameter lo;
  EdgeParameter hi;
};

enum class ConeMeeting : std::uint8_t {
  none,     // the visible part misses the closed pyramid
  touches,  // it meets the closed pyramid, not the open one
  passes,   // it meets the open pyramid
};

class EdgeVisibility {
 public:
  // The edge u -> v (u != v) seen from `eye`; all of it visible until occlude() hides some.
  EdgeVisibility(const Vec3& u, const Vec3& v, const Vec3& eye);

  // Hides what triangle abc hides. eye_side = orient(a, b, c, eye) (exact/light_orientation.h
  // with the eye as a point light); zero (edge-on or degenerate) hides nothing.
  void occlude(const Vec3& a, const Vec3& b, const Vec3& c, Sign eye_side);

  // The visible pieces, ascending, each of positive length: after every occlude() call.
  [[nodiscard]] std::vector<ParameterRange> visible_pieces() const;

  // Whether `pieces` (from visible_pieces) meet the eye pyramid spanned by `corners`, the
  // directions of a pixel's four corner rays in cyclic order. Exact.
  [[nodiscard]] ConeMeeting meets_cone(const std::vector<ParameterRange>& pieces,
                                       const std::array<Vec3, 4>& corners) const;

  // The point E(s) for s the middle of p's enclosure, in double: for finding candidate pixels.
  [[nodiscard]] Vec3 approximate_point(const EdgeParameter& p) const;

  [[nodiscard]] std::size_t hidden_intervals() const { return hidden_.size(); }

  // sign(a - b), exact.
  [[nodiscard]] Sign compare(const EdgeParameter& a, const EdgeParameter& b) const;

 private:
  Vec3 u_;
  Vec3 v_;
  Vec3 eye_;
  std::vector<ParameterRange> hidden_;
};

}  // namespace shadowcert::detail
