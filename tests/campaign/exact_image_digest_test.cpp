// The exact image's answers pinned bit for bit (reference/exact_image.h): every output of
// exact_image (hit triangles, view ambiguity, and per light the counts, lit mask and ambiguity
// bits) hashed for many scenes and compared with tests/data/exact_image_digests.txt, written by
// the implementation before issue 24's float traversal. A faster traversal, filter or BVH must
// give exactly these bytes: the image is a function of the input doubles alone.
//
// The scenes: data/scenes/ (its hard/ folder included; not the 1M-triangle sphere grid) with the
// diff's depth band, the bundled meshes over a floor under a point light, a directional light and
// a light in the floor's plane, the random soups of the campaign (every family and light
// placement, windows and footprints off among them) and the hard-soup scenes of
// campaign/hard_scene.h. The shared meshes (ogre, nefertiti, horse) at a larger size run when
// ../shared/data is there (tests/support/mesh_data.h).
//
// Regenerate (only when the answers are meant to change, with the reason in the commit):
//   SHADOWCERT_WRITE_EXACT_IMAGE_DIGESTS=1 build/tests/exact_image_digest_test
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "campaign/campaign_view.h"
#include "campaign/hard_scene.h"
#include "campaign/random_soup.h"
#include "gpu/depth_precision.h"
#include "io/soup_file.h"
#include "reference/exact_image.h"
#include "scene/merged_soup.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_file.h"
#include "support/bit_digest.h"
#include "support/mesh_data.h"

namespace {

using namespace shadowcert;

// Every output of the image, in a fixed order.
std::string digest(const ExactImage& image) {
  test::BitDigest d;
  d.add(std::vector<std::uint32_t>{image.width, image.height});
  d.add(image.hit_triangles);
  d.add(image.view_ambiguity);
  for (const ExactLightImage& light : image.lights) {
    d.add(light.counts);
    d.add(light.lit);
    d.add(light.ambiguity);
  }
  return d.hex();
}

ExactImageOptions diff_options(const Camera& camera) {
  ExactImageOptions options;
  options.depth_band = [near = camera.near_plane](double view_depth) { return gpu::depth_band(view_depth, near); };
  return options;
}

struct Case {
  std::string name;
  Soup soup;
  std::vector<Light> lights;
  Camera camera;
  ExactImageOptions options;
};

Camera sized(Camera camera, std::uint32_t width, std::uint32_t height) {
  camera.width = width;
  camera.height = height;
  return camera;
}

void add_scene_files(std::vector<Case>& cases, const std::filesystem::path& folder, std::uint32_t width,
                     std::uint32_t height) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.path().extension() == ".json" && entry.path().stem() != "sphere_grid_1m") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    const Scene scene = load_scene(file, [](const std::filesystem::path& p) { return read_soup(p); });
    Case c{folder.filename().string() + "/" + file.filename().string(), merged_soup(scene), scene.lights,
           sized(scene.camera, width, height), diff_options(scene.camera)};
    if (!std::all_of(scene.meshes.begin(), scene.meshes.end(), [](const SceneMesh& m) { return m.casts; }))
      c.options.casts = casting_triangles(scene);
    cases.push_back(std::move(c));
  }
}

