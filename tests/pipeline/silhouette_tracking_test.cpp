// pipeline/silhouette_tracking.h: silhouette tracking held to the exact silhouette (edges with
// exact m != 0). full and continue miss no exact silhouette edge on any frame of concave
// meshes' orbits, one-way misses some on the bifurcation case, periodic:T lets no edge stay
// missing T frames, and a soup is not tracked, with its reason, its silhouette the exact full
// search's.
#include "pipeline/silhouette_tracking.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "core/box.h"
#include "io/scene_input.h"
#include "io/soup_file.h"
#include "scene/light_orbit.h"
#include "scene/procedural_mesh.h"
#include "support/mesh_data.h"

namespace {

using namespace shadowcert;

const TrackingVariant kFull{TrackingSearch::full, 0};
const TrackingVariant kOneWay{TrackingSearch::one_way, 0};
const TrackingVariant kContinue{TrackingSearch::continue_search, 0};

std::vector<Light> orbit(const Vec3& center, double radius, double height, std::size_t frames) {
  return orbit_lights(LightOrbit{center, radius, height, 1.0}, frames);
}

std::vector<TrackingMesh> one(std::string name, const Soup& soup) {
  std::vector<TrackingMesh> meshes;
  meshes.push_back(tracking_mesh(std::move(name), soup));
  return meshes;
}

TEST(TrackingMesh, Qualifying_EveryTableEdgeIsOneGraphEdgeWithTheSameEnds) {
  const TrackingMesh m = tracking_mesh("knot", torus_knot({0.5, 0, -1}, 2, 3, 1.0, 0.4, 0.12, 64, 8));
  ASSERT_TRUE(m.tracked()) << m.qualification;
  EXPECT_EQ(m.qualification, "qualifies");
  ASSERT_EQ(m.graph_edge.size(), m.table.size());
  std::set<std::uint32_t> distinct(m.graph_edge.begin(), m.graph_edge.end());
  EXPECT_EQ(distinct.size(), m.graph->edge_count());
  for (std::size_t e = 0; e < m.table.size(); ++e) {
    const auto& ends = m.graph->edge_vertices[m.graph_edge[e]];
    const std::set<Vec3> graph_ends{m.graph->vertices[ends[0]], m.graph->vertices[ends[1]]};
    const std::set<Vec3> table_ends{m.canonical.vertices[m.table.edges[e][0]], m.canonical.vertices[m.table.edges[e][1]]};
    EXPECT_EQ(graph_ends, table_ends) << "edge " << e;
  }
}

TEST(TrackingMesh, Soup_IsNotTrackedAndSaysWhy) {
  const TrackingMesh m = tracking_mesh("fan", nonmanifold_fan(5));
  EXPECT_FALSE(m.tracked());
  EXPECT_NE(m.qualification.find("non-manifold edge"), std::string::npos) << m.qualification;
  EXPECT_GT(m.table.size(), 0u);
}

// The test: full and continue find every exact silhouette edge on every frame of a
// concave mesh's orbit (and list nothing else).
TEST(CompareTracking, FullAndContinue_MissNoExactSilhouetteEdgeOnConcaveOrbits) {
  for (const auto& [name, soup] : {std::pair<std::string, Soup>{"torus", torus({0, 1, 0}, 1.0, 0.25, 48, 24)},
                                   {"knot", torus_knot({0, 0, 0}, 2, 3, 1.0, 0.4, 0.12, 128, 12)}}) {
    const std::vector<TrackingMesh> meshes = one(name, soup);
    const Box box = used_vertex_box(soup);
    for (const double height : {0.0, 0.7}) {
      LightOrbit path = default_light_orbit(box);
      path.height = height;
      const std::vector<Light> lights = orbit_lights(path, 120);
      const TrackingComparison c = compare_tracking(meshes, lights, std::vector{kFull, kContinue});
      ASSERT_EQ(c.variants.size(), 2u);
      ASSERT_EQ(c.exact.size(), lights.size());
      for (const VariantTracking& v : c.variants)
        for (std::size_t i = 0; i < v.frames.size(); ++i) {
          const TrackingFrameRecord& f = v.frames[i];
          EXPECT_EQ(f.missed, 0u) << name << " " << tracking_variant_name(v.variant) << " frame " << i;
          EXPECT_EQ(f.false_positives, 0u) << name << " " << tracking_variant_name(v.variant) << " frame " << i;
          EXPECT_EQ(f.found, f.exact);
          EXPECT_EQ(f.exact, c.exact[i].tracked_edges);
          EXPECT_GT(f.exact, 0u);
        }
      EXPECT_LT(c.variants[1].summary().mean_edges_checked, c.variants[0].summary().mean_edges_checked) << name;
    }
  }
}

// The bifurcation case of tests/contour/silhouette_tracker_test.cpp, against the exact silhouette.
TEST(CompareTracking, OneWay_MissesOnTheBifurcationCase_ContinueDoesNot) {
  const std::vector<TrackingMesh> meshes = one("torus 8x8", torus({0, 0, 0}, 1.0, 0.3, 8, 8));
  const TrackingComparison c =
      compare_tracking(meshes, orbit({0, 0, 0}, 3.0, 0.0, 36), std::vector{kOneWay, kContinue});
  const TrackingFrameRecord& one_way = c.variants[0].frames[1];
  EXPECT_EQ(one_way.missed, 2u);
  EXPECT_EQ(one_way.oldest_miss, 1u);
  EXPECT_EQ(one_way.false_positives, 0u);
  EXPECT_GT(one_way.miss_rate(), 0.0);
  EXPECT_GT(c.variants[0].summary().mean_miss_rate, 0.0);
  EXPECT_EQ(c.variants[1].summary().missed, 0u);
  EXPECT_EQ(c.variants[1].summary().max_miss_rate, 0.0);
}

// The test: periodic:T bounds the misses' age by T (a knot whose tube the light
// grazes, where one-way leaves edges missing for several frames).
TEST(CompareTracking, Periodic_OldestMissBelowItsPeriod) {
  const std::vector<TrackingMesh> meshes = one("knot 64x8", torus_knot({0, 0, 0}, 2, 3, 1.0, 0.4, 0.12, 64, 8));
  const std::vector<TrackingVariant> variants{kFull, kOneWay, {TrackingSearch::periodic, 2}, {TrackingSearch::periodic, 3},
                                              {TrackingSearch::periodic, 5}};
  const TrackingComparison c = compare_tracking(meshes, orbit({0, 0, 0}, 1.5, 0.0, 180), variants);
  EXPECT_EQ(c.variants[0].summary().missed, 0u);
  EXPECT_GE(c.variants[1].summary().oldest_miss, 5u);
  for (std::size_t v = 2; v < variants.size(); ++v) {
    const TrackingSummary s = c.variants[v].summary();
    EXPECT_LT(s.oldest_miss, variants[v].period) << tracking_variant_name(variants[v]);
    EXPECT_GT(s.missed, 0u) << tracking_variant_name(variants[v]);
    for (std::size_t i = 0; i < c.variants[v].frames.size(); i += variants[v].period)
      EXPECT_EQ(c.variants[v].frames[i].missed, 0u) << "a full frame";
  }
}

// Border edges are silhouette edges whenever their face is not edge-on (m = -s(t)).
TEST(CompareTracking, OpenMesh_BorderEdgesAreOnTheList) {
  const std::vector<TrackingMesh> meshes = one("floor", floor_quad(1.0));
  ASSERT_TRUE(meshes[0].tracked());
  const TrackingComparison c =
      compare_tracking(meshes, orbit({0, 0, 0}, 2.0, 1.0, 12), std::vector{kFull, kOneWay, kContinue});
  for (const VariantTracking& v : c.variants)
    for (const TrackingFrameRecord& f : v.frames) {
      EXPECT_EQ(f.exact, 4u);
      EXPECT_EQ(f.found, 4u);
      EXPECT_EQ(f.missed, 0u);
    }
}

// A soup is searched by the exact full search alone: no tracker, its silhouette edges counted.
TEST(CompareTracking, Soup_ExactFullSearchOnly) {
  std::vector<TrackingMesh> meshes = one("fan", nonmanifold_fan(6));
  meshes.push_back(tracking_mesh("box", box({2, 0, 0}, {3, 1, 1})));
  const TrackingComparison c = compare_tracking(meshes, orbit({1, 0.5, 0.5}, 5.0, 2.0, 10), std::vector{kOneWay});
  for (std::size_t i = 0; i < c.exact.size(); ++i) {
    EXPECT_GT(c.exact[i].fallback_edges, 0u);
    EXPECT_EQ(c.variants[0].frames[i].exact, c.exact[i].tracked_edges);
    EXPECT_EQ(c.variants[0].frames[i].missed, 0u);
  }
}

// A grid on the tilted plane z = x + 2y, its vertices rounded off the plane (step 0.1), lit from
// within the plane: every face is within rounding of edge-on, so the float side often disagrees
// with the exact one. The full search then lists edges the exact silhouette does not have (false
// positives) and misses some it has: both counted, apart.
TEST(CompareTracking, GrazingGrid_FloatDisagreementsCountedAsFalsePositivesAndMisses) {
  Soup s;
  constexpr std::uint32_t kW = 40, kH = 20;
  for (std::uint32_t i = 0; i <= kW; ++i)
    for (std::uint32_t j = 0; j <= kH; ++j) {
      const double x = i * 0.1, y = j * 0.1;
      s.vertices.push_back({x, y, x + 2 * y});
    }
  const auto id = [](std::uint32_t i, std::uint32_t j) { return i * (kH + 1) + j; };
  for (std::uint32_t i = 0; i < kW; ++i)
    for (std::uint32_t j = 0; j < kH; ++j) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const std::vector<TrackingMesh> meshes = one("grazing grid", s);
  ASSERT_TRUE(meshes[0].tracked());
  const double x = -30 * 0.1, y = 70 * 0.1;
  const TrackingComparison c = compare_tracking(meshes, std::vector{Light{{x, y, x + 2 * y, 1.0}}}, std::vector{kFull});
  const TrackingFrameRecord& f = c.variants[0].frames[0];
  EXPECT_GT(f.false_positives, 0u);
  EXPECT_GT(f.missed, 0u);
  EXPECT_EQ(f.found - f.false_positives, f.exact - f.missed);  // the edges both have
}

TEST(CompareTracking, Misuse_Throws) {
  const std::vector<TrackingMesh> meshes = one("box", box({0, 0, 0}, {1, 1, 1}));
  EXPECT_THROW((void)compare_tracking(meshes, std::vector{Light{{0, 0, 0, 0}}}, std::vector{kFull}), std::invalid_argument);
  EXPECT_THROW((void)compare_tracking(meshes, std::vector{Light{{3, 3, 3, 1}}}, std::vector{TrackingVariant{TrackingSearch::periodic, 0}}),
               std::invalid_argument);
  EXPECT_THROW((void)tracking_mesh("bad", Soup{{{0, 0, 0}}, {{0, 1, 2}}, {}}), std::invalid_argument);
}

// data/scenes/tracking/: the meshes of docs/smoothies.md's tracking tables load and qualify.
TEST(TrackingMesh, BundledTrackingScenes_LoadAndQualify) {
  std::size_t scenes = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "scenes" / "tracking")) {
    if (entry.path().extension() != ".json") continue;
    ++scenes;
    const Scene scene = load_scene_or_mesh(entry.path());
    ASSERT_EQ(scene.meshes.size(), 1u) << entry.path();
    const TrackingMesh m = tracking_mesh(scene.meshes[0].name, scene.meshes[0].soup);
    EXPECT_TRUE(m.tracked()) << entry.path() << ": " << m.qualification;
  }
  EXPECT_EQ(scenes, 4u);
}

// Real closed meshes (data/meshes/): continue and full miss nothing along the default orbit.
TEST(CompareTracking, BundledMeshes_ContinueAndFullMissNothing) {
  for (const char* mesh : {"closed_manifold/spot.obj", "closed_manifold/thingi10k_65004.stl"}) {
    SHADOWCERT_REQUIRE_MESH(mesh);
    const Soup soup = read_soup(test::mesh_file(mesh));
    const std::vector<TrackingMesh> meshes = one(mesh, soup);
    ASSERT_TRUE(meshes[0].tracked()) << meshes[0].qualification;
    const std::vector<Light> lights = orbit_lights(default_light_orbit(used_vertex_box(soup)), 90);
    const TrackingComparison c = compare_tracking(meshes, lights, std::vector{kFull, kContinue});
    for (const VariantTracking& v : c.variants) {
      EXPECT_EQ(v.summary().missed, 0u) << mesh << " " << tracking_variant_name(v.variant);
      EXPECT_EQ(v.summary().false_positives, 0u) << mesh << " " << tracking_variant_name(v.variant);
    }
  }
}

}  // namespace
