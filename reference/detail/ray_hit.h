#pragma once
// Internal to exact/: where a pixel ray (core/pixel_ray.h) meets triangles, decided exactly on
// the input doubles, for the exact image (reference/exact_image.h, docs/definitions.md#pixel-protocol):
//   - how the ray meets one triangle (orientation signs only, as exact/face_crossing.h);
//   - which of two meetings comes first along the ray: the parameters t = N / D are compared
//     by the sign of N1 D2 - N2 D1, an interval filter first, exact binary floats (Mpzf) when
//     the intervals overlap;
//   - the hit point P = e + (N / D) d, never rounded: an interval box that encloses it for the
//     filters, and exact homogeneous coordinates (X, W) = (|D| e + sign(D) N d, |D|), W > 0,
//     built on first need, for the signs the box cannot decide.
// Notation: ray origin e, direction d; for a triangle abc, N = det[b - a, c - a, a - e] and
// D = det[b - a, c - a, d], so the ray meets the triangle's plane at t = N / D when D != 0.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include "core/pixel_ray.h"
#include "core/sign.h"
#include "core/soup.h"
#include "exact/light_orientation.h"

namespace shadowcert::detail {

enum class RayContact : std::uint8_t {
  apart,     // the ray (t >= 0) misses the closed triangle, or the triangle has no area
  crosses,   // the open ray passes through the open triangle; e strictly off its plane
  touches,   // it meets the closed triangle in one point at a zero sign: through an edge or a
             // vertex, or from e itself when e lies on the closed triangle (t = 0)
  in_plane,  // the ray lies in the triangle's plane and meets it (along a segment or a point)
};

struct RayMeeting {
  RayContact contact = RayContact::apart;
  Sign eye_side = Sign::zero;        // orient(a, b, c, e)
  Sign direction_side = Sign::zero;  // orient(a, b, c, (d, 0)) = sign D
};

[[nodiscard]] RayMeeting ray_meets_triangle(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c);

// Signs of that test a caller already knows, each certified (a filter's verdict, or exact);
// nullopt: computed here. eye_side = orient(a, b, c, e), direction_side = orient(a, b, c, d),
// edges[k] = orient(e, d, p, q) for the edges pq = ab, bc, ca. The answer is the same.
struct KnownRaySigns {
  std::optional<Sign> eye_side;
  std::optional<Sign> direction_side;
  std::array<std::optional<Sign>, 3> edges{};
};
[[nodiscard]] RayMeeting ray_meets_triangle(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c,
                                            const KnownRaySigns& known);

// ray_meets_triangle's answer where `known` holds all five signs and the direction's is not
// zero (no in-plane test is needed): the same folding of the same signs, inline, for the
// listed rays whose tile filters decide them all. nullopt otherwise.
[[nodiscard]] inline std::optional<RayMeeting> meeting_from_signs(const KnownRaySigns& known) {
  if (!known.eye_side || !known.direction_side || *known.direction_side == Sign::zero || !known.edges[0] ||
      !known.edges[1] || !known.edges[2])
    return std::nullopt;
  RayMeeting m;
  m.eye_side = *known.eye_side;
  m.direction_side = *known.direction_side;
  if (m.eye_side == m.direction_side) return m;  // the plane behind the eye
  const Sign s = m.eye_side != Sign::zero ? m.eye_side : -m.direction_side;
  bool on_boundary = false;
  for (const std::optional<Sign>& edge : known.edges) {
    const Sign side = *edge * -s;  // as fold_boundary_signs (exact/face_crossing.h)
    if (side == Sign::negative) return m;
    on_boundary = on_boundary || side == Sign::zero;
  }
  m.contact = on_boundary || m.eye_side == Sign::zero ? RayContact::touches : RayContact::crosses;
  return m;
}

// A double and a certified bound on its distance from the exact value it estimates:
// |value - exact| <= error (error = +infinity: no estimate).
struct BoundedEstimate {
  double value = 0.0;
  double error = 0.0;
};

// N = det[b - a, c - a, a - e] of the parameter t = N / D at which rays from e meet the plane
// of abc (the same for every direction: a tile's rays share it), with CGAL's Orientation_3
// bound on its rounding (error = +infinity outside that filter's magnitude range).
[[nodiscard]] BoundedEstimate plane_numerator_estimate(const Vec3& e, const Vec3& a, const Vec3& b, const Vec3& c);

// The parameter t = N / D at which the ray meets the plane of abc (crosses or touches, so
// D != 0 and t >= 0). Keeps copies of its inputs for the exact fallback.
class RayParameter {
 public:
  // Precondition: direction_side = sign D != 0 (from ray_meets_triangle).
  RayParameter(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c, Sign direction_side);
  // The same parameter from estimates of N and D a caller already holds (`n` of N =
  // det[b - a, c - a, a - e], `d` of D = det[b - a, c - a, d]: plane_numerator_estimate's for a
  // tile's eye, a tile's direction filter): the semi-static stage without forming N and D
  // again, the constructor above where they are too loose for it (relative error over 2^-10).
  // compare() and the boxes answer as for the constructor above (every verdict is exact; the
  // enclosure, only a filter, may differ in its last bits).
  RayParameter(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c, Sign direction_side,
               const BoundedEstimate& n, const BoundedEstimate& d);
  // The same parameter with the enclosure [0, +infinity] (every meeting has t >= 0), computed
  // without a rounding-mode switch: for callers that keep it only for what it was made of (a
  // HitPoint whose box is known, a footprint's corners); compare() is still exact.
  struct Unenclosed {};
  RayParameter(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c, Sign direction_side, Unenclosed);

