#include "reference/detail/edge_visibility.h"

#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <algorithm>
#include <stdexcept>

#include "core/vector3.h"

namespace shadowcert::detail {
namespace {

using Interval = CGAL::Interval_nt<false>;  // only under a Protect_FPU_rounding
using Exact = CGAL::Mpzf;

template <typename NT>
Vector3<NT> minus(const Vec3& p, const Vec3& q) {
  return {NT(p[0]) - NT(q[0]), NT(p[1]) - NT(q[1]), NT(p[2]) - NT(q[2])};
}

// g(x), formed in NT from the raw doubles.
template <typename NT>
NT evaluate(const PlaneFunction& g, const Vec3& x) {
  return det3(minus<NT>(g.p1, g.p0), minus<NT>(g.q1, g.q0), minus<NT>(x, g.o));
}

std::optional<Sign> certain_sign(const Interval& x) {
  if (x.inf() > 0.0) return Sign::positive;
  if (x.sup() < 0.0) return Sign::negative;
  if (x.inf() == 0.0 && x.sup() == 0.0) return Sign::zero;
  return std::nullopt;
}

// sign det[x, y, z] of three double vectors.
Sign determinant_sign(const Vec3& x, const Vec3& y, const Vec3& z) {
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    const Vec3 zero{};
    if (const std::optional<Sign> s =
            certain_sign(det3(minus<Interval>(x, zero), minus<Interval>(y, zero), minus<Interval>(z, zero))))
      return *s;
  }
  const Vec3 zero{};
  return sign_of(det3(minus<Exact>(x, zero), minus<Exact>(y, zero), minus<Exact>(z, zero)));
}

// A plane function on the edge's two ends: enclosures, and exact signs on demand.
struct EndValues {
  const PlaneFunction* g = nullptr;
  const Vec3* u = nullptr;
  const Vec3* v = nullptr;
  double u_lo = 0.0, u_hi = 0.0, v_lo = 0.0, v_hi = 0.0;  // enclosures of g(u), g(v)

  EndValues(const PlaneFunction& plane, const Vec3& start, const Vec3& end) : g(&plane), u(&start), v(&end) {
    const CGAL::Protect_FPU_rounding<true> protect;
    const Interval gu = evaluate<Interval>(plane, start), gv = evaluate<Interval>(plane, end);
    u_lo = gu.inf();
    u_hi = gu.sup();
    v_lo = gv.inf();
    v_hi = gv.sup();
  }
  [[nodiscard]] static std::optional<Sign> certain(double lo, double hi) {
    if (lo > 0.0) return Sign::positive;
    if (hi < 0.0) return Sign::negative;
    if (lo == 0.0 && hi == 0.0) return Sign::zero;
    return std::nullopt;
  }
  [[nodiscard]] Sign at_u() const {
    if (const std::optional<Sign> s = certain(u_lo, u_hi)) return *s;
    return sign_of(evaluate<Exact>(*g, *u));
  }
  [[nodiscard]] Sign at_v() const {
    if (const std::optional<Sign> s = certain(v_lo, v_hi)) return *s;
    return sign_of(evaluate<Exact>(*g, *v));
  }
  // Certainly inside * g < 0 at both ends: the closed restriction is empty.
  [[nodiscard]] bool certainly_outside(Sign inside) const {
    return inside == Sign::positive ? (u_hi < 0.0 && v_hi < 0.0) : (u_lo > 0.0 && v_lo > 0.0);
  }
  [[nodiscard]] bool certainly_inside(Sign inside) const {
    return inside == Sign::positive ? (u_lo > 0.0 && v_lo > 0.0) : (u_hi < 0.0 && v_hi < 0.0);
  }
  // Where g changes sign along the edge, with its enclosure (g(u) and g(v) of opposite signs,
  // or one of them zero, so that s lies in [0, 1]).
  [[nodiscard]] EdgeParameter crossing() const {
    EdgeParameter p;
    p.kind = EdgeParameter::Kind::crossing;
    p.plane = *g;
    p.lo = 0.0;
    p.hi = 1.0;
    const CGAL::Protect_FPU_rounding<true> protect;
    const Interval gu(u_lo, u_hi), gv(v_lo, v_hi);
    const Interval d = gu - gv;
    if (d.inf() > 0.0 || d.sup() < 0.0) {
      const Interval s = gu / d;
      p.lo = std::clamp(s.inf(), 0.0, 1.0);
      p.hi = std::clamp(s.sup(), 0.0, 1.0);
    }
    return p;
  }
};

EdgeParameter start_parameter() { return {EdgeParameter::Kind::start, 0.0, 0.0, {}}; }
EdgeParameter end_parameter() { return {EdgeParameter::Kind::end, 1.0, 1.0, {}}; }

// s as an exact fraction n / d (d != 0).
std::pair<Exact, Exact> exact_fraction(const EdgeParameter& p, const Vec3& u, const Vec3& v) {
  switch (p.kind) {
    case EdgeParameter::Kind::start:
      return {Exact(0), Exact(1)};
    case EdgeParameter::Kind::end:
      return {Exact(1), Exact(1)};
    case EdgeParameter::Kind::crossing:
      break;
  }
  const Exact gu = evaluate<Exact>(p.plane, u);
  const Exact gv = evaluate<Exact>(p.plane, v);
  return {gu, gu - gv};
}

struct Restriction {
  std::optional<ParameterRange> closed;  // {s : inside * g(E(s)) >= 0}
  std::optional<ParameterRange> open;    // {s : inside * g(E(s)) > 0}, by its bounds
};

// The parameters where inside * g is >= 0 (closed) and > 0 (open) along the edge: g is linear
// in s, so each is one range (or empty), bounded by 0, 1 or the crossing.
Restriction restrict_to(const EndValues& values, Sign inside, bool want_open) {
  Restriction r;
  if (values.certainly_inside(inside)) {
    r.closed = r.open = ParameterRange{start_parameter(), end_parameter()};
    return r;
  }
  if (values.certainly_outside(inside)) return r;
  const Sign a = inside * values.at_u(), b = inside * values.at_v();
  const auto whole = ParameterRange{start_parameter(), end_parameter()};
  // Closed: inside * g >= 0.
  if (a != Sign::negative && b != Sign::negative) {
    r.closed = whole;
  } else if (a != Sign::negative) {
    r.closed = ParameterRange{start_parameter(), values.crossing()};
  } else if (b != Sign::negative) {
    r.closed = ParameterRange{values.crossing(), end_parameter()};
  }
  if (!want_open) return r;
  // Open: inside * g > 0; its range is bounded by the same crossing (open there).
  if (a == Sign::positive && b == Sign::positive) {
    r.open = whole;
  } else if (a == Sign::positive) {
    r.open = ParameterRange{start_parameter(), values.crossing()};
  } else if (b == Sign::positive) {
    r.open = ParameterRange{values.crossing(), end_parameter()};
  }
  return r;
}

}  // namespace

