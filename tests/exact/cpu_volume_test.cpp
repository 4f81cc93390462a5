// exact/cpu_volume.h: the volume `render --method cpu` draws is the exact chain of the input
// rounded to float (as the GPU receives it), as float homogeneous triangles: closed as drawn;
// the double chain's triangles when rounding changes no sign; and on the light one double ulp
// off the floor's plane (docs/definitions.md#hard-cases), where the light lies in that plane once rounded, the
// floor casts nothing.
#include "exact/volume_closure.h"
#include "exact/cpu_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/certificate_test_support.h"
#include "core/scene.h"
#include "io/volume_file.h"
#include "exact/chain_mesh.h"
#include "reference/input_rounding.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_file.h"

namespace {

using namespace shadowcert;
using namespace shadowcert::test_support;

// The double input's exact chain as chain_mesh converts it: the volume cpu drew before
// exact/cpu_volume.h, the comparison for the cases where rounding changes no sign.
HomogeneousMesh double_chain_mesh(const Soup& canonical, const EdgeTable& table, const Light& light) {
  return chain_mesh(assemble_chain(canonical, table, exact_multiplicities(canonical, table, light), light), canonical,
                    light);
}

void expect_closed_as_drawn(const HomogeneousMesh& mesh) {
  const VolumeClosure closure = certify_volume_closure(mesh);
  EXPECT_TRUE(closure.certificate.closed)
      << closure.certificate.unbalanced.size() << " unbalanced edges of " << mesh.triangles.size() << " triangles";
}

// Coordinates that are not floats (0.1, 1.3, ...), so rounding moves every vertex and the light.
const Light kPointLight = point_light(0.3, 4.1, 5.7);
const Light kDirectionalLight = directional_light(0.35, 1.1, 0.7);

TEST(CpuVolume, RandomSoupsPointAndDirectional_ClosedAsDrawn) {
  constexpr std::uint64_t kSeed = 20240611;
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 seeds(kSeed);
  for (int run = 0; run < 20; ++run) {
    const std::uint64_t seed = seeds();
    SCOPED_TRACE("seed " + std::to_string(seed));
    const CanonicalSoup canonical = canonical_soup(random_soup(seed, 40, 1.7));
    const EdgeTable table = build_edge_table(canonical.soup);
    std::uniform_real_distribution<double> coordinate(-3.1, 3.1);
    std::mt19937_64 rng(seed);
    const Light point = point_light(coordinate(rng), 2.3 + coordinate(rng), coordinate(rng));
    for (const Light& light : {point, kDirectionalLight}) {
      const HomogeneousMesh mesh = cpu_volume_mesh(canonical.soup, table, light);
      EXPECT_FALSE(mesh.triangles.empty());
      expect_closed_as_drawn(mesh);
    }
  }
}

TEST(CpuVolume, FloatInputs_EqualTheDoubleChain) {
  // Dyadic coordinates are floats: rounding is the identity, so is the reference.
  const CanonicalSoup canonical = canonical_soup(box({-0.5, 1.5, -0.5}, {0.5, 2.5, 0.5}));
  const EdgeTable table = build_edge_table(canonical.soup);
  for (const Light& light : {point_light(0.25, 3.0, 3.0), directional_light(0.25, 1.0, 0.5)}) {
    const HomogeneousMesh mesh = cpu_volume_mesh(canonical.soup, table, light);
    const HomogeneousMesh reference = double_chain_mesh(canonical.soup, table, light);
    EXPECT_FALSE(mesh.triangles.empty());
    EXPECT_EQ(mesh.vertices, reference.vertices);
    EXPECT_EQ(mesh.triangles, reference.triangles);
  }
}

TEST(CpuVolume, RoundingChangesNoSign_SameTrianglesAndFiniteVerticesAsTheDoubleChain) {
  const CanonicalSoup canonical = canonical_soup(torus({0.1, 1.3, -0.7}, 1.3, 0.35, 17, 11));
  const EdgeTable table = build_edge_table(canonical.soup);
  const std::size_t n = canonical.soup.vertices.size();
  for (const Light& light : {kPointLight, kDirectionalLight}) {
    // The precondition: every exact sign is the same on both inputs.
    const EdgeMultiplicities exact = exact_multiplicities(canonical.soup, table, light);
    const EdgeMultiplicities rounded = exact_multiplicities(float_rounded(canonical.soup), table, float_rounded(light));
    ASSERT_EQ(exact.multiplicity, rounded.multiplicity);
    ASSERT_EQ(exact.triangle_sign, rounded.triangle_sign);
    const HomogeneousMesh mesh = cpu_volume_mesh(canonical.soup, table, light);
    const HomogeneousMesh reference = double_chain_mesh(canonical.soup, table, light);
    EXPECT_FALSE(mesh.triangles.empty());
    EXPECT_EQ(mesh.triangles, reference.triangles);
    ASSERT_EQ(mesh.vertices.size(), reference.vertices.size());
    // Finite vertices are the same floats; far vertices x - l are formed from the rounded x and
    // l (as a GPU forms them) and may differ from the double difference's float by rounding.
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(mesh.vertices[i], reference.vertices[i]) << "vertex " << i;
    for (std::size_t i = n; i < mesh.vertices.size(); ++i) EXPECT_EQ(mesh.vertices[i][3], 0.0f) << "vertex " << i;
    expect_closed_as_drawn(mesh);
  }
}

Scene one_ulp_off_floor_scene() {
  return load_scene(std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data/scenes/hard/light_one_ulp_off_floor_plane.json",
                    [](const std::filesystem::path& file) -> Soup {
                      throw std::runtime_error("the scene should need no mesh file: " + file.string());
                    });
}

// Vertex-id sets of a mesh's triangles, far ids (point light: n + i) mapped to their finite i,
// so a back cap or a side quad half names the soup vertices it comes from.
std::set<std::set<std::uint32_t>> finite_id_sets(const HomogeneousMesh& mesh, std::size_t n) {
  std::set<std::set<std::uint32_t>> sets;
  for (const auto& t : mesh.triangles) {
    std::set<std::uint32_t> ids;
    for (std::uint32_t id : t) ids.insert(id >= n ? static_cast<std::uint32_t>(id - n) : id);
    sets.insert(ids);
  }
  return sets;
}

TEST(CpuVolume, LightOneUlpOffTheFloorPlane_TheFloorCastsNothing) {
  const Scene scene = one_ulp_off_floor_scene();
  ASSERT_EQ(scene.lights.size(), 2u);
  ASSERT_FALSE(scene.meshes.empty());
  for (const Vec3& v : scene.meshes.front().soup.vertices) ASSERT_EQ(v[1], 1.0) << "the first mesh is the floor";
  const CanonicalSoup canonical = canonical_soup(merged_soup(scene));
  const EdgeTable table = build_edge_table(canonical.soup);
  const std::size_t n = canonical.soup.vertices.size();
  // The same scene without its floor: what the volume must be when the floor casts nothing.
  Scene floorless = scene;
  floorless.meshes.erase(floorless.meshes.begin());
  const CanonicalSoup floorless_canonical = canonical_soup(merged_soup(floorless));
  const EdgeTable floorless_table = build_edge_table(floorless_canonical.soup);

  std::vector<std::uint32_t> floor_triangles;  // canonical triangles with every vertex at y = 1
  for (std::uint32_t t = 0; t < canonical.soup.triangles.size(); ++t) {
    const Triangle& tri = canonical.soup.triangles[t];
    if (std::all_of(tri.begin(), tri.end(), [&](std::uint32_t v) { return canonical.soup.vertices[v][1] == 1.0; }))
      floor_triangles.push_back(t);
  }
  ASSERT_FALSE(floor_triangles.empty());

  for (const Light& light : scene.lights) {
    SCOPED_TRACE("light y = " + std::to_string(light.position[1]));
    // The premise: exactly, the floor faces the light (the double chain has its caps) ...
    const EdgeMultiplicities exact = exact_multiplicities(canonical.soup, table, light);
    for (std::uint32_t t : floor_triangles) ASSERT_NE(exact.triangle_sign[t], Sign::zero) << "triangle " << t;
    const std::set<std::set<std::uint32_t>> double_ids = finite_id_sets(double_chain_mesh(canonical.soup, table, light), n);
    // ... but cpu's volume has no cap of the floor, and is the floorless scene's volume.
    const HomogeneousMesh mesh = cpu_volume_mesh(canonical.soup, table, light);
    const std::set<std::set<std::uint32_t>> ids = finite_id_sets(mesh, n);
    for (std::uint32_t t : floor_triangles) {
      const Triangle& tri = canonical.soup.triangles[t];
      const std::set<std::uint32_t> cap(tri.begin(), tri.end());
      EXPECT_EQ(double_ids.count(cap), 1u) << "the double chain should cap floor triangle " << t;
      EXPECT_EQ(ids.count(cap), 0u) << "floor triangle " << t << " casts";
    }
    const HomogeneousMesh floorless_mesh = cpu_volume_mesh(floorless_canonical.soup, floorless_table, light);
    EXPECT_FALSE(floorless_mesh.triangles.empty());
    EXPECT_EQ(mesh.triangles.size(), floorless_mesh.triangles.size());
    expect_closed_as_drawn(mesh);
  }
}

TEST(CpuVolume, BadLight_Throws) {
  const CanonicalSoup canonical = canonical_soup(box({0, 0, 0}, {1, 1, 1}));
  const EdgeTable table = build_edge_table(canonical.soup);
  EXPECT_THROW((void)cpu_volume_mesh(canonical.soup, table, Light{{0, 0, 0, 0}}), std::invalid_argument);
  EXPECT_THROW((void)cpu_volume_mesh(canonical.soup, table, Light{{0, 1, 0, 0.5}}), std::invalid_argument);
}

}  // namespace
