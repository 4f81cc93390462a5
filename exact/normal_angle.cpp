#include "exact/normal_angle.h"

#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/portable_math.h"
#include "core/vector3.h"

namespace shadowcert {
namespace {

using Interval = CGAL::Interval_nt<false>;  // only under a Protect_FPU_rounding
using Exact = CGAL::Mpzf;                   // exact for sums and products of doubles

template <typename NT>
Vector3<NT> difference_of(const Vec3& p, const Vec3& q) {
  return {NT(p[0]) - NT(q[0]), NT(p[1]) - NT(q[1]), NT(p[2]) - NT(q[2])};
}

template <typename NT>
Vector3<NT> lifted(const Vec3& p) {
  return {NT(p[0]), NT(p[1]), NT(p[2])};
}

// The two vectors whose angle is compared, and whether to take |n1 . n2| (an angle between
// lines, in [0, 90]) rather than n1 . n2 (between vectors, in [0, 180]).
template <typename NT>
struct AnglePair {
  Vector3<NT> n1;
  Vector3<NT> n2;
};

std::optional<Sign> certain_sign(const Interval& x) {
  if (x.inf() > 0.0) return Sign::positive;
  if (x.sup() < 0.0) return Sign::negative;
  if (x.inf() == 0.0 && x.sup() == 0.0) return Sign::zero;
  return std::nullopt;
}

Sign exact_sign(const Exact& x) { return sign_of(x); }

// sign(angle - theta) = sign(c sqrt(q) - d), q > 0: by the signs of c and d, then by
// c^2 q against d^2 (both sides of one sign). nullopt where intervals cannot tell.
std::optional<Sign> decide(const Interval& d, const Interval& q, double c) {
  const std::optional<Sign> sd = certain_sign(d);
  if (!sd) return std::nullopt;
  if (c == 0.0) return -*sd;
  if (c > 0.0 && *sd != Sign::positive) return Sign::positive;  // c sqrt(q) > 0 >= d
  if (c < 0.0 && *sd != Sign::negative) return Sign::negative;  // c sqrt(q) < 0 <= d
  const Interval cc = Interval(c) * Interval(c) * q;
  const Interval dd = d * d;
  const std::optional<Sign> s = certain_sign(cc - dd);  // sign(c^2 q - d^2)
  if (!s) return std::nullopt;
  return c > 0.0 ? *s : -*s;  // c < 0, d < 0: c sqrt(q) - d = |d| - |c| sqrt(q)
}

Sign decide(const Exact& d, const Exact& q, double c) {
  const Sign sd = exact_sign(d);
  if (c == 0.0) return -sd;
  if (c > 0.0 && sd != Sign::positive) return Sign::positive;
  if (c < 0.0 && sd != Sign::negative) return Sign::negative;
  const Sign s = exact_sign(Exact(c) * Exact(c) * q - d * d);
  return c > 0.0 ? s : -s;
}

void require_cosine(double cosine, const char* function) {
  if (!(cosine >= -1.0 && cosine <= 1.0))
    throw std::invalid_argument(std::string(function) + ": the cosine must lie in [-1, 1]");
}

// sign(angle(n1, n2) - acos(cosine)); `lines`: the angle between the lines (|n1 . n2|).
template <typename Make>
Sign angle_sign(Make make, double cosine, bool lines, const char* function) {
  require_cosine(cosine, function);
  {
    const CGAL::Protect_FPU_rounding<true> protect;
    const AnglePair<Interval> p = make(Interval(0.0));
    Interval d = dot(p.n1, p.n2);
    if (lines) d = CGAL::abs(d);
    const Interval q = dot(p.n1, p.n1) * dot(p.n2, p.n2);
    if (q.inf() > 0.0)
      if (const std::optional<Sign> s = decide(d, q, cosine)) return *s;
  }
  const AnglePair<Exact> p = make(Exact(0));
  Exact d = dot(p.n1, p.n2);
  if (lines && exact_sign(d) == Sign::negative) d = -d;
  const Exact q = dot(p.n1, p.n1) * dot(p.n2, p.n2);
  if (exact_sign(q) == Sign::zero) throw std::invalid_argument(std::string(function) + ": a zero vector has no angle");
  return decide(d, q, cosine);
}

}  // namespace

double angle_cosine(double degrees) {
  if (!(degrees >= 0.0 && degrees <= 180.0))
    throw std::invalid_argument("angle_cosine: the angle must lie in [0, 180] degrees");
  if (degrees == 0.0) return 1.0;
  if (degrees == 60.0) return 0.5;
  if (degrees == 90.0) return 0.0;
  if (degrees == 120.0) return -0.5;
  if (degrees == 180.0) return -1.0;
  constexpr double kPi = 3.14159265358979323846;
  return portable::cos(degrees * (kPi / 180.0));
}

Sign bend_angle_sign(const Vec3& u, const Vec3& v, const Vec3& o1, const Vec3& o2, double cosine) {
  return angle_sign(
      [&]<typename NT>(NT) {
        const Vector3<NT> edge = difference_of<NT>(v, u);
        return AnglePair<NT>{cross(edge, difference_of<NT>(o1, u)), cross(difference_of<NT>(o2, u), edge)};
      },
      cosine, false, "bend_angle_sign");
}

Sign incidence_angle_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double cosine) {
  return angle_sign(
      [&]<typename NT>(NT) {
        return AnglePair<NT>{cross(difference_of<NT>(b, a), difference_of<NT>(c, a)), lifted<NT>(d)};
      },
      cosine, true, "incidence_angle_sign");
}

}  // namespace shadowcert
