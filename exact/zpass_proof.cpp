// prove_zpass of exact/zpass_proof.h: whether any face of the exact chain meets the frustum's
// tip, and the occluder count there.
//
// A side face S (convex, planar, unbounded: the wedge at the light beyond the edge uv) meets a
// tetrahedron K exactly when an edge of K meets S or an edge of S (the segment uv, the two rays
// from u and v away from the light) meets K. Proof: let Q = K ∩ plane(S), a convex compact
// polygon, segment or point. If Q meets S but Q is not inside S's relative interior, the segment
// from a point of Q ∩ S to a point of Q outside relint S crosses S's relative boundary, which is
// its edges. If Q lies in relint S, Q's extreme points lie on edges of K (a plane section's
// vertices are where the plane meets edges of the polytope). So no truncation of S at some far
// parameter is needed, and nothing about S is rounded: the edges of K against S are orientation
// signs of input doubles (exact/face_crossing.h), the segment uv and a directional light's rays
// (direction -l, exact) go to CGAL's filtered predicates, and a point light's rays (direction
// u - l, not a double) to CGAL's exact constructions.
#include "exact/zpass_proof.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/box.h"
#include "exact/count_certificate.h"
#include "exact/edge_multiplicity.h"
#include "exact/face_crossing.h"
#include "exact/light_orientation.h"
#include "exact/orient_unchecked.h"

