#include "exact/degenerate_triangles.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace shadowcert {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_3 point(const Vec3& v) { return {v[0], v[1], v[2]}; }

TriangleShape shape_of(const Soup& soup, const Triangle& t) {
  if (!has_distinct_indices(t)) return TriangleShape::RepeatedIndex;
  // Epick's collinear is a filtered predicate: interval arithmetic, exact fallback, so the
  // answer is exact for double inputs (docs/definitions.md#orientation: no tolerance).
  const bool collinear = CGAL::collinear(point(soup.vertices[t[0]]), point(soup.vertices[t[1]]),
                                         point(soup.vertices[t[2]]));
  return collinear ? TriangleShape::Collinear : TriangleShape::Proper;
}

}  // namespace

std::vector<TriangleShape> classify_triangle_shapes(const Soup& welded) {
  std::vector<TriangleShape> shapes(welded.triangles.size(), TriangleShape::Proper);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, shapes.size(), 1 << 14),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t t = range.begin(); t != range.end(); ++t)
                        shapes[t] = shape_of(welded, welded.triangles[t]);
                    });
  return shapes;
}

}  // namespace shadowcert
