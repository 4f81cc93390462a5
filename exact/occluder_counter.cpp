// OccluderCounter of exact/count_certificate.h: the direct occluder count n(P) of docs/definitions.md#counts,
// by a box tree over the casting triangles (exact s != 0) and the exact crossing test of
// exact/face_crossing.h on every triangle in a tree leaf the segment (or ray) to the light
// reaches. The leaf's own box is not tested: the triangle test, one orient for most
// triangles (the light's side is known), is cheaper.
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "core/box.h"
#include "exact/box_tree.h"
#include "exact/count_certificate.h"
#include "exact/face_crossing.h"
#include "exact/light_orientation.h"

namespace shadowcert {
namespace {

// What n(P) is counted over: the casting triangles and the light.
struct CasterSet {
  std::vector<Vec3> vertices;
  std::vector<Triangle> casters;  // the soup's triangles with s(t) != 0 (docs/definitions.md#counts)
  std::vector<Sign> light_side;   // their s(t)
  HomogeneousPoint light{};
};

void require_valid_light(const Light& light) { require_defined(light, "OccluderCounter"); }

// The casting triangles of `soup` for `l`, with their exact light sides.
CasterSet casting_triangles(const Soup& soup, const Light& l) {
  require_valid_light(l);
  CasterSet set{soup.vertices, {}, {}, l.position};
  const std::vector<Vec3>& vertices = set.vertices;
  require_indices_in_range(soup, "OccluderCounter");
  for (const Triangle& t : soup.triangles) {
    const Sign s = light_orientation(vertices[t[0]], vertices[t[1]], vertices[t[2]], l);
    switch (s) {
      case Sign::zero:
        break;  // the light on its plane, or no area: casts nothing (docs/definitions.md#orientation)
      case Sign::positive:
      case Sign::negative:
        set.casters.push_back(t);
        set.light_side.push_back(s);
        break;
    }
  }
  if (set.casters.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("OccluderCounter: more than 2^32 casting triangles");
  return set;
}

// Each caster's box: its vertices' coordinates, exact.
std::vector<Box> caster_boxes(const CasterSet& set) {
  std::vector<Box> boxes;
  boxes.reserve(set.casters.size());
  for (const Triangle& t : set.casters) boxes.push_back(triangle_box(set.vertices, t));
  return boxes;
}

}  // namespace

struct OccluderCounter::Impl {
  CasterSet set;
  detail::BoxTree tree;

  Impl(const Soup& soup, const Light& l)
      : set(casting_triangles(soup, l)), tree(caster_boxes(set), detail::LeafTest::skip) {}

  [[nodiscard]] std::optional<std::uint32_t> count(const Vec3& p) const;
};

// Classifies every caster whose box the query meets and stops at the first touch, where n(P)
// is undefined (docs/definitions.md#counts: P on no boundary).
std::optional<std::uint32_t> OccluderCounter::Impl::count(const Vec3& p) const {
  const HomogeneousPoint& light = set.light;
  const HomogeneousPoint start = finite_point(p);
  std::uint32_t crossings = 0;
  bool touched = false;
  auto classify = [&](std::uint32_t id) {
    const Triangle& t = set.casters[id];
    const auto& v = set.vertices;
    switch (detail::segment_meets_triangle(start, light, set.light_side[id], v[t[0]], v[t[1]], v[t[2]]).meeting) {
      case detail::Meeting::apart:
        return true;
      case detail::Meeting::crosses:
        ++crossings;
        return true;
      case detail::Meeting::touches:
        touched = true;
        return false;
    }
    return false;
  };
  if (light[3] == 0.0) {
    tree.ray_query(p, {light[0], light[1], light[2]}, classify);
  } else {
    const Vec3 l{light[0], light[1], light[2]};
    if (p == l) return 0u;  // the open segment is empty: nothing is crossed
    tree.segment_query(p, l, classify);
  }
  if (touched) return std::nullopt;
  return crossings;
}

OccluderCounter::OccluderCounter(const Soup& soup, const Light& light) : impl_(std::make_unique<Impl>(soup, light)) {}
OccluderCounter::~OccluderCounter() = default;
OccluderCounter::OccluderCounter(OccluderCounter&&) noexcept = default;
OccluderCounter& OccluderCounter::operator=(OccluderCounter&&) noexcept = default;

std::optional<std::uint32_t> OccluderCounter::count(const Vec3& point) const { return impl_->count(point); }

}  // namespace shadowcert
