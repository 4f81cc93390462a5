// libFuzzer harness: the JSON scene format (scene/scene_file.h parse_scene), on arbitrary
// bytes (docs/fuzzing-parsers.md). Mesh files are not read from disk: a stub reader stands
// for read_soup (which has its own harnesses), and generated meshes are capped by an
// allocation budget (fuzz/allocation_budget.h).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <new>
#include <string>
#include <string_view>

#include "core/input_error.h"
#include "core/scene.h"
#include "fuzz/allocation_budget.h"
#include "fuzz/fuzz_check.h"
#include "scene/scene_file.h"

namespace {

namespace fs = std::filesystem;
using shadowcert::fuzz::finite;
using shadowcert::fuzz::require;

// Enough for every bundled scene's generators at their default resolutions (a 32 x 16 UV
// sphere is 992 triangles); a sphere_grid of a million triangles is over it.
constexpr std::size_t kAllocationBudget = std::size_t{8} << 20;

// docs/scene-format.md: image sides are in [1, kMaxImageSide] (core/camera.h).
using shadowcert::kMaxImageSide;

// A named file "missing..." fails as read_soup fails on a bad file; any other name reads
// as a closed tetrahedron, so that transforms and the default light get a mesh to work on.
shadowcert::Soup stub_mesh_reader(const fs::path& file) {
  if (file.filename().string().starts_with("missing"))
    throw shadowcert::InputError(file.string(), 1, "no such mesh (fuzz stub reader)");
  return {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}, {}};
}

// parse_scene's promises (docs/scene-format.md) on a scene it returns.
void require_valid_scene(const shadowcert::Scene& scene) {
  for (const shadowcert::SceneMesh& mesh : scene.meshes) {
    shadowcert::fuzz::require_valid_soup(mesh.soup);
    if (mesh.epsilon) require(std::isfinite(*mesh.epsilon) && *mesh.epsilon > 0.0);
    if (mesh.ellipsoid) {
      require(finite(mesh.ellipsoid->centre));
      for (const shadowcert::Vec3& axis : mesh.ellipsoid->axes) require(finite(axis));
    }
  }
  require(!scene.lights.empty());
  for (const shadowcert::Light& light : scene.lights) {
    const auto& p = light.position;
    require(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
    require(p[3] == 0.0 || p[3] == 1.0);
    if (light.directional()) require(p[0] != 0.0 || p[1] != 0.0 || p[2] != 0.0);
  }
  const shadowcert::Camera& camera = scene.camera;
  require(finite(camera.eye) && finite(camera.target) && finite(camera.up));
  require(camera.eye != camera.target);
  require(camera.up != shadowcert::Vec3{0, 0, 0});
  require(camera.fov_y_degrees > 0.0 && camera.fov_y_degrees < 180.0);
  require(camera.width >= 1 && camera.width <= kMaxImageSide);
  require(camera.height >= 1 && camera.height <= kMaxImageSide);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string file_name = "fuzz.json";
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const shadowcert::fuzz::AllocationBudget budget(kAllocationBudget);
    const shadowcert::Scene scene = shadowcert::parse_scene(text, file_name, "/fuzz", stub_mesh_reader);
    require_valid_scene(scene);
  } catch (const shadowcert::InputError& error) {
    require(error.file() == file_name);
  } catch (const std::bad_alloc&) {
    // Over the budget: a scene asking for more geometry than a fuzz input may build.
  }
  return 0;
}
