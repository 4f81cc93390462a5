#pragma once
// The scene format's "generator" meshes: each procedural_mesh.h function by name, with JSON
// params that all have defaults (docs/scene-format.md lists them).
#include <optional>

#include "core/ellipsoid.h"
#include "core/soup.h"
#include "scene/json_field.h"

namespace shadowcert {

// A generator's mesh in its model space, and for uv_sphere and icosphere the sphere it
// approximates (its "center" and "radius"; nullopt for the other generators).
struct GeneratedMesh {
  Soup soup;
  std::optional<Ellipsoid> ellipsoid;
};

// `name` is the mesh's "generator" field, `params` its "params" object if any. Unknown names,
// unknown or mistyped params and out-of-range values are InputErrors naming the key path.
[[nodiscard]] GeneratedMesh run_generator(const JsonField& name, const std::optional<JsonField>& params);

}  // namespace shadowcert
