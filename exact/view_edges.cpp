#include "exact/view_edges.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/light.h"
#include "exact/degenerate_triangles.h"
#include "exact/edge_multiplicity.h"
#include "exact/normal_angle.h"

namespace shadowcert {

std::size_t ViewEdges::count(std::uint8_t bits) const {
  return static_cast<std::size_t>(
      std::count_if(classes.begin(), classes.end(), [bits](std::uint8_t c) { return (c & bits) != 0; }));
}

ViewEdges view_edges(const Soup& canonical, const EdgeTable& table, const Vec3& eye, double crease_cosine) {
  for (const double x : eye)
    if (!std::isfinite(x)) throw std::invalid_argument("view_edges: the eye must be finite");
  if (!(crease_cosine >= -1.0 && crease_cosine <= 1.0))
    throw std::invalid_argument("view_edges: the crease cosine must lie in [-1, 1]");
  const Light at_eye{{eye[0], eye[1], eye[2], 1.0}};
  // sign D(u, v, o, eye) per entry, zero for a triangle that casts nothing from the eye (seen
  // edge-on, or degenerate): the multiplicity's own terms (throws on a foreign table).
  std::vector<Sign> entries;
  try {
    entries = edge_entry_signs(MultiplicityMethod::exact, canonical, table, at_eye, Precision::float64);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("view_edges: ") + e.what());
  }
  const std::vector<TriangleShape> shapes = classify_triangle_shapes(canonical);

  ViewEdges out;
  out.classes.assign(table.size(), 0);
  out.multiplicity.assign(table.size(), 0);
  out.proper_faces.assign(table.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, table.size(), 4096), [&](const auto& range) {
    for (std::size_t e = range.begin(); e != range.end(); ++e) {
      std::int32_t m = 0;
      std::uint32_t proper = 0;
      std::uint32_t first = 0, second = 0;  // the first two proper entries
      for (std::uint32_t k = table.first_opposite[e]; k < table.first_opposite[e + 1]; ++k) {
        m -= to_int(entries[k]);
        if (shapes[table.opposite_triangle[k]] != TriangleShape::Proper) continue;
        (proper == 0 ? first : second) = k;
        ++proper;
      }
      std::uint8_t bits = 0;
      if (m != 0) bits |= kSilhouetteEdge;
      if (proper == 1) bits |= kBorderEdge;
      // Both seen (nonzero), m = 0 between them: opposite signs, the eye sees a fold, not an
      // outline. The bend decides; a bend exactly at the threshold is no crease.
      if (proper == 2 && m == 0 && entries[first] != Sign::zero && entries[second] != Sign::zero) {
        const Vec3& u = canonical.vertices[table.edges[e][0]];
        const Vec3& v = canonical.vertices[table.edges[e][1]];
        const Vec3& o1 = canonical.vertices[table.opposite_vertex[first]];
        const Vec3& o2 = canonical.vertices[table.opposite_vertex[second]];
        switch (bend_angle_sign(u, v, o1, o2, crease_cosine)) {
          case Sign::positive:
            bits |= kCreaseEdge;
            break;
          case Sign::zero:  // exactly the threshold: not above it
          case Sign::negative:
            break;
        }
      }
      out.classes[e] = bits;
      out.multiplicity[e] = m;
      out.proper_faces[e] = proper;
    }
  });
  return out;
}

}  // namespace shadowcert
