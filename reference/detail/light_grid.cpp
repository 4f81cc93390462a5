// LightGrid of reference/detail/light_grid.h: the projection, its enclosures and the cells.
#include "reference/detail/light_grid.h"

#include "core/outward_float.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace shadowcert::detail {
namespace {

// A projected coordinate (n - ln) / (d - ld), computed as (n - ln) * r with r = 1 / (d - ld)
// rounded (one division per point, shared by its two coordinates), and an interval around it
// that holds its exact value: four roundings of relative 2^-53 each keep the product within
// 2^-50 relative of it (2^-1074 absolute where it underflows; a difference that is subnormal is
// exact). The interval is 2^-48 relative plus 2^-1000 wide on each side, which also absorbs the
// rounding of its own end points. A non-finite r or product gives a non-finite interval, which
// the callers refuse.
struct Enclosure {
  double lo, hi;
};
Enclosure enclosure(double q) {
  const double slack = std::fabs(q) * 0x1p-48 + 0x1p-1000;
  return {q - slack, q + slack};
}

// The largest depth d - ld taken: beyond it 1 / (d - ld) could be subnormal (rounded by more
// than 2^-53 relative) or, where the difference overflows, zero.
inline constexpr double kMostDepth = 0x1p1000;

// The cells per listed triangle: ogre's 124K triangles over a floor, 1024x768, gave the
// shortest count stage near one cell per triangle (docs/diff.md, "The light grid").
inline constexpr double kCellsPerTriangle = 1.0;
// The most cells along one side (a scene whose projection is a thin strip).
inline constexpr std::uint32_t kMostCellsPerSide = 4096;

}  // namespace

std::uint32_t LightGrid::column(double u) const {
  // (u - u0) * scale rounds monotonically in u, and so does the clamped truncation: a larger u
  // never gets a smaller column (the reason two meeting intervals share a cell).
  const double f = (u - u0_) * u_scale_;
  if (!(f > 0.0)) return 0;
  if (f >= static_cast<double>(columns_)) return columns_ - 1;
  return static_cast<std::uint32_t>(f);
}

std::uint32_t LightGrid::row(double v) const {
  const double f = (v - v0_) * v_scale_;
  if (!(f > 0.0)) return 0;
  if (f >= static_cast<double>(rows_)) return rows_ - 1;
  return static_cast<std::uint32_t>(f);
}

std::optional<LightGrid::Reach> LightGrid::reach(const Vec3& lo, const Vec3& hi) const {
  const auto a = static_cast<std::size_t>(axis_), b = static_cast<std::size_t>(b_), c = static_cast<std::size_t>(c_);
  if (side_ < 0 ? !(hi[a] < light_[a]) : !(lo[a] > light_[a])) return std::nullopt;
  // Over the box, u's extremes lie at the corners of its (b, a) face, v's at those of (c, a).
  double ulo = std::numeric_limits<double>::infinity(), uhi = -ulo, vlo = ulo, vhi = -ulo;
  for (const double d : {lo[a], hi[a]}) {
    const double depth = d - light_[a];
    if (!(std::fabs(depth) <= kMostDepth)) return std::nullopt;
    const double r = 1.0 / depth;
    for (const double n : {lo[b], hi[b]}) {
      const Enclosure e = enclosure((n - light_[b]) * r);
      ulo = std::min(ulo, e.lo);
      uhi = std::max(uhi, e.hi);
    }
    for (const double n : {lo[c], hi[c]}) {
      const Enclosure e = enclosure((n - light_[c]) * r);
      vlo = std::min(vlo, e.lo);
      vhi = std::max(vhi, e.hi);
    }
  }
  if (!(std::isfinite(ulo) && std::isfinite(uhi) && std::isfinite(vlo) && std::isfinite(vhi))) return std::nullopt;
  // A triangle can hold a point strictly nearer to L than P (as a point of the open segment
  // P -> L is) only if its nearest coordinate is: key > P's, for some P of the box.
  const double threshold = side_ < 0 ? lo[a] : -hi[a];
  return Reach{column(ulo), column(uhi), row(vlo), row(vhi), threshold};
}

