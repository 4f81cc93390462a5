#include "scene/fuzz_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace shadowcert {
namespace {

Vec3 unframed_point(const Vec3& p, const FuzzFrame& frame) {
  return {std::ldexp(p[0] - frame.offset, -frame.scale_exponent), std::ldexp(p[1] - frame.offset, -frame.scale_exponent),
          std::ldexp(p[2] - frame.offset, -frame.scale_exponent)};
}

bool reframes_to(const Vec3& unit, const Vec3& framed, const FuzzFrame& frame) {
  for (int k = 0; k < 3; ++k)
    if (std::ldexp(unit[k], frame.scale_exponent) + frame.offset != framed[k]) return false;
  return true;
}

struct Box {
  Vec3 low{0.0, 0.0, 0.0};
  Vec3 high{0.0, 0.0, 0.0};

  [[nodiscard]] Vec3 centre() const {
    return {0.5 * (low[0] + high[0]), 0.5 * (low[1] + high[1]), 0.5 * (low[2] + high[2])};
  }
  // Half the diagonal, at least kMinViewRadius.
  [[nodiscard]] double radius() const {
    const double dx = high[0] - low[0], dy = high[1] - low[1], dz = high[2] - low[2];
    return std::max(0.5 * std::sqrt(dx * dx + dy * dy + dz * dz), kMinViewRadius);
  }
};

// The box of the vertices the triangles use (unused vertices are not drawn).
Box used_box(const Soup& soup) {
  Box box;
  bool first = true;
  for (const Triangle& t : soup.triangles)
    for (const std::uint32_t index : t) {
      const Vec3& v = soup.vertices.at(index);
      for (int i = 0; i < 3; ++i) {
        box.low[i] = first ? v[i] : std::min(box.low[i], v[i]);
        box.high[i] = first ? v[i] : std::max(box.high[i], v[i]);
      }
      first = false;
    }
  return box;
}

double to_float(double x) { return static_cast<double>(static_cast<float>(x)); }

}  // namespace

Soup unframed(const Soup& soup, const FuzzFrame& frame) {
  Soup out = soup;
  for (Vec3& v : out.vertices) v = unframed_point(v, frame);
  return out;
}

Light unframed(const Light& light, const FuzzFrame& frame) {
  if (light.directional()) return light;
  const Vec3 p = unframed_point({light.position[0], light.position[1], light.position[2]}, frame);
  return Light{{p[0], p[1], p[2], 1.0}};
}

bool unframes_exactly(const FuzzCase& fuzz_case) {
  const FuzzFrame& frame = fuzz_case.kind.frame;
  for (const Vec3& v : fuzz_case.soup.vertices)
    if (!reframes_to(unframed_point(v, frame), v, frame)) return false;
  if (fuzz_case.light.directional()) return true;
  const Vec3 l{fuzz_case.light.position[0], fuzz_case.light.position[1], fuzz_case.light.position[2]};
  return reframes_to(unframed_point(l, frame), l, frame);
}

Soup fuzz_view_floor(const Soup& soup) {
  const Box box = used_box(soup);
  const Vec3 c = box.centre();
  const double r = box.radius();
  const double y = to_float(box.low[1] - kFloorDrop * r);
  const double x0 = to_float(c[0] - kFloorHalfSide * r), x1 = to_float(c[0] + kFloorHalfSide * r);
  const double z0 = to_float(c[2] - kFloorHalfSide * r), z1 = to_float(c[2] + kFloorHalfSide * r);
  Soup floor;
  floor.vertices = {{x0, y, z0}, {x0, y, z1}, {x1, y, z1}, {x1, y, z0}};
  // Counter-clockwise seen from above: normals +y.
  floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  return floor;
}

Camera fuzz_view_camera(const Soup& soup, std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0) throw std::invalid_argument("fuzz_view: the image size must be at least 1x1");
  const Box box = used_box(soup);
  const Vec3 c = box.centre();
  const double half_fov = 0.5 * kFuzzViewFovDegrees * std::numbers::pi / 180.0;
  const double distance = kViewMargin * box.radius() / std::sin(half_fov);
  Camera camera;
  camera.target = c;
  camera.eye = {c[0] + distance * kViewDirection[0], c[1] + distance * kViewDirection[1],
                c[2] + distance * kViewDirection[2]};
  camera.up = {0.0, 1.0, 0.0};
  camera.fov_y_degrees = kFuzzViewFovDegrees;
  camera.width = width;
  camera.height = height;
  return camera;
}

FuzzView fuzz_view(const FuzzCase& fuzz_case, std::uint32_t width, std::uint32_t height) {
  FuzzView view;
  const FuzzFrame& frame = fuzz_case.kind.frame;
  view.unframed = (frame.scale_exponent != 0 || frame.offset != 0.0) && unframes_exactly(fuzz_case);
  view.soup = view.unframed ? unframed(fuzz_case.soup, frame) : fuzz_case.soup;
  view.light = view.unframed ? unframed(fuzz_case.light, frame) : fuzz_case.light;
  view.camera = fuzz_view_camera(view.soup, width, height);
  view.floor = fuzz_view_floor(view.soup);
  return view;
}

}  // namespace shadowcert
