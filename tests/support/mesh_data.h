#pragma once
// The real meshes the tests read, and what a test does when one is missing (test code only).
//
// Two sets, named by the same relative paths ("closed_manifold/spot.obj"):
//   - bundled: the ten meshes of data/meshes/ (its README: sources, licences, SHA-256), in every
//     clone. A missing bundled mesh is a failure, always: the real-mesh tests must not go green
//     by skipping on a clean clone (docs/development.md#real-meshes).
//   - shared: the larger meshes of a developer checkout (SHADOWCERT_SHARED_DATA, ../shared/data
//     beside the source tree), which may not be redistributed. Their tests skip with the reason
//     when the folder is absent, and fail instead under SHADOWCERT_REQUIRE_SHARED_DATA=1 (CI).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "support/test_requirements.h"

namespace shadowcert::test {

// The meshes of data/meshes/, relative to it.
inline constexpr std::array<std::string_view, 10> kBundledMeshes{
    "closed_manifold/thingi10k_65004.stl",
    "closed_manifold/spot.obj",
    "closed_defective/manifold_self_intersectA.obj",
    "soups/trimesh_bunny.ply",
    "soups/trimesh_chair_model.obj",
    "soups/trimesh_cycloidal.ply",
    "edge_cases/trimesh_multibody.stl",
    "edge_cases/manifold_openscad-nonmanifold-crash.obj",
    "edge_cases/trimesh_featuretype.STL",
    "edge_cases/trimesh_shared.STL",
};

inline bool is_bundled_mesh(std::string_view relative) {
  return std::find(kBundledMeshes.begin(), kBundledMeshes.end(), relative) != kBundledMeshes.end();
}

// The folder of the bundled meshes (data/meshes/ of the source tree).
inline std::filesystem::path bundled_mesh_dir() { return std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "meshes"; }

// The folder of the shared meshes: $SHADOWCERT_SHARED_DATA when set, else ../shared/data beside
// the source tree.
inline std::filesystem::path shared_mesh_dir() {
  const char* value = std::getenv("SHADOWCERT_SHARED_DATA");
  return value != nullptr && *value != '\0' ? std::filesystem::path(value) : std::filesystem::path(SHADOWCERT_SHARED_DATA);
}

// The file of a mesh named by its relative path: data/meshes/ for a bundled one, the shared
// folder for the others.
inline std::filesystem::path mesh_file(std::string_view relative) {
  return (is_bundled_mesh(relative) ? bundled_mesh_dir() : shared_mesh_dir()) / std::string(relative);
}

// Why a test cannot run: empty when the mesh is there; else the reason, and whether that is a
// failure (bundled, or shared under SHADOWCERT_REQUIRE_SHARED_DATA=1) or a skip.
struct MissingMesh {
  std::string reason;
  bool fails = false;
  explicit operator bool() const { return !reason.empty(); }
};

inline MissingMesh missing_mesh(std::string_view relative) {
  const std::filesystem::path file = mesh_file(relative);
  if (std::filesystem::is_regular_file(file)) return {};
  if (is_bundled_mesh(relative)) return {file.string() + " is missing: the bundled meshes of data/meshes/ are part of the repository", true};
  return {file.string() + " is not here (a developer checkout's shared meshes; SHADOWCERT_SHARED_DATA names their folder)",
          shared_data_required()};
}

// A gtest parameter name for a mesh: its file name's stem with every character that is not a
// letter or digit replaced by '_' ("closed_manifold/spot.obj" -> "spot").
inline std::string mesh_test_name(std::string_view relative) {
  std::string name = std::filesystem::path(std::string(relative)).stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) == 0; }, '_');
  return name;
}

}  // namespace shadowcert::test

// In a test body: fails (bundled or required) or skips the test when the mesh RELATIVE is missing.
#define SHADOWCERT_REQUIRE_MESH(relative)                                                    \
  do {                                                                                       \
    const ::shadowcert::test::MissingMesh shadowcert_missing = ::shadowcert::test::missing_mesh(relative); \
    if (shadowcert_missing) {                                                                \
      if (shadowcert_missing.fails) FAIL() << shadowcert_missing.reason;                     \
      GTEST_SKIP() << shadowcert_missing.reason;                                             \
    }                                                                                        \
  } while (false)
