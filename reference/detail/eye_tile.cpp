// eye_tile_cone of reference/detail/eye_tile.h. Every bound below is formed in round-to-nearest
// doubles and then widened by a relative 2^-40 (far more than the few roundings of each
// expression) and, for the slacks, an absolute 2^-1000 (underflow); u = 2^-53.
#include "reference/detail/eye_tile.h"

#include <algorithm>
#include <cmath>

namespace shadowcert::detail {
namespace {

constexpr double kWiden = 1.0 + 0x1p-40;
// Image plane points beyond this many units of the axis (a field of view within about 0.1
// degree of 180) are left to per-ray queries: the bounds below assume |a|, |b| small against 2^50.
constexpr double kPlaneLimit = 0x1p10;
// Coordinates beyond this are left to per-ray queries: no product below overflows.
constexpr double kMagnitudeLimit = 0x1p400;

// pixel_ray's a and b (core/pixel_ray.h), the same operations in the same order: each is a
// monotone function of x (of y), which is what bounds a tile's rays by its corners' values.
double plane_a(const CameraFrame& frame, double x) { return (2.0 * x / frame.width - 1.0) * frame.half_width; }
double plane_b(const CameraFrame& frame, double y) { return (1.0 - 2.0 * y / frame.height) * frame.half_height; }

bool tame(const Vec3& v) {
  return std::all_of(v.begin(), v.end(), [](double c) { return std::isfinite(c) && std::fabs(c) <= kMagnitudeLimit; });
}

}  // namespace

std::optional<EyeTileCone> eye_tile_cone(const CameraFrame& frame, double x0, double x1, double y0, double y1,
                                         const Vec3& lo, const Vec3& hi) {
  if (!(x0 <= x1 && y0 <= y1) || frame.width == 0 || frame.height == 0) return std::nullopt;
  const Vec3 &e = frame.eye, &f = frame.forward, &r = frame.right, &u = frame.up;
  if (!tame(e) || !tame(f) || !tame(r) || !tame(u) || !tame(lo) || !tame(hi)) return std::nullopt;
  // a over the tile lies in [a0, a1], b in [b0, b1] (monotone roundings, y grows downwards).
  const double a0 = plane_a(frame, x0), a1 = plane_a(frame, x1);
  const double b0 = plane_b(frame, y1), b1 = plane_b(frame, y0);
  const double amax = std::max(std::fabs(a0), std::fabs(a1)), bmax = std::max(std::fabs(b0), std::fabs(b1));
  if (!(amax <= kPlaneLimit && bmax <= kPlaneLimit && a0 <= a1 && b0 <= b1)) return std::nullopt;
  // The middle direction c and each tile ray's distance from it: |a - ac| <= sa (the halved
  // width plus ac's rounding), likewise b; each direction's own rounding (three roundings of
  // f + a r + b u, to first order 3u M) and c's are within 2^-51 M each.
  const double ac = 0.5 * (a0 + a1), bc = 0.5 * (b0 + b1);
  const double sa = 0.5 * (a1 - a0) * kWiden + 0x1p-50 * amax;
  const double sb = 0.5 * (b1 - b0) * kWiden + 0x1p-50 * bmax;
  Vec3 c{}, s{}, m{};
  for (int k = 0; k < 3; ++k) {
    m[k] = std::fabs(f[k]) + amax * std::fabs(r[k]) + bmax * std::fabs(u[k]);
    c[k] = f[k] + ac * r[k] + bc * u[k];
    s[k] = (sa * std::fabs(r[k]) + sb * std::fabs(u[k]) + 0x1p-49 * m[k]) * kWiden;
  }
  // |d| >= d.f / |f| for every direction d of the tile (and every convex combination of them):
  // d.f = f.f + a r.f + b u.f + (rounding of d).f, each dot product within 2^-50 of its terms'
  // magnitudes.
  double ff = 0.0, rf = 0.0, uf = 0.0, rf_abs = 0.0, uf_abs = 0.0, mf = 0.0, m_sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    ff += f[k] * f[k];
    rf += r[k] * f[k];
    uf += u[k] * f[k];
    rf_abs += std::fabs(r[k] * f[k]);
    uf_abs += std::fabs(u[k] * f[k]);
    mf += m[k] * std::fabs(f[k]);
    m_sum += m[k];
  }
  const double lower = (ff * (1.0 - 0x1p-50) - amax * (std::fabs(rf) + 0x1p-50 * rf_abs) -
                        bmax * (std::fabs(uf) + 0x1p-50 * uf_abs) - 0x1p-50 * mf) /
                       kWiden;
  if (!(lower > 0.25 * ff)) return std::nullopt;
  const double d_min = lower / (std::sqrt(ff) * kWiden) / kWiden;
  const double d_max = m_sum * kWiden * kWiden;  // |d| <= |d|_1 <= sum (1 + 2^-51) m
  // A met point p of the box: t |d| = |p - e|, between e's distance to the box and its
  // distance to the farthest corner.
  double far2 = 0.0, near2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double span = std::max(std::fabs(lo[k] - e[k]), std::fabs(hi[k] - e[k]));
    far2 += span * span;
    const double gap = std::max({lo[k] - e[k], e[k] - hi[k], 0.0});
    near2 += gap * gap;
  }
  const double t_far = std::sqrt(far2) * kWiden / d_min * kWiden;
  const double t_near = std::sqrt(near2) / kWiden / d_max / kWiden;
  if (!std::isfinite(t_far)) return std::nullopt;

  EyeTileCone cone;
  const auto cut = [&](std::size_t j) {
    if (j == 0) return t_near;
    if (j == kEyeTilePieces) return t_far;
    return t_near + (t_far - t_near) * (static_cast<double>(j) / kEyeTilePieces);
  };
  for (std::size_t j = 0; j < kEyeTilePieces; ++j) {
    const double t0 = cut(j), t1 = std::max(t0, cut(j + 1));
    DilatedSegment& piece = cone[j];
    for (int k = 0; k < 3; ++k) {
      piece.from[k] = e[k] + t0 * c[k];
      piece.to[k] = e[k] + t1 * c[k];
      // Between t0 and t1 a ray point lies within t s of e + t c, which lies on the exact
      // segment between the end points; each end point's two roundings err by 2u of its terms.
      piece.slack[k] = (t1 * s[k] + 0x1p-50 * (std::fabs(e[k]) + t1 * std::fabs(c[k]))) * kWiden + 0x1p-1000;
    }
  }
  return cone;
}

Vec3 eye_tile_direction_bound(const CameraFrame& frame, double x0, double x1, double y0, double y1) {
  // |d_k| <= |f_k| + |a| |r_k| + |b| |u_k| plus its three roundings (3u of that sum).
  const double amax = std::max(std::fabs(plane_a(frame, x0)), std::fabs(plane_a(frame, x1)));
  const double bmax = std::max(std::fabs(plane_b(frame, y0)), std::fabs(plane_b(frame, y1)));
  Vec3 w{};
  for (int k = 0; k < 3; ++k)
    w[k] = (std::fabs(frame.forward[k]) + amax * std::fabs(frame.right[k]) + bmax * std::fabs(frame.up[k])) * kWiden;
  return w;
}

}  // namespace shadowcert::detail