EdgeVisibility::EdgeVisibility(const Vec3& u, const Vec3& v, const Vec3& eye) : u_(u), v_(v), eye_(eye) {
  if (u == v) throw std::invalid_argument("EdgeVisibility: the edge has no length");
}

Sign EdgeVisibility::compare(const EdgeParameter& a, const EdgeParameter& b) const {
  if (a.hi < b.lo) return Sign::negative;
  if (a.lo > b.hi) return Sign::positive;
  if (a.kind != EdgeParameter::Kind::crossing && b.kind != EdgeParameter::Kind::crossing) {
    return a.kind == b.kind ? Sign::zero : (a.kind == EdgeParameter::Kind::start ? Sign::negative : Sign::positive);
  }
  const auto [na, da] = exact_fraction(a, u_, v_);
  const auto [nb, db] = exact_fraction(b, u_, v_);
  return sign_of(na * db - nb * da) * sign_of(da) * sign_of(db);
}

namespace {

// [max(lo), min(hi)] of two ranges, empty when max > min.
std::optional<ParameterRange> intersect(const EdgeVisibility& edge, const std::optional<ParameterRange>& a,
                                        const std::optional<ParameterRange>& b) {
  if (!a || !b) return std::nullopt;
  ParameterRange r{edge.compare(a->lo, b->lo) == Sign::negative ? b->lo : a->lo,
                   edge.compare(a->hi, b->hi) == Sign::positive ? b->hi : a->hi};
  if (edge.compare(r.lo, r.hi) == Sign::positive) return std::nullopt;
  return r;
}

}  // namespace

