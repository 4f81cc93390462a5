// reference/detail/ray_hit.h's semi-static filters (issue 24): semi_static_hit_box must enclose
// the exact hit point and RayParameter's enclosure the exact parameter, on rays and triangles at
// every scale the campaign draws (1e-6 to 1e6, offsets of 1e6, nearly parallel rays, far
// triangles). Containment is checked exactly: HitPoint::side against the box's face planes.
#include "reference/detail/ray_hit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

#include "exact/light_orientation.h"
#include "exact/orient_unchecked.h"

namespace {

using namespace shadowcert;
using detail::HitPoint;
using detail::RayParameter;

struct Draw {
  PixelRay ray;
  std::array<Vec3, 3> triangle;
};

// A triangle of size `scale` around `centre`, and a ray from a point `distance` away towards a
// point on or near it; `grazing` tilts the ray almost into the triangle's plane.
Draw draw(std::mt19937_64& rng, double scale, double offset, double distance, bool grazing) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Draw d;
  const Vec3 centre{offset + unit(rng) * scale, offset + unit(rng) * scale, offset + unit(rng) * scale};
  for (Vec3& v : d.triangle) v = {centre[0] + unit(rng) * scale, centre[1] + unit(rng) * scale, centre[2] + unit(rng) * scale};
  const double wa = std::abs(unit(rng)), wb = std::abs(unit(rng)), wc = std::abs(unit(rng)), sum = wa + wb + wc;
  Vec3 target{};
  for (int k = 0; k < 3; ++k)
    target[k] = (wa * d.triangle[0][k] + wb * d.triangle[1][k] + wc * d.triangle[2][k]) / sum;
  Vec3 from_dir{unit(rng), unit(rng), unit(rng)};
  if (grazing) {
    // Along an edge direction, plus a tiny component: nearly in the plane.
    for (int k = 0; k < 3; ++k) from_dir[k] = d.triangle[1][k] - d.triangle[0][k] + 1e-9 * scale * unit(rng);
  }
  const double norm = std::sqrt(from_dir[0] * from_dir[0] + from_dir[1] * from_dir[1] + from_dir[2] * from_dir[2]);
  for (int k = 0; k < 3; ++k) d.ray.origin[k] = target[k] + from_dir[k] / norm * distance;
  for (int k = 0; k < 3; ++k) d.ray.direction[k] = target[k] - d.ray.origin[k];
  return d;
}

// The exact side of P of the plane x_k = value, seen as orient(a, b, c, P) with a, b, c spanning
// it: +1 or -1 by the coordinate's order, 0 on it.
Sign side_of_coordinate(const HitPoint& p, int k, double value) {
  Vec3 a{}, b{}, c{};
  a[k] = b[k] = c[k] = value;
  b[(k + 1) % 3] = 1.0;
  c[(k + 2) % 3] = 1.0;
  // det[b - a, c - a, P - a] = (P_k - value) for this cyclic choice of axes.
  return p.side(a, b, c);
}

// Two triangles on one ray, at a random scale: the second is the first moved along the ray by
// a tiny step (case i even) or a large one (odd).
std::array<Draw, 2> two_on_a_ray(std::mt19937_64& rng, int i) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double scale = std::pow(10.0, 6.0 * unit(rng));
  const Draw a = draw(rng, scale, 0.0, 4.0 * scale, false);
  Draw b = a;
  const double step = (i % 2 == 0 ? 1e-12 : 0.1) * unit(rng);
  for (Vec3& v : b.triangle)
    for (int k = 0; k < 3; ++k) v[k] += step * a.ray.direction[k];
  return {a, b};
}

