#include "exact/count_sampling.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace shadowcert::detail {
namespace {

constexpr double kEnlargement = 0.1;  // per side, of the largest extent (count_certificate.h)

// Spreads the low 21 bits of x to every third bit of a 64-bit word.
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffffULL;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

// Cell of coordinate x in [lo, hi] on a 2^21 grid (clamped; only the order matters).
std::uint64_t grid_cell(double x, double lo, double hi) {
  constexpr double kCells = 2097152.0;  // 2^21
  if (!(hi > lo)) return 0;
  const double t = (x - lo) / (hi - lo) * kCells;
  if (!(t > 0.0)) return 0;
  return t >= kCells - 1.0 ? (1u << 21) - 1 : static_cast<std::uint64_t>(t);
}

std::uint64_t morton_code(const Vec3& p, const Box& box) {
  return spread_bits(grid_cell(p[0], box.lo[0], box.hi[0])) |
         spread_bits(grid_cell(p[1], box.lo[1], box.hi[1])) << 1 |
         spread_bits(grid_cell(p[2], box.lo[2], box.hi[2])) << 2;
}

// One ulp of the point's largest coordinate, the grain of doubles at the point's scale.
double coordinate_grain(const Vec3& p) {
  const double m = std::max({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])});
  if (m == 0.0) return std::numeric_limits<double>::min();
  return std::nextafter(m, std::numeric_limits<double>::infinity()) - m;
}

}  // namespace

Box sampling_box(const Soup& soup) {
  Box box = used_vertex_box(soup);
  double extent = 0.0;
  for (int i = 0; i < 3; ++i) extent = std::max(extent, box.hi[i] - box.lo[i]);
  const double margin = extent > 0.0 ? kEnlargement * extent : 1.0;
  for (int i = 0; i < 3; ++i) {
    box.lo[i] -= margin;
    box.hi[i] += margin;
  }
  return box;
}

Vec3 draw_in_box(const Box& box, std::mt19937_64& rng) {
  Vec3 p{};
  for (int i = 0; i < 3; ++i) {
    std::uniform_real_distribution<double> coordinate(box.lo[i], box.hi[i]);
    p[i] = std::clamp(coordinate(rng), box.lo[i], box.hi[i]);
  }
  return p;
}

Vec3 draw_near_triangle(const Soup& soup, std::mt19937_64& rng) {
  std::uniform_int_distribution<std::size_t> which(0, soup.triangles.size() - 1);
  const Triangle& t = soup.triangles[which(rng)];
  const Vec3 &a = soup.vertices[t[0]], &b = soup.vertices[t[1]], &c = soup.vertices[t[2]];
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double r = unit(rng), s = unit(rng);
  if (r + s > 1.0) {  // fold the unit square onto the triangle: uniform barycentrics
    r = 1.0 - r;
    s = 1.0 - s;
  }
  Vec3 p{};
  for (int i = 0; i < 3; ++i) p[i] = a[i] + r * (b[i] - a[i]) + s * (c[i] - a[i]);
  const double grain = coordinate_grain(p);
  std::bernoulli_distribution up(0.5);
  for (int i = 0; i < 3; ++i) p[i] += up(rng) ? grain : -grain;
  return p;
}

std::mt19937_64 sample_stream(std::uint64_t seed, std::uint64_t kind, std::uint64_t index) {
  std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                         static_cast<std::uint32_t>(kind), static_cast<std::uint32_t>(index),
                         static_cast<std::uint32_t>(index >> 32)};
  return std::mt19937_64(sequence);
}

std::vector<std::uint32_t> morton_order(const std::vector<Vec3>& points, const Box& box) {
  if (points.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("morton_order: more than 2^32 points");
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) keyed[i] = {morton_code(points[i], box), i};
  tbb::parallel_sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(points.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace shadowcert::detail
