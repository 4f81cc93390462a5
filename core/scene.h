#pragma once
// A scene models only what a shadow needs (docs/definitions.md#inputs): soups already placed in
// world space, one or more lights, and a camera.
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"

namespace shadowcert {

struct SceneMesh {
  std::string name;  // the file path or the generator's name, for reports
  Soup soup;         // world-space: the mesh's transform has been applied
};

struct Scene {
  std::vector<SceneMesh> meshes;
  std::vector<Light> lights;  // at least one
  Camera camera;
};

}  // namespace shadowcert