TEST(SemiStaticHitBox, RandomRaysAtEveryScale_EncloseTheExactPoint) {
  std::mt19937_64 rng(24);
  int checked = 0, filtered = 0;
  for (double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6})
    for (double offset : {0.0, 1e6})
      for (double distance : {1.0, 1e3})
        for (bool grazing : {false, true})
          for (int i = 0; i < 100; ++i) {
            const Draw d = draw(rng, scale, offset, distance * scale, grazing);
            const detail::RayMeeting m = detail::ray_meets_triangle(d.ray, d.triangle[0], d.triangle[1], d.triangle[2]);
            if (m.direction_side == Sign::zero) continue;
            const RayParameter t(d.ray, d.triangle[0], d.triangle[1], d.triangle[2], m.direction_side);
            const HitPoint exact(t);
            ++checked;
            const std::optional<std::array<Vec3, 2>> box = detail::semi_static_hit_box(d.ray, d.triangle);
            // The parameter's own box (its semi-static stage, not run again) is the same box.
            std::array<Vec3, 2> own{};
            EXPECT_EQ(t.semi_static_hit_box(own), box.has_value()) << "scale " << scale;
            if (box) EXPECT_EQ(own, *box) << "scale " << scale;
            if (!box) continue;
            ++filtered;
            for (int k = 0; k < 3; ++k) {
              EXPECT_NE(side_of_coordinate(exact, k, (*box)[0][k]), Sign::negative) << "lo, axis " << k << ", scale " << scale;
              EXPECT_NE(side_of_coordinate(exact, k, (*box)[1][k]), Sign::positive) << "hi, axis " << k << ", scale " << scale;
            }
          }
  EXPECT_GT(checked, 3000);
  EXPECT_GT(filtered, checked / 2);  // the filter decides most cases (else it is no speed-up)
}

TEST(RayParameter, SemiStaticEnclosure_OrdersAsTheExactParameters) {
  // Two triangles on one ray: compare() (filter first, exact when the enclosures overlap) must
  // agree with the order of the exact hit points along the ray, read exactly through HitPoint.
  std::mt19937_64 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const auto [a, b] = two_on_a_ray(rng, i);
    const auto meet = [](const Draw& d) {
      return detail::ray_meets_triangle(d.ray, d.triangle[0], d.triangle[1], d.triangle[2]);
    };
    const detail::RayMeeting ma = meet(a), mb = meet(b);
    if (ma.direction_side == Sign::zero || mb.direction_side == Sign::zero) continue;
    const RayParameter ta(a.ray, a.triangle[0], a.triangle[1], a.triangle[2], ma.direction_side);
    const RayParameter tb(a.ray, b.triangle[0], b.triangle[1], b.triangle[2], mb.direction_side);
    const RayParameter ta_plain(a.ray, a.triangle[0], a.triangle[1], a.triangle[2], ma.direction_side,
                                RayParameter::Unenclosed{});
    std::array<Vec3, 2> unset{};
    EXPECT_FALSE(ta_plain.semi_static_hit_box(unset)) << "an unenclosed parameter ran no semi-static stage";
    const RayParameter tb_plain(a.ray, b.triangle[0], b.triangle[1], b.triangle[2], mb.direction_side,
                                RayParameter::Unenclosed{});
    // The unenclosed parameters always take the exact comparison: the reference order.
    EXPECT_EQ(ta.compare(tb), ta_plain.compare(tb_plain)) << "case " << i;
    EXPECT_EQ(tb.compare(ta), tb_plain.compare(ta_plain)) << "case " << i;
  }
}

// The estimates constructor (a tile's N and a ray's filtered D, each with a certified error):
// its enclosure holds the exact parameter (compare() against the unenclosed parameter, which
// always takes the exact path, is zero), its box encloses the exact point, and it orders
// against a second triangle as the plain constructor does. D's estimate here is the long
// double dot product of d with the normal, with an error bound far above its rounding; a
// bound too loose for the semi-static stage (every tenth case) falls back to the plain one.
TEST(RayParameter, EstimatesConstructor_EnclosesAndOrdersAsThePlainOne) {
  std::mt19937_64 rng(20261207);
  int semi_static = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto [a, b] = two_on_a_ray(rng, i);
    const detail::RayMeeting ma = detail::ray_meets_triangle(a.ray, a.triangle[0], a.triangle[1], a.triangle[2]);
    const detail::RayMeeting mb = detail::ray_meets_triangle(a.ray, b.triangle[0], b.triangle[1], b.triangle[2]);
    if (ma.direction_side == Sign::zero || mb.direction_side == Sign::zero) continue;
    const Vec3 &p = a.triangle[0], &q = a.triangle[1], &r = a.triangle[2];
    const detail::BoundedEstimate n = detail::plane_numerator_estimate(a.ray.origin, p, q, r);
    // D = d . ((q - p) x (r - p)), in long double (64 bits): within 2^-50 of its terms.
    long double dot = 0.0L, magnitude = 0.0L;
    for (int k = 0; k < 3; ++k) {
      const int j = (k + 1) % 3, l = (k + 2) % 3;
      const long double cross = static_cast<long double>(q[j] - p[j]) * (r[l] - p[l]) -
                                static_cast<long double>(q[l] - p[l]) * (r[j] - p[j]);
      const long double term = a.ray.direction[k] * cross;
      dot += term;
      magnitude += std::fabs(static_cast<long double>(a.ray.direction[k])) *
                   (std::fabs(static_cast<long double>(q[j] - p[j]) * (r[l] - p[l])) +
                    std::fabs(static_cast<long double>(q[l] - p[l]) * (r[j] - p[j])));
    }
    // The differences q - p, r - p are rounded too: a relative 2^-52 of each product.
    const double error = static_cast<double>(magnitude) * (i % 10 == 9 ? 0.5 : 0x1p-40);
    const detail::BoundedEstimate d{static_cast<double>(dot), error};
    const RayParameter estimated(a.ray, p, q, r, ma.direction_side, n, d);
    const RayParameter plain(a.ray, p, q, r, ma.direction_side);
    const RayParameter exact(a.ray, p, q, r, ma.direction_side, RayParameter::Unenclosed{});
    const RayParameter other(a.ray, b.triangle[0], b.triangle[1], b.triangle[2], mb.direction_side);
    EXPECT_EQ(estimated.compare(exact), Sign::zero) << "case " << i;
    EXPECT_EQ(estimated.compare(other), plain.compare(other)) << "case " << i;
    EXPECT_EQ(other.compare(estimated), other.compare(plain)) << "case " << i;
    std::array<Vec3, 2> box{};
    if (!estimated.semi_static_hit_box(box)) continue;
    ++semi_static;
    const HitPoint point(exact);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NE(side_of_coordinate(point, k, box[0][k]), Sign::negative) << "case " << i << " axis " << k;
      EXPECT_NE(side_of_coordinate(point, k, box[1][k]), Sign::positive) << "case " << i << " axis " << k;
    }
  }
  EXPECT_GT(semi_static, 1000);
}

