#include "scene/framed_scene.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/near_plane.h"
#include "core/vector3.h"
#include "scene/procedural_mesh.h"

namespace shadowcert {
namespace {

constexpr double kAnalyticFloorHalfSize = 8.0;

void check_size(std::uint32_t width, std::uint32_t height, const char* function) {
  if (width == 0 || height == 0)
    throw std::invalid_argument(std::string(function) + ": the image size has a zero side");
}

}  // namespace

Scene framed_mesh_scene(const Soup& mesh, const std::string& name, const FramedMeshOptions& options) {
  check_size(options.width, options.height, "framed_mesh_scene");
  if (mesh.triangles.empty()) throw std::invalid_argument("framed_mesh_scene: " + name + " has no triangle");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t)
      for (std::size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], mesh.vertices[v][k]);
        hi[k] = std::max(hi[k], mesh.vertices[v][k]);
      }
  const Vec3 c{0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
  const double r = 0.5 * std::sqrt(dot(difference(hi, lo), difference(hi, lo)));
  const auto at = [&](double x, double y, double z) { return Vec3{c[0] + r * x, c[1] + r * y, c[2] + r * z}; };
  SceneMesh floor;
  floor.name = "floor";
  const double y = lo[1] - 0.01 * r;
  floor.soup.vertices = {{c[0] - 3 * r, y, c[2] - 3 * r}, {c[0] - 3 * r, y, c[2] + 3 * r},
                         {c[0] + 3 * r, y, c[2] + 3 * r}, {c[0] + 3 * r, y, c[2] - 3 * r}};
  floor.soup.triangles = {{0, 1, 2}, {0, 2, 3}};
  floor.casts = options.floor_casts;
  SceneMesh caster;
  caster.name = name;
  caster.soup = mesh;
  Scene scene;
  scene.meshes.push_back(std::move(caster));
  scene.meshes.push_back(std::move(floor));
  const Vec3 light = at(1.5, 3.0, 1.0);
  scene.lights = {Light{{light[0], light[1], light[2], 1.0}}};
  scene.camera.eye = at(2.4, 1.6, 3.2);
  scene.camera.target = c;
  scene.camera.width = options.width;
  scene.camera.height = options.height;
  scene.camera = camera_fitted_to(scene);
  return scene;
}

std::vector<AnalyticShape> analytic_shapes() {
  std::vector<AnalyticShape> out;
  for (const auto& [slices, stacks] : {std::pair{8u, 4u}, {12u, 6u}, {16u, 8u}, {32u, 16u}, {64u, 32u}, {128u, 64u},
                                       {256u, 128u}})
    out.push_back({"sphere" + std::to_string(slices) + "x" + std::to_string(stacks),
                   uv_sphere({0, 0, 0}, 1.0, slices, stacks), Ellipsoid{}});
  const Ellipsoid e{{0, 0, 0}, {{{1.4, 0.0, 0.2}, {0.0, 0.8, 0.0}, {-0.3, 0.0, 1.0}}}};
  Soup s = uv_sphere({0, 0, 0}, 1.0, 32, 16);
  s.normals.clear();  // computed from the transformed mesh
  for (Vec3& v : s.vertices) {
    const Vec3 u = v;
    for (std::size_t k = 0; k < 3; ++k) v[k] = e.axes[0][k] * u[0] + e.axes[1][k] * u[1] + e.axes[2][k] * u[2];
  }
  out.push_back({"ellipsoid32x16", std::move(s), e});
  return out;
}

Scene analytic_shape_scene(const AnalyticShape& shape, const Light& light, std::uint32_t width, std::uint32_t height) {
  check_size(width, height, "analytic_shape_scene");
  Scene scene;
  SceneMesh floor;
  floor.name = "floor";
  floor.soup = floor_quad(kAnalyticFloorHalfSize);
  for (Vec3& v : floor.soup.vertices) v[1] += kAnalyticFloorHeight;
  floor.casts = false;  // it only receives
  scene.meshes.push_back(std::move(floor));
  SceneMesh caster;
  caster.name = shape.name;
  caster.soup = shape.soup;
  caster.ellipsoid = shape.ellipsoid;
  scene.meshes.push_back(std::move(caster));
  scene.lights = {light};
  scene.camera.eye = {-2.5, 5.5, 6.5};
  scene.camera.target = {-0.4, -0.9, -0.3};
  scene.camera.width = width;
  scene.camera.height = height;
  scene.camera = camera_fitted_to(scene);
  return scene;
}

}  // namespace shadowcert