  // An upper bound of t (+infinity when the enclosure is unbounded).
  [[nodiscard]] double upper() const { return hi_; }

  // semi_static_hit_box(ray(), triangle()) (below), from the semi-static stage this parameter's
  // enclosure already ran (the same values, not computed twice), into `box`: false (`box`
  // unspecified) where there is none, also for an Unenclosed parameter, which ran none. (An out
  // parameter: a returned optional box is copied with wide loads of values just stored one by
  // one, which stall.)
  [[nodiscard]] bool semi_static_hit_box(std::array<Vec3, 2>& box) const;

  // sign(t - other.t), exact. Both on the same ray.
  [[nodiscard]] Sign compare(const RayParameter& other) const;

  // What it was made of (for reference/detail/hit_point_coordinates.h).
  [[nodiscard]] const PixelRay& ray() const { return ray_; }
  [[nodiscard]] const std::array<Vec3, 3>& triangle() const { return triangle_; }
  [[nodiscard]] Sign direction_side() const { return direction_side_; }

 private:
  friend class HitPoint;
  friend bool in_plane_contact_before(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c,
                                      const RayParameter& bound);
  // The enclosure q (1 -+ rho) of the semi-static stage (t = q (1 + eps), |eps| <= rho).
  void enclose_semi_static(double q, double rho);
  // The enclosure of the interval stage (a rounding-mode switch), where the semi-static one
  // does not apply.
  void enclose_by_intervals();

  PixelRay ray_;
  std::array<Vec3, 3> triangle_;
  Sign direction_side_;
  bool semi_static_ = false;  // q_ and rho_ hold the semi-static stage's t = q (1 + eps), |eps| <= rho
  double q_ = 0.0;
  double rho_ = 0.0;
  double lo_;
  double hi_;
};

// Whether the ray, lying in the plane of abc (an in_plane meeting), meets the closed triangle
// at some t in [0, bound.t]: exact (rational constructions, a rare path).
[[nodiscard]] bool in_plane_contact_before(const PixelRay& ray, const Vec3& a, const Vec3& b, const Vec3& c,
                                           const RayParameter& bound);

// A box enclosing the point where `ray` meets the plane of `triangle` (D != 0), from a
// semi-static filter in round-to-nearest doubles (certified error bounds, ray_hit.cpp; no
// rounding-mode switch): nullopt where the filter does not apply (the caller then takes
// HitPoint's own box). Usually a little wider than HitPoint's; any enclosure serves
// HitPoint(t, box), whose answers are exact whatever the box.
[[nodiscard]] std::optional<std::array<Vec3, 2>> semi_static_hit_box(const PixelRay& ray,
                                                                     const std::array<Vec3, 3>& triangle);

// The point P where the ray meets the plane of a triangle (its RayParameter), with exact
// predicates on it. Not thread-safe (the exact coordinates are built lazily): one per thread.
class HitPoint {
 public:
  explicit HitPoint(const RayParameter& t);
  // The same point with a box known to enclose it (`box`: lo and hi; HitPoint(t)'s own, or
  // semi_static_hit_box's, as a per-ray cache holds them): every answer is HitPoint(t)'s (the
  // box only filters; undecided signs go to the exact coordinates).
  HitPoint(const RayParameter& t, const std::array<Vec3, 2>& box);
  ~HitPoint();
  HitPoint(HitPoint&&) noexcept;
  HitPoint& operator=(HitPoint&&) noexcept;

  // A box that contains P: lo[k] <= P[k] <= hi[k].
  [[nodiscard]] const Vec3& lo() const { return lo_; }
  [[nodiscard]] const Vec3& hi() const { return hi_; }

  // orient(a, b, c, P) = sign det[b - a, c - a, P - a].
  [[nodiscard]] Sign side(const Vec3& a, const Vec3& b, const Vec3& c) const;
  // orient(P, L, p, q): sign det[L - P, p - P, q - P] for a point light, det[l, p - P, q - P]
  // for a directional one (L = (l, 0)); `light` validated by the caller.
  [[nodiscard]] Sign orient_with(const HomogeneousPoint& light, const Vec3& p, const Vec3& q) const;
  // P == x, exact.
  [[nodiscard]] bool equals(const Vec3& x) const;

 private:
  struct Exact;
  const Exact& exact() const;
  // The box's middle (a double, within rounding of the box): where the semi-static filters of
  // side and orient_with evaluate.
  [[nodiscard]] Vec3 middle() const;

  RayParameter t_;
  Vec3 lo_{};
  Vec3 hi_{};
  mutable std::unique_ptr<Exact> exact_;
};

}  // namespace shadowcert::detail