std::optional<LightGrid> LightGrid::build(const Soup& soup, const Vec3& light, const Box& scene,
                                          std::span<const std::uint8_t> listed) {
  if (listed.size() != soup.triangles.size())
    throw std::invalid_argument("LightGrid::build: `listed` has " + std::to_string(listed.size()) +
                                " entries for " + std::to_string(soup.triangles.size()) + " triangles");
  LightGrid grid;
  grid.light_ = light;
  // The axis with the scene strictly on one side of the light and the widest gap beside the
  // scene's extent across it (the flattest projection).
  double best = -1.0;
  for (int a = 0; a < 3; ++a) {
    const auto i = static_cast<std::size_t>(a);
    const double gap = scene.hi[i] < light[i] ? light[i] - scene.hi[i] : scene.lo[i] > light[i] ? scene.lo[i] - light[i] : -1.0;
    if (!(gap > 0.0)) continue;
    double across = 0.0;
    for (std::size_t k = 0; k < 3; ++k)
      if (k != i) across = std::max(across, scene.hi[k] - scene.lo[k]);
    const double score = across > 0.0 ? gap / across : std::numeric_limits<double>::infinity();
    if (score > best) {
      best = score;
      grid.axis_ = a;
      grid.side_ = scene.hi[i] < light[i] ? -1 : 1;
    }
  }
  if (best < 0.0) return std::nullopt;
  grid.b_ = (grid.axis_ + 1) % 3;
  grid.c_ = (grid.axis_ + 2) % 3;
  const auto a = static_cast<std::size_t>(grid.axis_), b = static_cast<std::size_t>(grid.b_),
             c = static_cast<std::size_t>(grid.c_);

  // Every vertex's projection, computed once for the triangles around it (each vertex lies in
  // `scene`, so at a depth of the scene's sign).
  struct Projection {
    double u, v;
  };
  std::vector<Projection> at(soup.vertices.size());
  std::atomic<bool> finite{true};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, at.size(), 8192), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const Vec3& p = soup.vertices[k];
      const double depth = p[a] - light[a];
      const double reciprocal = 1.0 / depth;
      at[k] = {(p[b] - light[b]) * reciprocal, (p[c] - light[c]) * reciprocal};
      if (!(std::fabs(depth) <= kMostDepth && std::isfinite(at[k].u) && std::isfinite(at[k].v)))
        finite.store(false, std::memory_order_relaxed);
    }
  });
  if (!finite.load()) return std::nullopt;

  // A triangle's projection lies in the box of its vertices' enclosures.
  struct Rect {
    double ulo = std::numeric_limits<double>::infinity(), uhi = -ulo, vlo = ulo, vhi = -ulo;
    void join(const Rect& o) {
      ulo = std::min(ulo, o.ulo);
      uhi = std::max(uhi, o.uhi);
      vlo = std::min(vlo, o.vlo);
      vhi = std::max(vhi, o.vhi);
    }
  };
  const auto rect_of = [&](std::size_t t) {
    Rect r;
    for (const std::uint32_t v : soup.triangles[t]) {
      const Enclosure u = enclosure(at[v].u), w = enclosure(at[v].v);
      r.join({u.lo, u.hi, w.lo, w.hi});
    }
    return r;
  };
  const auto cell_rect = [&](const Rect& r) {
    return Reach{grid.column(r.ulo), grid.column(r.uhi), grid.row(r.vlo), grid.row(r.vhi), 0.0};
  };
  const auto wide = [&](const Reach& r) { return 2 * r.cells() > grid.cells(); };
  // Its key: its nearest coordinate along the axis (negated above the light), rounded up.
  const auto key_of = [&](std::size_t t) -> float {
    const Triangle& tri = soup.triangles[t];
    const double x = soup.vertices[tri[0]][a], y = soup.vertices[tri[1]][a], z = soup.vertices[tri[2]][a];
    return round_up_to_float(grid.side_ < 0 ? std::max({x, y, z}) : -std::min({x, y, z}));
  };
  const std::size_t triangles = soup.triangles.size();
  const auto listed_count = static_cast<std::size_t>(std::count_if(listed.begin(), listed.end(), [](std::uint8_t x) { return x != 0; }));
  if (listed_count == 0) {
    grid.first_.assign(2, 0);
    return grid;
  }
  // The listed triangles, in order, and each one's projection box, computed once for the
  // passes below (every one of them reads it).
  std::vector<std::uint32_t> order;
  order.reserve(listed_count);
  for (std::size_t t = 0; t < triangles; ++t)
    if (listed[t] != 0) order.push_back(static_cast<std::uint32_t>(t));
  std::vector<Rect> rects(order.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 8192), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) rects[k] = rect_of(order[k]);
  });
  // The box of the listed triangles' projections (`only_narrow`: of those that the grid as it
  // stands finds not wide).
  const auto domain = [&](bool only_narrow) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, rects.size(), 8192), std::pair<Rect, std::size_t>{},
        [&](const auto& r, std::pair<Rect, std::size_t> acc) {
          for (std::size_t k = r.begin(); k != r.end(); ++k) {
            if (only_narrow && wide(cell_rect(rects[k]))) continue;
            acc.first.join(rects[k]);
            ++acc.second;
          }
          return acc;
        },
        [](std::pair<Rect, std::size_t> x, const std::pair<Rect, std::size_t>& y) {
          x.first.join(y.first);
          x.second += y.second;
          return x;
        });
  };
  // The cells: about kCellsPerTriangle per listed triangle over `box`, in its proportions.
  const auto lay_out = [&](const Rect& box, std::size_t narrow) {
    const double du = box.uhi - box.ulo, dv = box.vhi - box.vlo;
    const double target = std::max(1.0, kCellsPerTriangle * static_cast<double>(narrow));
    const auto side_cells = [](double cells) {
      return static_cast<std::uint32_t>(std::clamp(std::round(cells), 1.0, static_cast<double>(kMostCellsPerSide)));
    };
    if (du > 0.0 && dv > 0.0 && std::isfinite(du / dv)) {
      grid.columns_ = side_cells(std::sqrt(target * du / dv));
      grid.rows_ = side_cells(target / grid.columns_);
    } else {
      grid.columns_ = du > 0.0 ? side_cells(target) : 1;
      grid.rows_ = dv > 0.0 && du == 0.0 ? side_cells(target) : 1;
    }
    grid.u0_ = box.ulo;
    grid.v0_ = box.vlo;
    grid.u_scale_ = du > 0.0 && std::isfinite(grid.columns_ / du) ? grid.columns_ / du : 0.0;
    grid.v_scale_ = dv > 0.0 && std::isfinite(grid.rows_ / dv) ? grid.rows_ / dv : 0.0;
  };
  // A few wide triangles (a floor under a mesh) would stretch the box far beyond the rest: it
  // is drawn twice, the second time without the triangles the first grid finds wide.
  lay_out(domain(false).first, listed_count);
  if (const auto [box, narrow] = domain(true); narrow > 0) lay_out(box, narrow);

  // A counting sort of the listed triangles into their cells, in contiguous chunks of them
  // (one per thread, each with its own counts): each cell's list comes in triangle order. The
  // wide triangles go to big_ apart.
  grid.keys_.resize(triangles);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 8192), [&](const auto& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) grid.keys_[order[k]] = key_of(order[k]);
  });
  const std::size_t cells = grid.cells();
  const auto chunks = static_cast<std::size_t>(std::max(1, tbb::this_task_arena::max_concurrency()));
  const auto chunk_begin = [&](std::size_t j) { return order.size() * j / chunks; };
  std::vector<std::vector<std::uint32_t>> cursor(chunks);
  std::vector<std::vector<std::uint32_t>> big(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t j) {
    cursor[j].assign(cells, 0);
    for (std::size_t k = chunk_begin(j); k != chunk_begin(j + 1); ++k) {
      const Reach r = cell_rect(rects[k]);
      if (wide(r)) {
        big[j].push_back(order[k]);
        continue;
      }
      grid.for_each_cell(r, [&](std::size_t cell) { ++cursor[j][cell]; });
    }
  });
  for (const std::vector<std::uint32_t>& some : big) grid.big_.insert(grid.big_.end(), some.begin(), some.end());
  if (grid.big_.size() > kMostBigTriangles) return std::nullopt;
  grid.first_.resize(cells + 1);
  // Offsets in 32 bits: the cap keeps them below 2^32.
  const std::size_t most = std::min<std::size_t>(kMostEntriesPerTriangle * listed_count, std::numeric_limits<std::uint32_t>::max());
  std::size_t total = 0;
  for (std::size_t cell = 0; cell < cells; ++cell) {
    grid.first_[cell] = static_cast<std::uint32_t>(total);
    for (std::size_t j = 0; j < chunks; ++j) {
      const std::size_t here = cursor[j][cell];
      cursor[j][cell] = static_cast<std::uint32_t>(total);
      total += here;
    }
    if (total > most) return std::nullopt;
  }
  grid.first_[cells] = static_cast<std::uint32_t>(total);
  grid.entries_ = HugePageBuffer<std::uint32_t>(total);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t j) {
    for (std::size_t k = chunk_begin(j); k != chunk_begin(j + 1); ++k) {
      const Reach r = cell_rect(rects[k]);
      if (wide(r)) continue;
      grid.for_each_cell(r, [&](std::size_t cell) { grid.entries_[cursor[j][cell]++] = order[k]; });
    }
  });
  return grid;
}

}  // namespace shadowcert::detail
