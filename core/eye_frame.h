#pragma once
// Camera-relative upload (docs/diff.md, "Camera-relative upload"): GL receives every position
// minus the eye, each difference taken in double and then rounded once to float. Near the eye,
// where pixels are small, float then keeps its full relative precision; in world space a scene
// at 1e6 would be rounded to 0.0625 (docs/definitions.md#hard-cases, offset_1e6). The exact
// protocol models exactly this input: reference/input_rounding.h rounds the scene as moved here.
// Directions (w = 0 lights) and the camera's up vector do not move.
#include <optional>
#include <utility>

#include "core/camera.h"
#include "core/light.h"
#include "core/scene.h"
#include "core/soup.h"
#include "core/vector3.h"

namespace shadowcert {

// Every vertex minus `origin`, in double.
[[nodiscard]] inline Soup relative_to(const Soup& soup, const Vec3& origin) {
  Soup out = soup;
  for (Vec3& v : out.vertices) v = difference(v, origin);
  return out;
}

// A point light minus `origin`; a directional light as it is.
[[nodiscard]] inline Light relative_to(const Light& light, const Vec3& origin) {
  if (light.directional()) return light;
  const Vec3 l = difference({light.position[0], light.position[1], light.position[2]}, origin);
  return Light{{l[0], l[1], l[2], 1.0}};
}

// Eye and target minus `origin`; up, field of view and size as they are.
[[nodiscard]] inline Camera relative_to(const Camera& camera, const Vec3& origin) {
  Camera out = camera;
  out.eye = difference(camera.eye, origin);
  out.target = difference(camera.target, origin);
  return out;
}

// The scene in its eye's frame: what every GL method is given (the eye lands on 0 exactly).
[[nodiscard]] inline Scene eye_relative_scene(const Scene& scene) {
  const Vec3 origin = scene.camera.eye;
  Scene out;
  out.meshes.reserve(scene.meshes.size());
  for (const SceneMesh& mesh : scene.meshes) {
    // Every field named, so that a new one warns here (-Wmissing-field-initializers).
    std::optional<Ellipsoid> ellipsoid = mesh.ellipsoid;
    if (ellipsoid) ellipsoid->centre = difference(ellipsoid->centre, origin);
    out.meshes.push_back({mesh.name, relative_to(mesh.soup, origin), mesh.casts, mesh.silhouette, mesh.epsilon,
                          std::move(ellipsoid)});
  }
  for (const Light& light : scene.lights) out.lights.push_back(relative_to(light, origin));
  out.camera = relative_to(scene.camera, origin);
  return out;
}

}  // namespace shadowcert