// meeting_from_signs folds the five signs as ray_meets_triangle does: for random rays and
// triangles whose signs are all nonzero, the same meeting; with one sign unknown or the
// direction's zero, none.
TEST(RayMeeting, FromKnownSigns_AsRayMeetsTriangle) {
  std::mt19937_64 rng(5);
  int crossing = 0;
  for (int i = 0; i < 3000; ++i) {
    const Draw dr = draw(rng, 1.0, 0.0, 3.0, false);
    const PixelRay ray{dr.ray.origin, {dr.ray.direction[0] + 0.3 * (i % 3 - 1), dr.ray.direction[1], dr.ray.direction[2]}};
    const auto& t = dr.triangle;
    const HomogeneousPoint e = finite_point(ray.origin), dir{ray.direction[0], ray.direction[1], ray.direction[2], 0.0};
    detail::KnownRaySigns known;
    known.eye_side = detail::orient_unchecked(finite_point(t[0]), finite_point(t[1]), finite_point(t[2]), e);
    known.direction_side = detail::orient_unchecked(finite_point(t[0]), finite_point(t[1]), finite_point(t[2]), dir);
    for (int k = 0; k < 3; ++k)
      known.edges[static_cast<std::size_t>(k)] =
          detail::orient_unchecked(e, dir, finite_point(t[static_cast<std::size_t>(k)]), finite_point(t[static_cast<std::size_t>((k + 1) % 3)]));
    const detail::RayMeeting reference = detail::ray_meets_triangle(ray, t[0], t[1], t[2]);
    const std::optional<detail::RayMeeting> folded = detail::meeting_from_signs(known);
    if (*known.direction_side == Sign::zero) {
      EXPECT_FALSE(folded.has_value());
      continue;
    }
    ASSERT_TRUE(folded.has_value()) << "case " << i;
    EXPECT_EQ(folded->contact, reference.contact) << "case " << i;
    EXPECT_EQ(folded->eye_side, reference.eye_side) << "case " << i;
    EXPECT_EQ(folded->direction_side, reference.direction_side) << "case " << i;
    crossing += reference.contact == detail::RayContact::crosses ? 1 : 0;
    known.edges[1].reset();
    EXPECT_FALSE(detail::meeting_from_signs(known).has_value());
  }
  EXPECT_GT(crossing, 500);
}