// `mesh` over a floor just below it, seen from the front and above (exact_image_bench's view),
// under a point light above it, a directional light and a point light in the floor's plane.
Case mesh_case(const std::string& name, const Soup& mesh, std::uint32_t width, std::uint32_t height) {
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  const Vec3 c{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  Case out;
  out.name = name;
  out.soup = floor_quad(1.5 * size);
  out.soup.normals.clear();
  const double floor_y = lo[1] - 0.01 * size;
  for (Vec3& v : out.soup.vertices) v = {v[0] + c[0], floor_y, v[2] + c[2]};
  Soup m = mesh;
  m.normals.clear();
  append_soup(out.soup, m);
  out.lights = {Light{{c[0] + 0.4 * size, c[1] + 2.0 * size, c[2] + 0.6 * size, 1.0}},
                Light{{-0.3, 1.0, 0.2, 0.0}},
                Light{{c[0] + 2.0 * size, floor_y, c[2] - 0.5 * size, 1.0}}};
  out.camera.eye = {c[0], c[1] + 0.8 * size, c[2] + 1.6 * size};
  out.camera.target = c;
  out.camera.width = width;
  out.camera.height = height;
  out.camera.near_plane = 0.01 * size;
  out.options = diff_options(out.camera);
  return out;
}

std::vector<Case> small_cases() {
  std::vector<Case> cases;
  const std::filesystem::path scenes = std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "scenes";
  add_scene_files(cases, scenes, 96, 72);
  add_scene_files(cases, scenes / "hard", 96, 72);
  for (std::string_view relative : test::kBundledMeshes)
    cases.push_back(mesh_case(std::string(relative), read_soup(test::mesh_file(relative)), 96, 72));
  // The campaign's random soups: the first cases of two seeds, every few with a window or
  // without footprints (their own code paths).
  for (std::uint64_t seed : {1u, 7u})
    for (std::uint64_t index = 0; index < 40; ++index) {
      const CampaignCase cc = campaign_case(seed, index, 24);
      const CampaignView view = campaign_view(cc, 48, 36);
      Case c;
      c.name = "campaign/" + std::to_string(seed) + "/" + std::to_string(index);
      c.soup = view.floor;
      append_soup(c.soup, view.soup);
      c.lights = {view.light};
      c.camera = view.camera;
      c.options = diff_options(c.camera);
      if (index % 5 == 1) c.options.footprints = false;
      if (index % 5 == 2) c.options.window = PixelWindow{7, 5, 20, 13};
      if (index % 5 == 3) c.options.depth_band = nullptr;
      cases.push_back(std::move(c));
    }
  for (std::uint64_t index = 0; index < 12; ++index) {
    const HardSceneCase hard = hard_scene_case(3, index, 128, 96);
    Case c{"hard_scene/3/" + std::to_string(index), merged_soup(hard.scene), hard.scene.lights, hard.scene.camera,
           diff_options(hard.scene.camera)};
    if (index % 4 == 1) c.options.footprints = false;
    if (index % 4 == 2) c.options.window = PixelWindow{30, 20, 41, 33};
    cases.push_back(std::move(c));
  }
  return cases;
}

std::vector<Case> shared_cases() {
  std::vector<Case> cases;
  for (std::string_view relative : {"soups/ogre.obj", "closed_manifold/nefertiti.obj", "closed_defective/horse.ply"}) {
    const std::filesystem::path file = test::mesh_file(relative);
    if (!std::filesystem::exists(file)) return {};
    cases.push_back(mesh_case(std::string(relative), read_soup(file), 256, 192));
  }
  return cases;
}

std::filesystem::path digest_file(const std::string& set) {
  return std::filesystem::path(SHADOWCERT_TEST_DATA) / ("exact_image_digests_" + set + ".txt");
}

std::map<std::string, std::string> read_digests(const std::filesystem::path& file) {
  std::map<std::string, std::string> out;
  std::ifstream in(file);
  std::string name, hex;
  while (in >> name >> hex) out[name] = hex;
  return out;
}

void check(const std::string& set, const std::vector<Case>& cases) {
  const bool write = std::getenv("SHADOWCERT_WRITE_EXACT_IMAGE_DIGESTS") != nullptr;
  std::map<std::string, std::string> computed;
  for (const Case& c : cases) computed[c.name] = digest(exact_image(c.soup, c.lights, c.camera, c.options));
  if (write) {
    std::ofstream out(digest_file(set));
    for (const auto& [name, hex] : computed) out << name << ' ' << hex << '\n';
    GTEST_SKIP() << "wrote " << digest_file(set);
  }
  const std::map<std::string, std::string> expected = read_digests(digest_file(set));
  ASSERT_EQ(expected.size(), computed.size()) << digest_file(set);
  for (const auto& [name, hex] : computed) {
    const auto it = expected.find(name);
    ASSERT_NE(it, expected.end()) << name << " has no digest in " << digest_file(set);
    EXPECT_EQ(it->second, hex) << name << ": the exact image changed";
  }
}

TEST(ExactImageDigest, ScenesMeshesAndSoups_AnswersUnchanged) { check("small", small_cases()); }

TEST(ExactImageDigest, SharedMeshes_AnswersUnchanged) {
  const std::vector<Case> cases = shared_cases();
  if (cases.empty()) {
    if (test::shared_data_required()) FAIL() << "the shared meshes are missing";
    GTEST_SKIP() << "the shared meshes (ogre, nefertiti, horse) are not in " << test::shared_mesh_dir();
  }
  check("shared", cases);
}

}  // namespace
