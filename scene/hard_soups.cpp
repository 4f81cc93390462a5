#include "scene/hard_soups.h"

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/portable_math.h"

namespace shadowcert {
namespace {

Soup soup_of(std::vector<Vec3> vertices, std::vector<Triangle> triangles) {
  Soup s;
  s.vertices = std::move(vertices);
  s.triangles = std::move(triangles);
  return s;
}

}  // namespace

Soup half_fan(std::uint32_t k) {
  if (k == 0) throw std::invalid_argument("half_fan: k must be at least 1");
  Soup s;
  s.vertices = {{0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};
  for (std::uint32_t i = 0; i < k; ++i) {
    const double angle = portable::kPi * (i + 0.5) / k;
    s.vertices.push_back({portable::cos(angle), 0.5, portable::sin(angle)});
    s.triangles.push_back(i % 2 == 0 ? Triangle{0, 1, i + 2} : Triangle{1, 0, i + 2});
  }
  return s;
}

Soup slivers() {
  return soup_of({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0.5, 1e-12, 0}, {0.5, 0.3, 1e-9}, {0, 1, 0}, {1, 1, 1e-15}},
                 {{0, 1, 2},   // zero area: collinear, distinct
                  {0, 2, 3},   // sliver
                  {0, 1, 4},   // grazing the light below
                  {1, 5, 6},   // nearly vertical
                  {2, 6, 5}});
}

Soup t_junctions_and_cracks() {
  return soup_of({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {1, 0, 0.5}, {2, 0, 0}, {2, 0, 1}, {2.001, 0, 0},
                  {3, 0, 0}, {3, 0, 1}, {2.001, 0, 1}},
                 {{0, 2, 1}, {0, 3, 2}, {1, 4, 5}, {4, 2, 6}, {4, 6, 5}, {7, 10, 9}, {7, 9, 8}});
}

Soup bow_ties() {
  return soup_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {3, 0, 0},
                  {4, 0, 0}, {3, 1, 0}, {2, 0, 0}, {3, -1, 0.5}},
                 {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 4, 5}, {0, 6, 4}, {4, 6, 5}, {0, 5, 6}, {7, 8, 9},
                  {7, 10, 11}});
}

Soup unwelded(const Soup& soup) {
  Soup s;
  s.vertices.reserve(3 * soup.triangles.size());
  s.triangles.reserve(soup.triangles.size());
  for (const Triangle& t : soup.triangles) {
    const auto first = static_cast<std::uint32_t>(s.vertices.size());
    for (std::uint32_t id : t) {
      const Vec3& p = soup.vertices.at(id);
      s.vertices.push_back({static_cast<double>(static_cast<float>(p[0])), static_cast<double>(static_cast<float>(p[1])),
                            static_cast<double>(static_cast<float>(p[2]))});
    }
    s.triangles.push_back({first, first + 1, first + 2});
  }
  return s;
}

}  // namespace shadowcert