// HitPoint's signs with a tight box (the semi-static and interval filters decide) equal the
// exact ones (a box so wide that every filter fails and P's exact coordinates decide), for
// planes and light wedges through points at and near P.
TEST(HitPoint, FilteredSigns_EqualExactSigns) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::array<Vec3, 2> wide{Vec3{-1e300, -1e300, -1e300}, Vec3{1e300, 1e300, 1e300}};
  int decided = 0;
  for (double scale : {1e-6, 1.0, 1e6})
    for (double offset : {0.0, 1e6})
      for (int i = 0; i < 150; ++i) {
        const Draw d = draw(rng, scale, offset, 3.0 * scale, false);
        const detail::RayMeeting m = detail::ray_meets_triangle(d.ray, d.triangle[0], d.triangle[1], d.triangle[2]);
        if (m.direction_side == Sign::zero) continue;
        const RayParameter t(d.ray, d.triangle[0], d.triangle[1], d.triangle[2], m.direction_side);
        const std::optional<std::array<Vec3, 2>> box = detail::semi_static_hit_box(d.ray, d.triangle);
        if (!box) continue;
        const HitPoint tight(t, *box);
        const HitPoint exact(t, wide);
        // Points near P: its box's middle moved by 0 to 1e-3 of the scale.
        const Vec3 mid{((*box)[0][0] + (*box)[1][0]) / 2, ((*box)[0][1] + (*box)[1][1]) / 2,
                       ((*box)[0][2] + (*box)[1][2]) / 2};
        const auto near = [&](double spread) {
          return Vec3{mid[0] + spread * scale * unit(rng), mid[1] + spread * scale * unit(rng),
                      mid[2] + spread * scale * unit(rng)};
        };
        for (double spread : {0.0, 1e-12, 1e-6, 1e-3, 1.0}) {
          const Vec3 a = near(spread), b = near(1.0), c = near(1.0);
          EXPECT_EQ(tight.side(a, b, c), exact.side(a, b, c)) << "scale " << scale << ", spread " << spread;
          const HomogeneousPoint point{b[0] + 2.0 * scale, b[1] + 3.0 * scale, b[2], 1.0};
          const HomogeneousPoint direction{unit(rng), 1.0, unit(rng), 0.0};
          EXPECT_EQ(tight.orient_with(point, a, c), exact.orient_with(point, a, c)) << "scale " << scale;
          EXPECT_EQ(tight.orient_with(direction, a, c), exact.orient_with(direction, a, c)) << "scale " << scale;
          ++decided;
        }
      }
  EXPECT_GT(decided, 2000);
}


// ray_meets_triangle with some of its signs given (as exact_image's per-tile filters give them)
// answers as it does computing them all, on rays across, along and through triangles, and on
// triangles without area.
TEST(RayMeetsTriangle, KnownSigns_GiveTheSameMeeting) {
  std::mt19937_64 rng(2412);
  std::uniform_int_distribution<int> coin(0, 1);
  int met = 0;
  for (double scale : {1e-3, 1.0, 1e3})
    for (int i = 0; i < 600; ++i) {
      Draw d = draw(rng, scale, 0.0, 3.0 * scale, i % 3 == 0);
      if (i % 7 == 0) d.triangle[2] = d.triangle[1];  // no area
      if (i % 11 == 0) d.ray.origin = d.triangle[0];  // from a vertex
      const auto& [a, b, c] = d.triangle;
      const HomogeneousPoint ha = finite_point(a), hb = finite_point(b), hc = finite_point(c);
      const HomogeneousPoint e = finite_point(d.ray.origin);
      const HomogeneousPoint dir{d.ray.direction[0], d.ray.direction[1], d.ray.direction[2], 0.0};
      detail::KnownRaySigns known;
      if (coin(rng) != 0) known.eye_side = detail::orient_unchecked(ha, hb, hc, e);
      if (coin(rng) != 0) known.direction_side = detail::orient_unchecked(ha, hb, hc, dir);
      const std::array<std::pair<HomogeneousPoint, HomogeneousPoint>, 3> edges{{{ha, hb}, {hb, hc}, {hc, ha}}};
      for (std::size_t k = 0; k < 3; ++k)
        if (coin(rng) != 0) known.edges[k] = detail::orient_unchecked(e, dir, edges[k].first, edges[k].second);
      const detail::RayMeeting all = detail::ray_meets_triangle(d.ray, a, b, c);
      const detail::RayMeeting given = detail::ray_meets_triangle(d.ray, a, b, c, known);
      EXPECT_EQ(given.contact, all.contact) << "scale " << scale << " draw " << i;
      EXPECT_EQ(given.eye_side, all.eye_side) << "scale " << scale << " draw " << i;
      EXPECT_EQ(given.direction_side, all.direction_side) << "scale " << scale << " draw " << i;
      met += all.contact != detail::RayContact::apart;
    }
  EXPECT_GT(met, 500);  // the draws aim at the triangles: most rays meet them
}

}  // namespace
