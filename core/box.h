#pragma once
// An axis-aligned box of doubles, closed: the one box type of the project (sampling boxes,
// tree nodes, the view a campaign case is framed by).
#include <algorithm>
#include <stdexcept>
#include <vector>

#include "core/soup.h"

namespace shadowcert {

struct Box {
  Vec3 lo{};  // lo[i] <= hi[i] for a box built below
  Vec3 hi{};
};

// The smallest box holding every point. Throws std::invalid_argument("bounding_box: no
// points") for none.
[[nodiscard]] inline Box bounding_box(const std::vector<Vec3>& points) {
  if (points.empty()) throw std::invalid_argument("bounding_box: no points");
  Box box{points.front(), points.front()};
  for (const Vec3& p : points)
    for (std::size_t i = 0; i < 3; ++i) {
      box.lo[i] = std::min(box.lo[i], p[i]);
      box.hi[i] = std::max(box.hi[i], p[i]);
    }
  return box;
}

// The box of the vertices the soup's triangles use (unused vertices are neither drawn nor
// cast); the point box at the origin when there is no triangle. Throws std::out_of_range on
// an index out of range.
[[nodiscard]] inline Box used_vertex_box(const Soup& soup) {
  std::vector<Vec3> used;
  used.reserve(soup.triangles.size() * 3);
  for (const Triangle& t : soup.triangles)
    for (const std::uint32_t i : t) used.push_back(soup.vertices.at(i));
  if (used.empty()) used.push_back({0.0, 0.0, 0.0});
  return bounding_box(used);
}

// The box of one triangle: `vertices` indexed by `t` (in range: the caller's precondition).
[[nodiscard]] inline Box triangle_box(const std::vector<Vec3>& vertices, const Triangle& t) {
  Box box{vertices[t[0]], vertices[t[0]]};
  for (std::size_t k = 1; k < 3; ++k)
    for (std::size_t i = 0; i < 3; ++i) {
      box.lo[i] = std::min(box.lo[i], vertices[t[k]][i]);
      box.hi[i] = std::max(box.hi[i], vertices[t[k]][i]);
    }
  return box;
}

// The box of every triangle of the soup, in order (the leaves of a box tree over it).
[[nodiscard]] inline std::vector<Box> triangle_boxes(const Soup& soup) {
  std::vector<Box> boxes;
  boxes.reserve(soup.triangles.size());
  for (const Triangle& t : soup.triangles) boxes.push_back(triangle_box(soup.vertices, t));
  return boxes;
}

}  // namespace shadowcert