void EdgeVisibility::occlude(const Vec3& a, const Vec3& b, const Vec3& c, Sign eye_side) {
  switch (eye_side) {
    case Sign::zero:
      return;  // seen edge-on (or no area): covers no area of the image
    case Sign::positive:
    case Sign::negative:
      break;
  }
  // V(T): inside * g >= 0 for T's plane (the side away from the eye, or on it) and for the
  // planes through the eye and each edge of T (the side of the third vertex): one sign for all
  // four, the opposite of the eye's side of T (docs/definitions.md#orientation's orient is
  // alternating: orient(e, a, b, c) = -orient(a, b, c, e)).
  const Sign inside = -eye_side;
  const std::array<PlaneFunction, 4> planes{PlaneFunction{b, a, c, a, a}, PlaneFunction{a, eye_, b, eye_, eye_},
                                            PlaneFunction{b, eye_, c, eye_, eye_},
                                            PlaneFunction{c, eye_, a, eye_, eye_}};
  const std::array<EndValues, 4> values{EndValues(planes[0], u_, v_), EndValues(planes[1], u_, v_),
                                        EndValues(planes[2], u_, v_), EndValues(planes[3], u_, v_)};
  for (const EndValues& value : values)
    if (value.certainly_outside(inside)) return;
  // The whole edge in T's plane: T hides none of it.
  if (values[0].at_u() == Sign::zero && values[0].at_v() == Sign::zero) return;
  std::optional<ParameterRange> hidden = restrict_to(values[0], inside, false).closed;
  for (std::size_t k = 1; k < values.size() && hidden; ++k)
    hidden = intersect(*this, hidden, restrict_to(values[k], inside, false).closed);
  if (hidden && compare(hidden->lo, hidden->hi) == Sign::negative) hidden_.push_back(*hidden);
}

std::vector<ParameterRange> EdgeVisibility::visible_pieces() const {
  std::vector<ParameterRange> hidden = hidden_;
  std::sort(hidden.begin(), hidden.end(),
            [this](const ParameterRange& x, const ParameterRange& y) { return compare(x.lo, y.lo) == Sign::negative; });
  std::vector<ParameterRange> pieces;
  EdgeParameter from = start_parameter();  // the visible part resumes here
  for (const ParameterRange& h : hidden) {
    if (compare(from, h.lo) == Sign::negative) pieces.push_back({from, h.lo});
    if (compare(h.hi, from) == Sign::positive) from = h.hi;
  }
  if (compare(from, end_parameter()) == Sign::negative) pieces.push_back({from, end_parameter()});
  return pieces;
}

ConeMeeting EdgeVisibility::meets_cone(const std::vector<ParameterRange>& pieces,
                                       const std::array<Vec3, 4>& corners) const {
  if (pieces.empty()) return ConeMeeting::none;
  std::optional<ParameterRange> closed = ParameterRange{start_parameter(), end_parameter()};
  std::optional<ParameterRange> open = closed;
  const Vec3 zero{};
  for (std::size_t k = 0; k < 4 && closed; ++k) {
    const Vec3& c0 = corners[k];
    const Vec3& c1 = corners[(k + 1) % 4];
    // The face through the eye and corner rays k, k + 1; the pyramid on the side of ray k + 2.
    const Sign inside = determinant_sign(c0, c1, corners[(k + 2) % 4]);
    if (inside == Sign::zero) throw std::logic_error("meets_cone: a pixel's corner rays span no pyramid");
    const PlaneFunction face{c0, zero, c1, zero, eye_};
    const Restriction r = restrict_to(EndValues(face, u_, v_), inside, true);
    closed = intersect(*this, closed, r.closed);
    open = open && r.open ? intersect(*this, open, r.open) : std::nullopt;
  }
  if (!closed) return ConeMeeting::none;
  bool touches = false;
  for (const ParameterRange& piece : pieces) {
    // A piece is open where an occluder bounds it, the open pyramid's range open at its
    // crossings: both relatively open in [0, 1], so they meet iff max(lo) < min(hi).
    if (open) {
      const EdgeParameter& lo = compare(piece.lo, open->lo) == Sign::negative ? open->lo : piece.lo;
      const EdgeParameter& hi = compare(piece.hi, open->hi) == Sign::positive ? open->hi : piece.hi;
      if (compare(lo, hi) == Sign::negative) return ConeMeeting::passes;
    }
    const EdgeParameter& lo = compare(piece.lo, closed->lo) == Sign::negative ? closed->lo : piece.lo;
    const EdgeParameter& hi = compare(piece.hi, closed->hi) == Sign::positive ? closed->hi : piece.hi;
    if (compare(lo, hi) != Sign::positive) touches = true;
  }
  return touches ? ConeMeeting::touches : ConeMeeting::none;
}

Vec3 EdgeVisibility::approximate_point(const EdgeParameter& p) const {
  const double s = p.lo / 2 + p.hi / 2;
  return {u_[0] + s * (v_[0] - u_[0]), u_[1] + s * (v_[1] - u_[1]), u_[2] + s * (v_[2] - u_[2])};
}

}  // namespace shadowcert::detail