namespace shadowcert {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

template <class K>
typename K::Point_3 point(const Vec3& p) {
  return typename K::Point_3(p[0], p[1], p[2]);
}

// The tip: points[0] the apex, points[1..4] the corners c0..c3; tetrahedra (0, 1, 2, 3) and
// (0, 1, 3, 4), sharing the triangle (apex, c0, c2).
constexpr std::array<std::array<int, 2>, 9> kTipEdges{
    {{0, 1}, {0, 2}, {0, 3}, {0, 4}, {1, 2}, {2, 3}, {3, 4}, {4, 1}, {1, 3}}};
constexpr std::array<std::array<int, 4>, 2> kTipTetrahedra{{{0, 1, 2, 3}, {0, 1, 3, 4}}};

struct Tip {
  std::array<Vec3, 5> points{};
  std::array<HomogeneousPoint, 5> homogeneous{};
  Box box{};
  std::array<Epick::Tetrahedron_3, 2> tetrahedra;
  std::array<Epeck::Tetrahedron_3, 2> exact_tetrahedra;  // for the rays of a point light's sides
};

void require_finite(const Vec3& p, const char* what) {
  for (double x : p)
    if (!std::isfinite(x)) throw std::invalid_argument(std::string("prove_zpass: ") + what + " must be finite");
}

Tip make_tip(const Vec3& apex, const std::array<Vec3, 4>& corners) {
  Tip tip;
  tip.points[0] = apex;
  std::copy(corners.begin(), corners.end(), tip.points.begin() + 1);
  for (std::size_t i = 0; i < tip.points.size(); ++i) {
    require_finite(tip.points[i], i == 0 ? "the apex" : "the near corners");
    tip.homogeneous[i] = finite_point(tip.points[i]);
  }
  tip.box = bounding_box(std::vector<Vec3>(tip.points.begin(), tip.points.end()));
  const auto& h = tip.homogeneous;
  const Sign first = orient(h[0], h[1], h[2], h[3]);
  const Sign second = orient(h[0], h[1], h[3], h[4]);
  if (first == Sign::zero || second != first)
    throw std::invalid_argument(
        "prove_zpass: the tip must be two proper tetrahedra of one orientation (apex, c0, c1, c2) and "
        "(apex, c0, c2, c3)");
  for (std::size_t k = 0; k < 2; ++k) {
    const auto& q = kTipTetrahedra[k];
    tip.tetrahedra[k] = Epick::Tetrahedron_3(point<Epick>(tip.points[q[0]]), point<Epick>(tip.points[q[1]]),
                                             point<Epick>(tip.points[q[2]]), point<Epick>(tip.points[q[3]]));
    tip.exact_tetrahedra[k] = Epeck::Tetrahedron_3(point<Epeck>(tip.points[q[0]]), point<Epeck>(tip.points[q[1]]),
                                                   point<Epeck>(tip.points[q[2]]), point<Epeck>(tip.points[q[3]]));
  }
  return tip;
}

bool boxes_meet(const Box& a, const Box& b) {
  for (std::size_t k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

// True when every point of the tip lies strictly on one side of the plane (p, q, r): the plane,
// hence any face in it, misses the closed tip. A zero keeps the face a candidate.
bool tip_strictly_on_one_side(const Tip& tip, const HomogeneousPoint& p, const HomogeneousPoint& q,
                              const HomogeneousPoint& r) {
  const Sign first = detail::orient_unchecked(p, q, r, tip.homogeneous[0]);
  if (first == Sign::zero) return false;
  for (std::size_t i = 1; i < tip.homogeneous.size(); ++i)
    if (detail::orient_unchecked(p, q, r, tip.homogeneous[i]) != first) return false;
  return true;
}

// The front cap t' lies on the casting triangle abc itself (s != 0: it has area).
bool cap_meets_tip(const Tip& tip, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Box box = bounding_box({a, b, c});
  if (!boxes_meet(box, tip.box)) return false;
  if (tip_strictly_on_one_side(tip, finite_point(a), finite_point(b), finite_point(c))) return false;
  const Epick::Triangle_3 triangle(point<Epick>(a), point<Epick>(b), point<Epick>(c));
  return std::any_of(tip.tetrahedra.begin(), tip.tetrahedra.end(),
                     [&](const Epick::Tetrahedron_3& k) { return CGAL::do_intersect(triangle, k); });
}

// The side face of edge uv (m != 0, so the light is off the line uv and the face has area).
bool side_meets_tip(const Tip& tip, const HomogeneousPoint& light, const Vec3& u, const Vec3& v) {
  if (tip_strictly_on_one_side(tip, light, finite_point(u), finite_point(v))) return false;
  // The tip's edges against the face: a touch (any zero sign that matters) counts as meeting.
  for (const auto& [i, j] : kTipEdges)
    if (detail::segment_meets_side(tip.points[i], tip.points[j], light, u, v).meeting != detail::Meeting::apart)
      return true;
  // The face's edges against the tetrahedra: the segment uv, then the rays from u and v.
  const Epick::Segment_3 uv(point<Epick>(u), point<Epick>(v));
  for (const Epick::Tetrahedron_3& k : tip.tetrahedra)
    if (CGAL::do_intersect(uv, k)) return true;
  if (light[3] == 0.0) {
    const Epick::Vector_3 away(-light[0], -light[1], -light[2]);  // exact: a negation
    for (const Vec3* x : {&u, &v}) {
      const Epick::Ray_3 ray(point<Epick>(*x), away);
      for (const Epick::Tetrahedron_3& k : tip.tetrahedra)
        if (CGAL::do_intersect(ray, k)) return true;
    }
    return false;
  }
  const Epeck::Point_3 l = point<Epeck>({light[0], light[1], light[2]});
  for (const Vec3* x : {&u, &v}) {
    const Epeck::Point_3 start = point<Epeck>(*x);
    const Epeck::Ray_3 ray(start, start - l);  // {l + t (x - l) : t >= 1}, exactly
    for (const Epeck::Tetrahedron_3& k : tip.exact_tetrahedra)
      if (CGAL::do_intersect(ray, k)) return true;
  }
  return false;
}

// The centroid of tetrahedron k of the tip, rounded; kept only when it lies in the closed tip.
std::optional<Vec3> tip_probe(const Tip& tip, std::size_t k) {
  Vec3 c{};
  for (int i : kTipTetrahedra[k])
    for (std::size_t d = 0; d < 3; ++d) c[d] += tip.points[i][d] / 4.0;
  if (tip.tetrahedra[k].has_on_unbounded_side(point<Epick>(c))) return std::nullopt;
  return c;
}

}  // namespace

std::string_view zpass_verdict_name(ZPassVerdict verdict) {
  switch (verdict) {
    case ZPassVerdict::proven: return "proven";
    case ZPassVerdict::camera_in_volume: return "camera_in_volume";
    case ZPassVerdict::face_meets_tip: return "face_meets_tip";
    case ZPassVerdict::count_undefined: return "count_undefined";
  }
  throw std::invalid_argument("zpass_verdict_name: unknown verdict " + std::to_string(static_cast<int>(verdict)));
}

ZPassProof prove_zpass(const Soup& soup, const EdgeTable& table, const Light& light, const Vec3& apex,
                       const std::array<Vec3, 4>& corners) {
  require_defined(light, "prove_zpass");
  require_indices_in_range(soup, "prove_zpass");
  for (const Vec3& p : soup.vertices) require_finite(p, "the soup's vertices");
  if (table.first_opposite.size() != table.edges.size() + 1)
    throw std::invalid_argument("prove_zpass: the edge table does not belong to this soup");
  for (const auto& [u, v] : table.edges)
    if (u >= soup.vertices.size() || v >= soup.vertices.size())
      throw std::invalid_argument("prove_zpass: the edge table does not belong to this soup");
  const Tip tip = make_tip(apex, corners);

  ZPassProof proof;
  // (b) first: a camera inside a volume needs no face test.
  const OccluderCounter counter(soup, light);
  proof.apex_count = counter.count(apex);
  if (proof.apex_count && *proof.apex_count > 0) {
    proof.verdict = ZPassVerdict::camera_in_volume;
    return proof;
  }

  // (a): the front caps (s != 0), then the sides (m != 0); back caps lie at infinity.
  const EdgeMultiplicities m = exact_multiplicities(soup, table, light);
  const auto& v = soup.vertices;
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    if (m.triangle_sign[t] == Sign::zero) continue;  // casts nothing: no cap
    const Triangle& tri = soup.triangles[t];
    if (cap_meets_tip(tip, v[tri[0]], v[tri[1]], v[tri[2]])) {
      proof.verdict = ZPassVerdict::face_meets_tip;
      proof.face_kind = ChainFace::front_cap;
      proof.face = static_cast<std::uint32_t>(t);
      return proof;
    }
  }
  for (std::size_t e = 0; e < table.edges.size(); ++e) {
    if (m.multiplicity[e] == 0) continue;
    const auto& [a, b] = table.edges[e];
    if (side_meets_tip(tip, light.position, v[a], v[b])) {
      proof.verdict = ZPassVerdict::face_meets_tip;
      proof.face_kind = ChainFace::side;
      proof.face = static_cast<std::uint32_t>(e);
      proof.edge = table.edges[e];
      proof.multiplicity = m.multiplicity[e];
      return proof;
    }
  }

  // No face meets the tip: the winding number is one constant on it, n wherever n is defined.
  std::optional<std::uint32_t> count = proof.apex_count;
  for (std::size_t k = 0; k < kTipTetrahedra.size() && !count; ++k)
    if (const std::optional<Vec3> probe = tip_probe(tip, k)) count = counter.count(*probe);
  if (!count) {
    proof.verdict = ZPassVerdict::count_undefined;
  } else {
    proof.verdict = *count == 0 ? ZPassVerdict::proven : ZPassVerdict::camera_in_volume;
  }
  return proof;
}

}  // namespace shadowcert
