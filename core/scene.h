#pragma once
// A scene models only what a shadow needs (docs/definitions.md#inputs): soups already placed in
// world space, one or more lights, and a camera.
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/ellipsoid.h"
#include "core/light.h"
#include "core/soup.h"

namespace shadowcert {

// How a mesh says it is cast under the smooth-silhouette methods (the scene key "silhouette",
// docs/scene-format.md): by the robust exact chain whatever the command asks, or by one of the
// silhouette methods (docs/smooth-silhouettes.md).
enum class MeshSilhouette { chain, discrete, accurate, smooth };

struct SceneMesh {
  std::string name;  // the file path or the generator's name, for reports
  Soup soup;         // world-space: the mesh's transform has been applied
  // "casts": false keeps the mesh out of every shadow volume and every occluder count: it only
  // receives (a floor). It still hides what lies behind it.
  bool casts = true;
  // "silhouette" and "epsilon": the mesh's own silhouette method and contour error (world units,
  // > 0), overriding the command's for this mesh; nullopt: the command's.
  std::optional<MeshSilhouette> silhouette;
  std::optional<double> epsilon;
  // The analytic surface the mesh approximates, world space (a uv_sphere or icosphere generator,
  // its transform applied); nullopt for files and other generators.
  std::optional<Ellipsoid> ellipsoid;
};

struct Scene {
  std::vector<SceneMesh> meshes;
  std::vector<Light> lights;  // at least one
  Camera camera;
};

}  // namespace shadowcert
