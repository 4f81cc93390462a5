#include "exact/light_orientation.h"

#include "core/vector3.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "exact/light_orientation_filter.h"
#include "exact/orient_unchecked.h"

namespace shadowcert {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Sign from_cgal(CGAL::Sign s) {
  switch (s) {
    case CGAL::NEGATIVE:
      return Sign::negative;
    case CGAL::ZERO:
      return Sign::zero;
    case CGAL::POSITIVE:
      return Sign::positive;
  }
  throw std::logic_error("from_cgal: not a sign");
}

// Rows b - a, c - a, d of det[b - a, c - a, d] built in NT from the raw doubles, so that no
// difference is rounded in double before the sign is taken (docs/definitions.md#orientation).
template <typename NT>
NT direction_determinant(const Vec3& a, const Vec3& b, const Vec3& c, const std::array<double, 4>& d) {
  std::array<NT, 3> x, y, z;
  for (int k = 0; k < 3; ++k) {
    x[k] = NT(b[k]) - NT(a[k]);
    y[k] = NT(c[k]) - NT(a[k]);
    z[k] = NT(d[k]);
  }
  return det3(x, y, z);  // core/vector3.h: CGAL::determinant's order
}

// sign det[b - a, c - a, d] for a direction d = (d, 0): semi-static filter, then intervals
// under one rounding-mode switch, then Mpzf (exact for sums and products of doubles).
Sign directional_orientation(const Vec3& a, const Vec3& b, const Vec3& c, const std::array<double, 4>& d) {
  if (const std::optional<Sign> quick = detail::semi_static_light_orientation(a, b, c, d)) return *quick;
  {
    CGAL::Protect_FPU_rounding<true> protect;
    const CGAL::Uncertain<CGAL::Sign> s = CGAL::sign(direction_determinant<CGAL::Interval_nt<false>>(a, b, c, d));
    if (CGAL::is_certain(s)) return from_cgal(CGAL::get_certain(s));
  }
  return from_cgal(CGAL::sign(direction_determinant<CGAL::Mpzf>(a, b, c, d)));
}

// Four finite points: CGAL's filtered orientation (static filter, intervals, exact), which is
// sign det[q - p, r - p, s - p], the convention of docs/definitions.md#orientation.
Sign finite_orientation(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  const Kernel::Point_3 pp(p[0], p[1], p[2]), qq(q[0], q[1], q[2]), rr(r[0], r[1], r[2]), ss(s[0], s[1], s[2]);
  return from_cgal(CGAL::orientation(pp, qq, rr, ss));
}

Vec3 xyz(const HomogeneousPoint& p) { return {p[0], p[1], p[2]}; }

bool finite_coordinates(const std::array<double, 4>& p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) && std::isfinite(p[3]);
}

void require_homogeneous(const HomogeneousPoint& p, int position) {
  if (!finite_coordinates(p) || (p[3] != 0.0 && p[3] != 1.0))
    throw std::invalid_argument("orient: argument " + std::to_string(position) +
                                " must have finite coordinates and w = 0 or w = 1");
  if (p[3] == 0.0 && p[0] == 0.0 && p[1] == 0.0 && p[2] == 0.0)
    throw std::invalid_argument("orient: argument " + std::to_string(position) +
                                " is (0, 0, 0, 0), which is no point");
}

}  // namespace

Sign orient(const HomogeneousPoint& p, const HomogeneousPoint& q, const HomogeneousPoint& r,
            const HomogeneousPoint& s) {
  require_homogeneous(p, 1);
  require_homogeneous(q, 2);
  require_homogeneous(r, 3);
  require_homogeneous(s, 4);
  const int infinite = (p[3] == 0.0) + (q[3] == 0.0) + (r[3] == 0.0) + (s[3] == 0.0);
  if (infinite > 1) throw std::invalid_argument("orient: at most one argument may be a point at infinity (w = 0)");
  return detail::orient_unchecked(p, q, r, s);
}

namespace detail {

Sign orient_unchecked(const HomogeneousPoint& p, const HomogeneousPoint& q, const HomogeneousPoint& r,
                      const HomogeneousPoint& s) {
  if (p[3] != 0.0 && q[3] != 0.0 && r[3] != 0.0 && s[3] != 0.0)
    return finite_orientation(xyz(p), xyz(q), xyz(r), xyz(s));
  // orient is alternating (a determinant): move the point at infinity last by one
  // transposition, which flips the sign. With s = (d, 0), subtracting p from q and r gives
  // orient = sign det[q - p, r - p, d] (docs/definitions.md#orientation, the same reduction as for a light).
  if (s[3] == 0.0) return directional_orientation(xyz(p), xyz(q), xyz(r), s);
  if (r[3] == 0.0) return -directional_orientation(xyz(p), xyz(q), xyz(s), r);
  if (q[3] == 0.0) return -directional_orientation(xyz(p), xyz(s), xyz(r), q);
  return -directional_orientation(xyz(s), xyz(q), xyz(r), p);
}

}  // namespace detail

Sign light_orientation(const Vec3& a, const Vec3& b, const Vec3& c, const Light& light) {
  const std::array<double, 4>& l = light.position;
  require_defined(light, "light_orientation");
  if (l[3] == 0.0) return directional_orientation(a, b, c, l);
  return finite_orientation(a, b, c, {l[0], l[1], l[2]});
}

}  // namespace shadowcert
