#include "campaign/campaign_view.h"

#include "core/box.h"
#include "core/float_rounding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/portable_math.h"

namespace shadowcert {
namespace {

Vec3 unframed_point(const Vec3& p, const SoupFrame& frame) {
  return {std::ldexp(p[0] - frame.offset, -frame.scale_exponent), std::ldexp(p[1] - frame.offset, -frame.scale_exponent),
          std::ldexp(p[2] - frame.offset, -frame.scale_exponent)};
}

bool reframes_to(const Vec3& unit, const Vec3& framed, const SoupFrame& frame) {
  for (int k = 0; k < 3; ++k)
    if (std::ldexp(unit[k], frame.scale_exponent) + frame.offset != framed[k]) return false;
  return true;
}

Vec3 centre(const Box& box) {
  return {0.5 * (box.lo[0] + box.hi[0]), 0.5 * (box.lo[1] + box.hi[1]), 0.5 * (box.lo[2] + box.hi[2])};
}

// Half the diagonal, at least kMinViewRadius.
double radius(const Box& box) {
  const double dx = box.hi[0] - box.lo[0], dy = box.hi[1] - box.lo[1], dz = box.hi[2] - box.lo[2];
  return std::max(0.5 * std::sqrt(dx * dx + dy * dy + dz * dz), kMinViewRadius);
}

}  // namespace

Soup unframed(const Soup& soup, const SoupFrame& frame) {
  Soup out = soup;
  for (Vec3& v : out.vertices) v = unframed_point(v, frame);
  return out;
}

Light unframed(const Light& light, const SoupFrame& frame) {
  if (light.directional()) return light;
  const Vec3 p = unframed_point({light.position[0], light.position[1], light.position[2]}, frame);
  return Light{{p[0], p[1], p[2], 1.0}};
}

bool unframes_exactly(const CampaignCase& campaign_case) {
  const SoupFrame& frame = campaign_case.kind.frame;
  for (const Vec3& v : campaign_case.soup.vertices)
    if (!reframes_to(unframed_point(v, frame), v, frame)) return false;
  if (campaign_case.light.directional()) return true;
  const Vec3 l{campaign_case.light.position[0], campaign_case.light.position[1], campaign_case.light.position[2]};
  return reframes_to(unframed_point(l, frame), l, frame);
}

Soup campaign_view_floor(const Soup& soup) {
  const Box box = used_vertex_box(soup);
  const Vec3 c = centre(box);
  const double r = radius(box);
  const double y = float_rounded(box.lo[1] - kFloorDrop * r);
  const double x0 = float_rounded(c[0] - kFloorHalfSide * r), x1 = float_rounded(c[0] + kFloorHalfSide * r);
  const double z0 = float_rounded(c[2] - kFloorHalfSide * r), z1 = float_rounded(c[2] + kFloorHalfSide * r);
  Soup floor;
  floor.vertices = {{x0, y, z0}, {x0, y, z1}, {x1, y, z1}, {x1, y, z0}};
  // Counter-clockwise seen from above: normals +y.
  floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  return floor;
}

Camera campaign_view_camera(const Soup& soup, std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0) throw std::invalid_argument("campaign_view: the image size must be at least 1x1");
  const Box box = used_vertex_box(soup);
  const Vec3 c = centre(box);
  const double half_fov = 0.5 * kCampaignViewFovDegrees * std::numbers::pi / 180.0;
  const double distance = kViewMargin * radius(box) / portable::sin(half_fov);
  Camera camera;
  camera.target = c;
  camera.eye = {c[0] + distance * kViewDirection[0], c[1] + distance * kViewDirection[1],
                c[2] + distance * kViewDirection[2]};
  camera.up = {0.0, 1.0, 0.0};
  camera.fov_y_degrees = kCampaignViewFovDegrees;
  camera.width = width;
  camera.height = height;
  return camera;
}

CampaignView campaign_view(const CampaignCase& campaign_case, std::uint32_t width, std::uint32_t height) {
  CampaignView view;
  const SoupFrame& frame = campaign_case.kind.frame;
  view.unframed = (frame.scale_exponent != 0 || frame.offset != 0.0) && unframes_exactly(campaign_case);
  view.soup = view.unframed ? unframed(campaign_case.soup, frame) : campaign_case.soup;
  view.light = view.unframed ? unframed(campaign_case.light, frame) : campaign_case.light;
  view.camera = campaign_view_camera(view.soup, width, height);
  view.floor = campaign_view_floor(view.soup);
  return view;
}

}  // namespace shadowcert
